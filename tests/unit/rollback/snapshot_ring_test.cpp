// SPDX-License-Identifier: MIT
#include "rewind/net/snapshot_ring.h"

#include <gtest/gtest.h>

#include <vector>

namespace rwd::net {
namespace {

TEST(SnapshotRing, HoldsTheLastCapacityTicks) {
  auto sim = game::Simulation::create("crates", {2, 3});
  ASSERT_TRUE(sim.ok());
  SnapshotRing ring(4);
  std::vector<rwd::PlayerInput> inputs(2);
  std::vector<uint64_t> checksums;
  for (int i = 0; i < 6; ++i) {
    ring.save(**sim);
    checksums.push_back((*sim)->checksum());
    EXPECT_TRUE((*sim)->step(inputs).ok());
  }
  EXPECT_EQ(ring.find(0), nullptr);
  EXPECT_EQ(ring.find(1), nullptr);
  for (Tick t = 2; t < 6; ++t) {
    const game::SimSnapshot* snapshot = ring.find(t);
    ASSERT_NE(snapshot, nullptr) << t;
    EXPECT_EQ(snapshot->tick, t);
    EXPECT_EQ((*sim)->checksum_of(*snapshot), checksums[static_cast<size_t>(t)]);
  }
  EXPECT_EQ(ring.find(6), nullptr);
  EXPECT_EQ(ring.find(-1), nullptr);
  ring.clear();
  EXPECT_EQ(ring.find(5), nullptr);
}

}  // namespace
}  // namespace rwd::net
