// SPDX-License-Identifier: MIT
// The 3D vehicle game: cars on raycast wheels over a height field, lances
// welded on, ragdoll riders held by breakable welds, a wrecking ball on a
// chain of ball joints. A match rolls back and reloads bit for bit, a lance strike
// throws a rider and scores, the ball keeps swinging on a chain that holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "rewind/core/det_math.h"
#include "rewind/game/joust_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"

namespace rwd::game {
namespace {

std::unique_ptr<Simulation> make_match(uint32_t players, uint64_t seed = 5) {
  auto sim = Simulation::create("joust", {players, seed});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  return std::move(*sim);
}

JoustState state_of(const Simulation& sim) {
  JoustState s;
  EXPECT_EQ(sim.game_state().size(), sizeof(s));
  std::memcpy(&s, sim.game_state().data(), sizeof(s));
  return s;
}

// Writes a changed state block back (tests that move cars by hand), the
// way a resync does: through a snapshot of the whole match.
void store(Simulation& sim, const JoustState& s) {
  SimSnapshot snapshot;
  sim.save(snapshot);
  ASSERT_EQ(snapshot.game_state.size(), sizeof(s));
  std::memcpy(snapshot.game_state.data(), &s, sizeof(s));
  sim.restore(snapshot);
}

sim::World3D& world(Simulation& sim) {
  return *world_of<sim::World3D>(sim.lane());
}

sim::Quat yaw(float angle) {
  return {0.0f, rwd::det_sin(0.5f * angle), 0.0f, rwd::det_cos(0.5f * angle)};
}

// Scripted drivers: each player sweeps the stick through throttle and
// steering at its own rate, charging and braking now and then.
std::vector<StickInput> inputs_at(Tick t, uint32_t players) {
  std::vector<StickInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    const int32_t phase = (static_cast<int32_t>(t) * static_cast<int32_t>(p + 2) / 40) % 6;
    static constexpr int16_t kSteer[6] = {0, 600, 0, -900, 300, 0};
    static constexpr int16_t kThrottle[6] = {1000, 800, 1000, 600, -500, 1000};
    inputs[p].axis_x = kSteer[phase];
    inputs[p].axis_y = kThrottle[phase];
    inputs[p].buttons = (static_cast<uint32_t>(t) % 150 == 10 * p ? kJoustCharge : 0u) |
                        (phase == 4 ? kJoustBrake : 0u);
  }
  return inputs;
}

TEST(JoustGame, BuildsCarsRidersAndTheWreckingBall) {
  auto sim = make_match(4);
  const JoustState s = state_of(*sim);
  sim::World3D& w = world(*sim);
  EXPECT_EQ(s.player_count, 4u);
  for (uint32_t p = 0; p < 4; ++p) {
    EXPECT_TRUE(w.is_valid(s.chassis[p]));
    EXPECT_TRUE(w.is_valid(s.lances[p]));
    EXPECT_FALSE(s.seats[p].is_null());
    for (const sim::BodyId part : s.riders[p]) EXPECT_TRUE(w.is_valid(part));
    for (const sim::JointId joint : s.rider_joints[p]) EXPECT_TRUE(w.is_valid(joint));
  }
  EXPECT_TRUE(w.is_valid(s.ball));
  // Per car: the lance weld, the seat weld and the ragdoll's ten; the
  // chain: one per link and the ball's.
  EXPECT_EQ(w.joint_count(), 4u * (2u + sim::kRagdollJointCount3D) + kJoustChainLinks + 1u);
  EXPECT_TRUE(sim->game().validate_state(sim->setup(), sim->game_state()).ok());
}

TEST(JoustGame, CarsDriveAndRidersStaySeatedOnTheBumps) {
  // Every car drives its own slow circle: no car meets another, so every
  // rider rides out the bumps on its seat.
  auto sim = make_match(4);
  std::vector<StickInput> inputs(4);
  for (auto& in : inputs) {
    in.axis_y = 300;
    in.axis_x = 1000;
  }
  const JoustState start = state_of(*sim);
  const sim::Vec3 from = world(*sim).position(start.chassis[0]);
  // Where each rider's head sits in its car's frame.
  auto head_in_car = [&](uint32_t p) {
    const sim::World3D& w = world(*sim);
    const JoustState s = state_of(*sim);
    const sim::BodyId head = s.riders[p][static_cast<uint32_t>(sim::RagdollPart3D::kHead)];
    return sim::inv_rotate(w.rotation(s.chassis[p]), w.position(head) - w.position(s.chassis[p]));
  };
  std::vector<sim::Vec3> seated_head;
  for (uint32_t p = 0; p < 4; ++p) seated_head.push_back(head_in_car(p));
  float travelled = 0.0f;
  for (Tick t = 0; t < 600; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    travelled = std::max(travelled, sim::length(world(*sim).position(start.chassis[0]) - from));
  }
  const JoustState s = state_of(*sim);
  std::printf("[ measured ] car 0 went up to %.1f m from its spawn point\n", travelled);
  EXPECT_GT(travelled, 3.0f);
  for (uint32_t p = 0; p < 4; ++p) {
    // The ragdoll sits up: its head is where it was seated, within a few cm.
    EXPECT_LT(sim::length(head_in_car(p) - seated_head[p]), 0.05f) << "player " << p;
    EXPECT_EQ(s.unseated[p], 0u) << "player " << p;
    EXPECT_EQ(s.car_resets[p], 0u) << "player " << p;
    EXPECT_FALSE(s.seats[p].is_null()) << "player " << p;
  }
}

TEST(JoustGame, RollbackAndReloadAreBitForBit) {
  constexpr uint32_t kPlayers = 4;
  auto sim = make_match(kPlayers);
  for (Tick t = 0; t < 150; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, kPlayers))).ok());
  SimSnapshot saved;
  sim->save(saved);
  std::vector<uint64_t> expected;
  for (Tick t = 150; t < 450; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, kPlayers))).ok());
    expected.push_back(sim->checksum());
  }
  sim->restore(saved);
  // A misprediction first, then the real inputs.
  for (Tick t = 150; t < 230; ++t)
    EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t + 17, kPlayers))).ok());
  sim->restore(saved);
  std::vector<uint8_t> bytes;
  sim->serialize(bytes);
  auto reloaded = make_match(kPlayers);
  ASSERT_TRUE(reloaded->deserialize(bytes).ok());
  for (Tick t = 150; t < 450; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs_at(t, kPlayers))).ok());
    EXPECT_TRUE(reloaded->step(stick_inputs(inputs_at(t, kPlayers))).ok());
    ASSERT_EQ(sim->checksum(), expected[static_cast<size_t>(t - 150)]) << "tick " << t;
    ASSERT_EQ(reloaded->checksum(), expected[static_cast<size_t>(t - 150)]) << "tick " << t;
  }
}

