// SPDX-License-Identifier: MIT
// 3D lane scenes that FAIL their criterion at default settings today. This
// file is deliberately not in any CMake target, so the suite stays green
// while the solver changes; add it to stability3d_tests (in place of
// stability3d_ragdolls.cpp, whose scene it repeats) to check a fix. The
// criteria are the ragdoll spec's, unchanged. Measured at the time of
// writing (default settings, 4 substeps):
//
// - The pile of fifty ragdolls should be asleep within 8 s: all 550 parts
//   are still awake at 8 s, the fastest at 0.24 m/s and 2.1 rad/s, and not
//   all asleep after 30 s. What keeps the heap awake is mostly a few
//   heads that hang off it, touching nothing but held by the neck: each
//   swings along the rim of its neck's cone limit (swing at the 40 degree
//   cone, the twist drifting between its limits) at up to 0.6 m/s for
//   tens of seconds. Nothing seen pumps it (not the projection, not a
//   contact): a ragdoll lying on a table with its head over the edge,
//   the head set swinging the same way, swings on for over 10 s too, and
//   stops within 5 s with ten times the angular damping. The parts' angular
//   damping acts about each part's own centre, so it barely slows a head
//   swinging about the neck (a fifth of it reaches that motion), and the
//   joints have no friction. (With angular damping 2 or 5 1/s the heap
//   slept after 9.5 to 18.5 s in three runs of four, and not within 20 s
//   in the fourth: not within 8 s either.) A single ragdoll
//   dropped alone sleeps in 3 to 4 s (test_ragdoll3d.cpp). The
//   pile's joints hold (worst opening 2.3 mm in 8 s and in 30 s; at most
//   7 mm with one ragdoll nudged by 10 um to 1 mm; criterion 2 cm: the
//   built tests).
#include "ragdoll_pile3d.h"

namespace rwd::sim {
namespace {

TEST(Stability3DKnownFailure, RagdollPileSleepsWithinEightSeconds) {
  const pile::PileResult r = pile::run_pile(30 * pile::kTicksPerSecond);
  EXPECT_LE(r.worst_gap, 0.02);
  EXPECT_GT(r.asleep_at, 0);
  EXPECT_LE(r.asleep_at, 8 * pile::kTicksPerSecond);
}

}  // namespace
}  // namespace rwd::sim
