// SPDX-License-Identifier: MIT
// The 2D sample game runs on the fixed-point lane through the same seam as
// the 3D one: discs stay in the arena, shove crates, score goals, and a
// match rolls back and reloads bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "rewind/game/arena_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"

namespace rwd::game {
namespace {

using fixed::Fx;
using namespace fixed::literals;

std::unique_ptr<Simulation> make_match(uint32_t players) {
  auto sim = Simulation::create("arena", {players, 11});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  return std::move(*sim);
}

ArenaState state_of(const Simulation& sim) {
  ArenaState s;
  EXPECT_EQ(sim.game_state().size(), sizeof(s));
  std::memcpy(&s, sim.game_state().data(), sizeof(s));
  return s;
}

const sim2d::World2D& world(const Simulation& sim) {
  return *world_of<sim2d::World2D>(sim.lane());
}

// Scripted sticks: each player circles at its own rate, dashing now and then.
std::vector<StickInput> inputs_at(Tick t, uint32_t players) {
  std::vector<StickInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    const int32_t phase = (static_cast<int32_t>(t) * static_cast<int32_t>(p + 3) / 7) % 8;
    static constexpr int16_t kDir[8][2] = {{1000, 0},  {700, 700},   {0, 1000},  {-700, 700},
                                           {-1000, 0}, {-700, -700}, {0, -1000}, {700, -700}};
    inputs[p].axis_x = kDir[phase][0];
    inputs[p].axis_y = kDir[phase][1];
    inputs[p].buttons = (static_cast<uint32_t>(t) % 97 == p) ? kArenaDash : 0;
  }
  return inputs;
}

TEST(ArenaGame, DiscsStayInsideTheWallsAtFullSpeed) {
  // Everybody drives into the same corner, dashing whenever allowed.
  auto sim = make_match(8);
  std::vector<StickInput> inputs(8);
  for (Tick t = 0; t < 900; ++t) {
    for (uint32_t p = 0; p < 8; ++p) {
      inputs[p] = {};
      inputs[p].axis_x = kAxisMax;
      inputs[p].axis_y = (p % 2) ? kAxisMax : -kAxisMax;
      inputs[p].buttons = kArenaDash;
    }
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  }
  const ArenaState s = state_of(*sim);
  for (uint32_t p = 0; p < 8; ++p) {
    const fixed::Vec2 pos = world(*sim).position(s.discs[p]);
    // Inside the walls, or in a goal pocket (which reaches x = 14.5).
    EXPECT_LE(fixed::abs(pos.x), 14.5_fx) << "player " << p;
    if (fixed::abs(pos.x) > 12_fx) {
      EXPECT_LE(fixed::abs(pos.y), 2_fx) << "player " << p;
    }
    EXPECT_LE(fixed::abs(pos.y), 8_fx) << "player " << p;
  }
}

TEST(ArenaGame, ADiscShovesACrateIntoAGoalAndScores) {
  auto sim = make_match(2);
  ArenaState s = state_of(*sim);
  // Put player 0 behind crate 8 (home (-6, 2)) on the goal line y = 0 and
  // drive right: the crate goes into the right goal.
  sim2d::World2D& w = *world_of<sim2d::World2D>(sim->lane());
  ASSERT_TRUE(w.set_transform(s.crates[8], {8_fx, Fx()}, Fx()).ok());
  ASSERT_TRUE(w.set_transform(s.discs[0], {6_fx, Fx()}, Fx()).ok());
  std::vector<StickInput> inputs(2);
  inputs[0].axis_x = kAxisMax;
  for (Tick t = 0; t < 240 && state_of(*sim).goals_scored == 0; ++t)
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  s = state_of(*sim);
  EXPECT_EQ(s.goals_scored, 1u);
  EXPECT_EQ(s.score[0], 1u);
  EXPECT_EQ(s.score[1], 0u);
  // The crate went home.
  EXPECT_EQ(w.position(s.crates[8]), (fixed::Vec2{-6_fx, 2_fx}));
}

TEST(ArenaGame, RollbackAndReloadAreBitForBit) {
  auto sim = make_match(4);
  for (Tick t = 0; t < 200; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, 4))).ok());
  SimSnapshot saved;
  sim->save(saved);
  std::vector<uint64_t> expected;
  for (Tick t = 200; t < 400; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, 4))).ok());
    expected.push_back(sim->checksum());
  }
  sim->restore(saved);
  // A misprediction first, then the real inputs.
  for (Tick t = 200; t < 260; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t + 5, 4))).ok());
  sim->restore(saved);
  std::vector<uint8_t> bytes;
  sim->serialize(bytes);
  auto reloaded = make_match(4);
  ASSERT_TRUE(reloaded->deserialize(bytes).ok());
  for (Tick t = 200; t < 400; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, 4))).ok());
    EXPECT_TRUE(reloaded->step(stick_inputs(inputs_at(t, 4))).ok());
    ASSERT_EQ(sim->checksum(), expected[static_cast<size_t>(t - 200)]) << "tick " << t;
    ASSERT_EQ(reloaded->checksum(), expected[static_cast<size_t>(t - 200)]) << "tick " << t;
  }
  // The turnstile and the gate are on their hinges.
  EXPECT_EQ(world(*sim).joint_count(), 2u);
  // The crates moved: the match is not a still life.
  const ArenaState s = state_of(*sim);
  int moved = 0;
  for (uint32_t c = 0; c < s.crate_count; ++c) {
    const fixed::Vec2 p = world(*sim).position(s.crates[c]);
    moved += p.y != Fx() ? 1 : 0;
  }
  EXPECT_GT(moved, 0);
}

TEST(ArenaGame, ASimulationRefusesALaneOfAnotherType) {
  // The 3D game handed a 2D world: refused before any of its calls run.
  auto crates = make_builtin_game("crates");
  auto arena = make_builtin_game("arena");
  ASSERT_NE(crates, nullptr);
  ASSERT_NE(arena, nullptr);
  EXPECT_TRUE(arena->accepts_lane(*arena->make_lane()));
  EXPECT_FALSE(crates->accepts_lane(*arena->make_lane()));
  auto refused = Simulation::create(std::move(crates), MatchSetup{}, arena->make_lane());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.status().message().find("does not run on the lane given"), std::string::npos);
}

}  // namespace
}  // namespace rwd::game