TEST(JoustGame, EveryTickRoundTripsThroughTheSnapshotBytes) {
  // Serialized every tick into a second match, which then steps on its own
  // copy: both stay equal, through charges, crashes and thrown riders.
  constexpr uint32_t kPlayers = 6;
  auto sim = make_match(kPlayers, 9);
  auto loaded = make_match(kPlayers, 9);
  std::vector<uint8_t> bytes;
  for (Tick t = 0; t < 400; ++t) {
    const std::vector<StickInput> inputs = inputs_at(t, kPlayers);
    sim->serialize(bytes);
    Status s = loaded->deserialize(bytes);
    ASSERT_TRUE(s.ok()) << "tick " << t << ": " << s.message();
    ASSERT_EQ(loaded->checksum(), sim->checksum()) << "tick " << t;
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    EXPECT_TRUE(loaded->step(stick_inputs(inputs)).ok());
    ASSERT_EQ(loaded->checksum(), sim->checksum()) << "tick " << t;
    ASSERT_TRUE(sim->game().validate_state(sim->setup(), sim->game_state()).ok()) << "tick " << t;
  }
  const JoustState s = state_of(*sim);
  uint32_t thrown = 0, resets = 0;
  for (uint32_t p = 0; p < kPlayers; ++p) {
    thrown += s.unseated[p];
    resets += s.car_resets[p];
  }
  std::printf("[ measured ] 6 scripted players, 400 ticks: %u riders thrown, %u car resets\n",
              thrown, resets);
}

