// SPDX-License-Identifier: MIT
#pragma once
// The 3D lane's joint scene for det_checksums: every joint type (limits,
// motors, springs, a grab, a soft weld), a tree of joints solved as one
// system (a chain and a branching figure), a loop solved row by row, a
// sheet of bare ball joints solved in lane batches, a joint that breaks, a raycast-wheel car driven each tick and a character
// moved by shape casts, with the world restored from a snapshot and
// reloaded from its own bytes on the way, so the matrix holds the joint
// solver, the vehicle and the character controller to the same bits on
// every build.
namespace rwd::determinism {

/// Prints "joints3d <tick> <checksum>" for `ticks` ticks; false after
/// printing a ROLLBACK-MISMATCH or RELOAD-MISMATCH line.
bool run_joints3d_scene(int ticks);

}  // namespace rwd::determinism
