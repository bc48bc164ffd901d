// SPDX-License-Identifier: MIT
// A game's rules return errors instead of dropping them: Simulation::create
// and Simulation::step pass them on with the game and the tick named, and
// a failed step leaves the tick where it was.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "failing_game.h"
#include "rewind/game/simulation.h"

namespace rwd::game {
namespace {

using test::FailingGame;

std::unique_ptr<Simulation> made(FailingGame::Where where, Tick tick) {
  auto sim = Simulation::create(std::make_unique<FailingGame>(where, tick), MatchSetup{2, 1});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  return sim.ok() ? std::move(*sim) : nullptr;
}

TEST(RulesError, ABuildThatFailsIsRefusedWithItsMessage) {
  auto sim = Simulation::create(std::make_unique<FailingGame>(FailingGame::Where::kBuild, 0),
                                MatchSetup{2, 1});
  ASSERT_FALSE(sim.ok());
  EXPECT_EQ(sim.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(sim.status().message().find("game 'failing' could not build its match"),
            std::string::npos)
      << sim.status().message();
}

TEST(RulesError, AFailedStepNamesTheGameAndTheTickAndStaysThere) {
  for (const auto where : {FailingGame::Where::kApply, FailingGame::Where::kAfterStep}) {
    auto sim = made(where, 3);
    ASSERT_NE(sim, nullptr);
    const PlayerInput inputs[2] = {};
    for (Tick t = 0; t < 3; ++t) ASSERT_TRUE(sim->step(inputs).ok());
    const Status failed = sim->step(inputs);
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(failed.code(),
              where == FailingGame::Where::kApply ? ErrorCode::kCorrupt : ErrorCode::kNotFound);
    EXPECT_NE(failed.message().find("game 'failing', tick 3: "), std::string::npos)
        << failed.message();
    EXPECT_EQ(sim->tick(), 3) << "a failed tick is not counted as stepped";
  }
}

TEST(RulesError, NullGamesAndBadSetupsAreRefused) {
  EXPECT_EQ(Simulation::create(std::unique_ptr<Game>(), MatchSetup{}).status().code(),
            ErrorCode::kInvalidArgument);
  auto none = Simulation::create(std::make_unique<FailingGame>(FailingGame::Where::kNowhere, 0),
                                 MatchSetup{0, 1});
  EXPECT_EQ(none.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::game
