// SPDX-License-Identifier: MIT
// The 3D lane's ragdoll pile (ragdoll_pile3d.h). Jointed figures in a heap
// are where an iterative solver lets joints open and limbs jitter instead
// of sleeping. Criterion (the ragdoll spec): within the 8 s it has to
// settle, no joint opens by more than 2 cm. The spec's other criterion,
// every part asleep by then, is not met yet (heads hanging off the heap
// keep swinging along their neck's cone limit at up to 0.6 m/s); it is
// measured and printed here, and held in the unbuilt
// stability3d_known_failures.cpp, which also runs the heap on to 30 s.
#include "ragdoll_pile3d.h"

namespace rwd::sim {
namespace {

TEST(Stability3D, RagdollPileKeepsItsJointsClosed) {
  const pile::PileResult r = pile::run_pile(8 * pile::kTicksPerSecond);
  EXPECT_LE(r.worst_gap, 0.02);
}

// The same criterion with one ragdoll nudged by 10 to 610 um before the
// drop. The heap is chaotic: these nudges once turned the 1.7 cm worst
// opening above into 6, 11 and 17 cm (held limits released along their
// own rows only), a pass that held by luck.
TEST(Stability3D, RagdollPileKeepsItsJointsClosedWhenNudged) {
  const pile::PileNudge nudges[] = {{28, {1e-5f, 0.0f, 0.0f}},
                                    {7, {0.0f, 0.0f, 3.1e-4f}},
                                    {42, {6.1e-4f, 0.0f, 0.0f}}};
  for (const pile::PileNudge& n : nudges) {
    const pile::PileResult r = pile::run_pile(8 * pile::kTicksPerSecond, n);
    EXPECT_LE(r.worst_gap, 0.02) << "ragdoll " << n.ragdoll << " nudged";
  }
}

}  // namespace
}  // namespace rwd::sim
