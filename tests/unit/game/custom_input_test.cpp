// SPDX-License-Identifier: MIT
// A game that declares its own input (CarInput): its rules get the typed
// struct, the simulation refuses inputs outside the spec before anything
// changes, a spec that does not match the struct is refused, and the bots
// and the sync test drive it through the spec alone.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "car_input_game.h"
#include "rewind/game/game_registry.h"
#include "rewind/game/simulation.h"
#include "rewind/game/sync_test.h"

namespace rwd::game {
namespace {

using test::CarInput;
using test::CarInputGame;

std::unique_ptr<Simulation> make(uint32_t players, uint8_t size = sizeof(CarInput)) {
  auto sim = Simulation::create(std::make_unique<CarInputGame>(size), {players, 3});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  return sim.ok() ? std::move(*sim) : nullptr;
}

const test::CarGameState& state_of(const Simulation& sim) {
  return *reinterpret_cast<const test::CarGameState*>(sim.game_state().data());
}

TEST(CustomInput, TheRulesGetTheGamesOwnStruct) {
  auto sim = make(2);
  ASSERT_NE(sim, nullptr);
  const std::vector<PlayerInput> inputs = {PlayerInput::of(CarInput{-300, 50, 1}),
                                           PlayerInput::of(CarInput{120, 100, 0})};
  for (int t = 0; t < 3; ++t) ASSERT_TRUE(sim->step(inputs).ok());
  EXPECT_EQ(state_of(*sim).steer_total[0], -900);
  EXPECT_EQ(state_of(*sim).steer_total[1], 360);
  EXPECT_EQ(state_of(*sim).brakes[0], 3u);
}

TEST(CustomInput, AnInputOutsideTheSpecIsRefusedAndChangesNothing) {
  auto sim = make(2);
  ASSERT_NE(sim, nullptr);
  const uint64_t before = sim->checksum();
  const std::vector<PlayerInput> bad = {PlayerInput{}, PlayerInput::of(CarInput{0, 101, 0})};
  const Status status = sim->step(bad);
  EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(status.message(),
            "game 'cars', tick 0: player 1: input field 'throttle' is 101, outside [0, 100]");
  EXPECT_EQ(sim->tick(), 0);
  EXPECT_EQ(sim->checksum(), before);
  // A byte past the game's 4 is refused the same way.
  PlayerInput past;
  past.bytes[4] = 1;
  EXPECT_EQ(sim->step(std::vector<PlayerInput>{past, PlayerInput{}}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_TRUE(sim->step(std::vector<PlayerInput>(2)).ok());
}

TEST(CustomInput, ASpecThatDoesNotMatchTheStructIsRefused) {
  auto sim = Simulation::create(std::make_unique<CarInputGame>(6), {2, 3});
  ASSERT_FALSE(sim.ok());
  EXPECT_EQ(sim.status().message(),
            "game 'cars' could not build its match: input_spec() declares 6 bytes, but the "
            "game's Input struct has 4");
  auto empty = Simulation::create(std::make_unique<CarInputGame>(0), {2, 3});
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.status().message(),
            "game 'cars' declares a bad input: an input spec's size must be 1 to 32 bytes, not 0");
}

TEST(CustomInput, DefaultBotsAndTheSyncTestUseTheSpec) {
  const CarInputGame game;
  bool braked = false;
  for (Tick t = 0; t < 400; ++t) {
    const PlayerInput input = game.bot_input(9, 1, t);
    ASSERT_TRUE(check_input(game.input_spec(), input).ok()) << t;
    EXPECT_EQ(input, game.bot_input(9, 1, t));  // a pure function
    braked = braked || input.as<CarInput>().brake == 1;
  }
  EXPECT_TRUE(braked);

  ASSERT_TRUE(register_game("cars", [] { return std::make_unique<CarInputGame>(); }).ok());
  SyncTestOptions options;
  options.ticks = 120;
  auto report = run_sync_test("cars", {3, 5}, options);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_FALSE(report->failure.has_value());
}

}  // namespace
}  // namespace rwd::game
