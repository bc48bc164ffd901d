// SPDX-License-Identifier: MIT
// 3D lane scenes that FAIL their criterion at default settings today. This
// file is deliberately not in any CMake target, so the suite stays green
// while the solver changes; add it to stability3d_tests (in place of
// stability3d_ragdolls.cpp, whose scene it repeats) to check a fix. The
// criteria are the ragdoll spec's, unchanged. Measured at the time of
// writing (default settings, 4 substeps):
//
// - The pile of fifty ragdolls should be asleep within 8 s: all 550 parts
//   are still awake at 8 s, the fastest at 0.49 m/s and 3.5 rad/s (heads
//   and forearms of ragdolls lying on others turning against their joint
//   limits and their neighbours), and not all asleep after 30 s. A single
//   ragdoll dropped alone sleeps in 3 to 4 s (test_ragdoll3d.cpp); the
//   pile's joints hold while it settles (worst opening 1.8 cm in its first
//   8 s, criterion 2 cm: the built test), but the jitter that keeps it
//   awake later opens an elbow squeezed in the heap by 7.4 cm (at 14.7 s).
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
