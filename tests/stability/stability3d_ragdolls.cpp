// SPDX-License-Identifier: MIT
// The 3D lane's ragdoll pile (ragdoll_pile3d.h). Jointed figures in a heap
// are where an iterative solver lets joints open and limbs jitter instead
// of sleeping. Criteria (the ragdoll spec): within 8 s no joint opens by
// more than 2 cm and every part is asleep. What lets the heap sleep: the
// ragdolls' joint friction (RagdollSpec3D::joint_friction; without it
// heads hanging off the heap swing along their neck's cone limit for tens
// of seconds) and a sleep test by displacement (WorldConfig's
// sleep_threshold_mps: a limb trembling in place on a contact rests).
#include "ragdoll_pile3d.h"

namespace rwd::sim {
namespace {

TEST(Stability3D, RagdollPileKeepsItsJointsClosedAndSleeps) {
  const pile::PileResult r = pile::run_pile(8 * pile::kTicksPerSecond);
  EXPECT_LE(r.worst_gap, 0.02);
  EXPECT_GT(r.asleep_at, 0) << "not all asleep within 8 s";
}

// The same criterion with one ragdoll nudged by 10 to 610 um before the
// drop. The heap is chaotic: these nudges once turned the 1.7 cm worst
// opening above into 6, 11 and 17 cm (held limits released along their
// own rows only), a pass that held by luck.
TEST(Stability3D, RagdollPileKeepsItsJointsClosedAndSleepsWhenNudged) {
  const pile::PileNudge nudges[] = {
      {28, {1e-5f, 0.0f, 0.0f}}, {7, {0.0f, 0.0f, 3.1e-4f}}, {42, {6.1e-4f, 0.0f, 0.0f}}};
  for (const pile::PileNudge& n : nudges) {
    const pile::PileResult r = pile::run_pile(8 * pile::kTicksPerSecond, n);
    EXPECT_LE(r.worst_gap, 0.02) << "ragdoll " << n.ragdoll << " nudged";
    EXPECT_GT(r.asleep_at, 0) << "ragdoll " << n.ragdoll << " nudged: not all asleep within 8 s";
  }
}

}  // namespace
}  // namespace rwd::sim
