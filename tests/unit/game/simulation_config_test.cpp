// SPDX-License-Identifier: MIT
// Simulation::create with a world config of the caller's: the seam tools use
// to play a game at other solver settings.
#include <gtest/gtest.h>

#include <vector>

#include "rewind/game/crates_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"

namespace rwd::game {
namespace {

std::vector<PlayerInput> forward(uint32_t players) {
  std::vector<StickInput> inputs(players);
  for (StickInput& in : inputs) in.axis_y = kAxisMax;
  return stick_inputs(inputs);
}

TEST(SimulationConfig, TheGamesOwnConfigByDefault) {
  auto sim = Simulation::create("crates", {2, 1});
  ASSERT_TRUE(sim.ok()) << sim.status().message();
  EXPECT_EQ(world_of<sim::World3D>((**sim).lane())->config().substeps,
            CratesGame().world_config().substeps);
  EXPECT_EQ(world_of<sim::World3D>((**sim).lane())->config().relax_iterations,
            CratesGame().world_config().relax_iterations);
}

TEST(SimulationConfig, AnOverrideRunsTheSameGameOnThatWorld) {
  sim::WorldConfig fine = CratesGame().world_config();
  fine.substeps = 16;
  fine.relax_iterations = 4;
  auto tuned = Simulation::create("crates", {2, 1}, fine);
  auto usual = Simulation::create("crates", {2, 1});
  ASSERT_TRUE(tuned.ok()) << tuned.status().message();
  ASSERT_TRUE(usual.ok());
  EXPECT_EQ(world_of<sim::World3D>((**tuned).lane())->config().substeps, 16);
  EXPECT_EQ(world_of<sim::World3D>((**tuned).lane())->config().relax_iterations, 4);
  // The same bodies, built by the same rules.
  EXPECT_EQ(world_of<sim::World3D>((**tuned).lane())->body_count(),
            world_of<sim::World3D>((**usual).lane())->body_count());
  EXPECT_EQ((*tuned)->game_state().size(), (*usual)->game_state().size());
  // Another world: its checksum (which covers the config) differs from the
  // first tick on.
  const std::vector<PlayerInput> inputs = forward(2);
  EXPECT_TRUE((*tuned)->step(inputs).ok());
  EXPECT_TRUE((*usual)->step(inputs).ok());
  EXPECT_NE((*tuned)->checksum(), (*usual)->checksum());

  // The game's own config passed explicitly is the usual match, bit for bit.
  auto same = Simulation::create("crates", {2, 1}, CratesGame().world_config());
  ASSERT_TRUE(same.ok());
  EXPECT_TRUE((*same)->step(inputs).ok());
  EXPECT_EQ((*same)->checksum(), (*usual)->checksum());
}

TEST(SimulationConfig, InvalidConfigsAndSetupsAreRefused) {
  sim::WorldConfig bad = CratesGame().world_config();
  bad.substeps = 0;
  auto refused = Simulation::create("crates", {2, 1}, bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.status().message().find("substeps"), std::string::npos)
      << refused.status().message();

  auto unknown = Simulation::create("chess", {2, 1}, CratesGame().world_config());
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("unknown game 'chess'"), std::string::npos);
  auto nobody = Simulation::create("crates", {0, 1}, CratesGame().world_config());
  ASSERT_FALSE(nobody.ok());
  EXPECT_EQ(nobody.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::game
