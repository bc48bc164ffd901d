// SPDX-License-Identifier: MIT
#pragma once
// The 2D lane's engine scene for det_checksums: everything the step can
// do (boxes, circles, capsules, rounded polygons on a chain floor, every
// joint type, a sensor, sleeping and waking, continuous bullets), every
// query (their results digested), a character moved each tick, and the
// world reloaded from its own bytes and restored from snapshots on the
// way, so the matrix holds all of it to the same bits on every build.
namespace rwd::determinism {

/// Prints "lane2d <tick> <checksum> <query digest>" for `ticks` ticks;
/// false after printing a ROLLBACK-MISMATCH or RELOAD-MISMATCH line.
bool run_lane2d_scene(int ticks);

}  // namespace rwd::determinism
