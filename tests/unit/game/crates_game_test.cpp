// SPDX-License-Identifier: MIT
// The sample game keeps every player in play: a closed arena, and a kill
// plane plus the world bounds behind it that respawn whatever still escapes.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "rewind/game/crates_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"

namespace rwd::game {
namespace {

std::unique_ptr<Simulation> make_match(uint32_t players, uint64_t seed = 7) {
  auto sim = Simulation::create("crates", {players, seed});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  return std::move(*sim);
}

CratesState state_of(const Simulation& sim) {
  CratesState s;
  EXPECT_EQ(sim.game_state().size(), sizeof(s));
  std::memcpy(&s, sim.game_state().data(), sizeof(s));
  return s;
}

// Every pusher is in play: enabled, above the floor's underside, inside the
// arena's outer edge (a respawn puts it back at once).
void expect_all_in_play(const Simulation& sim, Tick tick) {
  const CratesState s = state_of(sim);
  for (uint32_t p = 0; p < s.player_count; ++p) {
    const sim::BodyId id = s.pushers[p];
    ASSERT_TRUE(world_of<sim::World3D>(sim.lane())->is_valid(id))
        << "player " << p << " tick " << tick;
    ASSERT_TRUE(world_of<sim::World3D>(sim.lane())->is_enabled(id))
        << "player " << p << " tick " << tick;
    const sim::Vec3 pos = world_of<sim::World3D>(sim.lane())->position(id);
    ASSERT_GT(pos.y, -10.0f) << "player " << p << " tick " << tick;
  }
}

TEST(CratesGame, CornersAreClosed) {
  // Everybody drives diagonally into the same corner at full speed, dashing
  // whenever the cooldown allows, without jumping: nobody may get out.
  auto sim = make_match(8);
  std::vector<StickInput> inputs(8);
  for (Tick t = 0; t < 1800; ++t) {
    for (uint32_t p = 0; p < 8; ++p) {
      inputs[p] = {};
      inputs[p].axis_x = kAxisMax;
      inputs[p].axis_y = (p % 2) ? kAxisMax : -kAxisMax;  // two corners
      inputs[p].buttons = kCratesDash;
    }
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    expect_all_in_play(*sim, t);
    if (HasFatalFailure()) return;
  }
  const CratesState s = state_of(*sim);
  for (uint32_t p = 0; p < 8; ++p) EXPECT_EQ(s.falls[p], 0u) << "player " << p;
}

TEST(CratesGame, EscapedPusherRespawnsAtItsSpawnPoint) {
  auto sim = make_match(4);
  const CratesState before = state_of(*sim);
  const sim::BodyId pusher = before.pushers[2];
  const sim::Vec3 spawn = world_of<sim::World3D>((*sim).lane())->position(pusher);
  // Put it outside the arena, beside the floor: it falls past the kill plane.
  ASSERT_TRUE(
      world_of<sim::World3D>((*sim).lane())->set_transform(pusher, {15.0f, 2.0f, 15.0f}, {}).ok());
  std::vector<StickInput> inputs(4);
  for (int t = 0; t < 240 && state_of(*sim).falls[2] == 0; ++t)
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  const CratesState after = state_of(*sim);
  EXPECT_EQ(after.falls[2], 1u);
  EXPECT_TRUE(world_of<sim::World3D>((*sim).lane())->is_enabled(pusher));
  EXPECT_NEAR(world_of<sim::World3D>((*sim).lane())->position(pusher).x, spawn.x, 0.2f);
  EXPECT_NEAR(world_of<sim::World3D>((*sim).lane())->position(pusher).z, spawn.z, 0.2f);
}

TEST(CratesGame, PusherFlungOutOfTheWorldComesBack) {
  auto sim = make_match(2);
  const sim::BodyId pusher = state_of(*sim).pushers[0];
  // Above the roof, then straight up at the API's speed limit: the engine
  // disables it on the world's upper bound, the game respawns it the same
  // tick.
  ASSERT_TRUE(
      world_of<sim::World3D>((*sim).lane())->set_transform(pusher, {0.0f, 20.0f, 0.0f}, {}).ok());
  ASSERT_TRUE(world_of<sim::World3D>((*sim).lane())
                  ->set_linear_velocity(pusher, {0.0f, 9999.0f, 0.0f})
                  .ok());
  std::vector<StickInput> inputs(2);
  for (int t = 0; t < 120 && state_of(*sim).falls[0] == 0; ++t)
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  EXPECT_EQ(state_of(*sim).falls[0], 1u);
  EXPECT_TRUE(world_of<sim::World3D>((*sim).lane())->is_enabled(pusher));
  EXPECT_LT(world_of<sim::World3D>((*sim).lane())->position(pusher).y, 2.0f);
}

TEST(CratesGame, AggressiveMatchStaysInPlayAndLoadable) {
  // Sixteen players: jumps, dashes, pile-ups in corners, changing every
  // couple of seconds; every state loads with its checksum.
  constexpr uint32_t kPlayers = 16;
  auto sim = make_match(kPlayers, 99);
  auto loaded = make_match(kPlayers, 99);
  std::vector<StickInput> inputs(kPlayers);
  std::vector<uint8_t> bytes;
  uint64_t rng = 12345;
  auto next = [&rng]() {
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(rng >> 33);
  };
  for (Tick t = 0; t < 12000; ++t) {
    if (t % 120 == 0) {
      const int16_t cx = (next() % 2) ? kAxisMax : -kAxisMax;
      const int16_t cz = (next() % 2) ? kAxisMax : -kAxisMax;
      for (uint32_t p = 0; p < kPlayers; ++p) {
        const bool follow = next() % 4 != 0;  // most players pile into one corner
        inputs[p].axis_x = follow ? cx : static_cast<int16_t>(next() % 2001) - 1000;
        inputs[p].axis_y = follow ? cz : static_cast<int16_t>(next() % 2001) - 1000;
      }
    }
    for (uint32_t p = 0; p < kPlayers; ++p) {
      inputs[p].buttons =
          (next() % 3 == 0 ? kCratesJump : 0u) | (next() % 5 == 0 ? kCratesDash : 0u);
    }
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    expect_all_in_play(*sim, t);
    if (HasFatalFailure()) return;
    if (t % 10 == 0) {
      sim->serialize(bytes);
      Status s = loaded->deserialize(bytes);
      ASSERT_TRUE(s.ok()) << "tick " << t << ": " << s.message();
      ASSERT_EQ(loaded->checksum(), sim->checksum()) << "tick " << t;
    }
  }
  const CratesState s = state_of(*sim);
  uint32_t falls = 0;
  for (uint32_t p = 0; p < kPlayers; ++p) falls += s.falls[p];
  std::printf("16 players, 12000 ticks: %u pusher respawns, %u crate respawns\n", falls,
              s.crate_respawns);
}

}  // namespace
}  // namespace rwd::game