TEST(JoustGame, ALanceStrikeThrowsTheRiderAndScores) {
  // Player 1's car stands broadside (facing +x), its rider at x = -10.2;
  // player 0 charges up the z axis with its lance (on its left, +x) lined
  // up on that rider.
  auto sim = make_match(2);
  JoustState s = state_of(*sim);
  sim::World3D& w = world(*sim);
  ASSERT_TRUE(JoustGame::place_car(w, s, 1, {-10.0f, 1.3f, 6.0f}, yaw(0.5f * rwd::kPi)));
  ASSERT_TRUE(JoustGame::place_car(w, s, 0, {-10.75f, 1.3f, -8.0f}, yaw(0.0f)));
  store(*sim, s);
  std::vector<StickInput> inputs(2);
  for (Tick t = 0; t < 60; ++t)
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());  // settle on the wheels
  s = state_of(*sim);
  ASSERT_FALSE(s.seats[1].is_null());
  ASSERT_EQ(s.unseated[1], 0u);

  inputs[0].axis_y = kAxisMax / 2;  // 6 m/s
  inputs[1].buttons = kJoustBrake;  // player 1 holds still
  Tick thrown_at = -1;
  float strike_speed = 0.0f;
  for (Tick t = 0; t < 240 && thrown_at < 0; ++t) {
    strike_speed = sim::length(w.linear_velocity(state_of(*sim).lances[0]));
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    if (state_of(*sim).unseated[1] > 0) thrown_at = t;
  }
  // Player 0 stops before its bumper meets the other car.
  inputs[0] = {};
  inputs[0].buttons = kJoustBrake;
  for (Tick t = 0; t < 6; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  ASSERT_GE(thrown_at, 0) << "the rider was never thrown";
  s = state_of(*sim);
  std::printf("[ measured ] rider thrown %d ticks into the run, the lance striking at %.1f m/s\n",
              static_cast<int>(thrown_at), static_cast<double>(strike_speed));
  EXPECT_TRUE(s.seats[1].is_null());
  EXPECT_EQ(s.score[0], 1u);
  EXPECT_EQ(s.score[1], 0u);
  EXPECT_EQ(s.unseated[0], 0u);  // the attacker kept its seat
  EXPECT_FALSE(s.seats[0].is_null());

  // The figure leaves the car: half a second later its pelvis is well clear.
  for (Tick t = 0; t < 30; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  s = state_of(*sim);
  const sim::Vec3 seat = w.position(s.chassis[1]);
  const float away = sim::length(w.position(s.riders[1][0]) - seat);
  std::printf("[ measured ] thrown rider's pelvis %.2f m from its car after 0.5 s\n",
              static_cast<double>(away));
  EXPECT_GT(away, 1.5f);
  EXPECT_EQ(state_of(*sim).score[0], 1u);  // one throw, one point

  // A few seconds later the rider is back on its car.
  for (Tick t = 0; t < 180; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  s = state_of(*sim);
  EXPECT_FALSE(s.seats[1].is_null());
  EXPECT_EQ(s.respawn_ticks[1], 0);
  EXPECT_LT(sim::length(w.position(s.riders[1][0]) - w.position(s.chassis[1])), 1.0f);
  EXPECT_TRUE(sim->game().validate_state(sim->setup(), sim->game_state()).ok());
}

TEST(JoustGame, AnUpsetCarGoesBackToItsSpawnPoint) {
  auto sim = make_match(2);
  JoustState s = state_of(*sim);
  sim::World3D& w = world(*sim);
  const sim::Vec3 spawn = w.position(s.chassis[1]);
  // On its roof, away from the spawn point.
  ASSERT_TRUE(JoustGame::place_car(w, s, 1, {-5.0f, 2.5f, 8.0f}, {1.0f, 0.0f, 0.0f, 0.0f}));
  store(*sim, s);
  std::vector<StickInput> inputs(2);
  for (Tick t = 0; t < 200; ++t) EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
  s = state_of(*sim);
  EXPECT_EQ(s.car_resets[1], 1u);
  // Put back and left with no brake on the bowl's floor, it may roll a
  // little before it stops.
  EXPECT_NEAR(w.position(s.chassis[1]).x, spawn.x, 0.5f);
  EXPECT_NEAR(w.position(s.chassis[1]).z, spawn.z, 0.5f);
  EXPECT_GT(sim::rotate(w.rotation(s.chassis[1]), {0.0f, 1.0f, 0.0f}).y, 0.9f);
}

TEST(JoustGame, TheWreckingBallSwingsAndItsChainHolds) {
  auto sim = make_match(2);
  const JoustState s = state_of(*sim);
  sim::World3D& w = world(*sim);
  std::vector<StickInput> inputs(2);
  float worst_opening = 0.0f;
  float z_min = 0.0f, z_max = 0.0f, top_speed = 0.0f;
  for (Tick t = 0; t < 1200; ++t) {
    EXPECT_TRUE(sim->step(stick_inputs(inputs)).ok());
    worst_opening = std::max(worst_opening, JoustGame::chain_opening(w, s));
    if (t >= 900) {  // the last five seconds
      const sim::Vec3 p = w.position(s.ball);
      z_min = std::min(z_min, p.z);
      z_max = std::max(z_max, p.z);
      top_speed = std::max(top_speed, sim::length(w.linear_velocity(s.ball)));
    }
  }
  std::printf(
      "[ measured ] wrecking ball after 15-20 s: swings z in [%.2f, %.2f] m, top speed %.2f m/s; "
      "max joint opening over 20 s %.5f m\n",
      static_cast<double>(z_min), static_cast<double>(z_max), static_cast<double>(top_speed),
      static_cast<double>(worst_opening));
  EXPECT_LT(z_min, -2.0f);
  EXPECT_GT(z_max, 2.0f);
  EXPECT_GT(top_speed, 4.0f);
  EXPECT_LT(worst_opening, 0.01f);
  for (const sim::JointId j : s.chain_joints) EXPECT_FALSE(w.is_joint_broken(j));
}

}  // namespace
}  // namespace rwd::game
