// SPDX-License-Identifier: MIT
#include "rewind/net/rollback_session.h"

#include "car_input_game.h"
#include "failing_game.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

namespace rwd::net {
namespace {

constexpr uint32_t kPlayers = 3;

std::unique_ptr<RollbackSession> make_session(int32_t snapshot_ticks = 32) {
  auto sim = game::Simulation::create("crates", {kPlayers, 11});
  EXPECT_TRUE(sim.ok());
  RollbackConfig config;
  config.snapshot_ticks = snapshot_ticks;
  return std::make_unique<RollbackSession>(std::move(*sim), config);
}

// A scripted input stream: direction changes every few ticks, buttons now
// and then, so mispredictions are frequent.
rwd::PlayerInput scripted(uint32_t player, Tick tick) {
  std::mt19937 rng(static_cast<uint32_t>(tick / 4) * 7919u + player * 104729u);
  std::uniform_int_distribution<int> axis(-1000, 1000);
  rwd::StickInput input;
  input.axis_x = static_cast<int16_t>(axis(rng));
  input.axis_y = static_cast<int16_t>(axis(rng));
  input.buttons = (rng() % 23 == 0) ? 1u : 0u;
  return rwd::PlayerInput::of(input);
}

// Checksums after each tick when every input is known before it is simulated.
std::vector<uint64_t> reference_checksums(Tick ticks) {
  auto session = make_session();
  std::vector<uint64_t> out;
  for (Tick t = 0; t < ticks; ++t) {
    for (uint32_t p = 0; p < kPlayers; ++p) {
      EXPECT_EQ(session->add_input(p, t, scripted(p, t)), InputResult::kAccepted);
    }
    session->advance();
    out.push_back(*session->checksum_after(t));
  }
  return out;
}

// The headline property of the rollback core: inputs arriving late and in
// random order, with predictions and re-simulation in between, give every
// final tick exactly the checksum of the run where all inputs were known.
TEST(RollbackSession, LateInputsReproduceTheAllKnownRunBitForBit) {
  constexpr Tick kTicks = 240;
  constexpr Tick kWindow = 8;
  const std::vector<uint64_t> expected = reference_checksums(kTicks);

  for (uint32_t seed : {1u, 2u, 3u}) {
    auto session = make_session();
    std::mt19937 rng(seed);
    // Arrival tick of each (player, tick) input: up to kWindow - 1 late,
    // or a few ticks early.
    std::multimap<Tick, std::pair<uint32_t, Tick>> arrivals;
    for (Tick t = 0; t < kTicks; ++t) {
      for (uint32_t p = 0; p < kPlayers; ++p) {
        std::uniform_int_distribution<int> delay(-3, kWindow - 1);
        arrivals.emplace(std::max<Tick>(0, t + delay(rng)), std::make_pair(p, t));
      }
    }
    Tick next_final = 0;
    for (Tick now = 0; now < kTicks + kWindow + 1; ++now) {
      auto [begin, end] = arrivals.equal_range(now);
      for (auto it = begin; it != end; ++it) {
        const auto [player, tick] = it->second;
        EXPECT_EQ(session->add_input(player, tick, scripted(player, tick)), InputResult::kAccepted);
      }
      ASSERT_TRUE(session->synchronize());
      while (next_final < session->current_tick() && next_final + kWindow <= now) {
        ASSERT_TRUE(session->finalize_through(next_final));
        const std::optional<uint64_t> checksum = session->checksum_after(next_final);
        ASSERT_TRUE(checksum.has_value());
        ASSERT_EQ(*checksum, expected[static_cast<size_t>(next_final)])
            << "seed " << seed << " final tick " << next_final;
        ++next_final;
      }
      if (session->current_tick() < kTicks) session->advance();
    }
    EXPECT_EQ(next_final, kTicks);
    EXPECT_GT(session->stats().rollbacks, 0u) << "the scenario must exercise rollback";
    EXPECT_GT(session->stats().resimulated_ticks, session->stats().rollbacks);
  }
}

TEST(RollbackSession, InputsForFinalTicksAndBadSlotsAreRefused) {
  auto session = make_session();
  for (Tick t = 0; t < 5; ++t) session->advance();
  ASSERT_TRUE(session->finalize_through(2));
  EXPECT_EQ(session->add_input(0, 2, {}), InputResult::kFinal);
  EXPECT_EQ(session->add_final_input(0, 1, {}), InputResult::kFinal);
  EXPECT_EQ(session->add_input(kPlayers, 3, {}), InputResult::kBadPlayer);
  EXPECT_EQ(session->add_input(0, 3 + 1000, {}), InputResult::kTooFar);
  EXPECT_EQ(session->add_input(0, 3, rwd::stick_input(100, 0)), InputResult::kAccepted);
  EXPECT_EQ(session->add_input(0, 3, rwd::stick_input(100, 0)), InputResult::kDuplicate);
  EXPECT_EQ(session->add_input(0, 3, rwd::stick_input(-100, 0)), InputResult::kConflict);
  // Outside the game's input spec: refused before it is stored.
  EXPECT_EQ(session->add_input(1, 3, rwd::stick_input(1001, 0)), InputResult::kBadInput);
  EXPECT_EQ(session->add_final_input(1, 3, rwd::stick_input(0, -1001)), InputResult::kBadInput);
  EXPECT_FALSE(session->queue(1).is_confirmed(3));
}

TEST(RollbackSession, UnconfirmedTicksUseTheGamesPredictor) {
  auto sim = game::Simulation::create(std::make_unique<test::CarInputGame>(), {2, 11});
  ASSERT_TRUE(sim.ok());
  RollbackSession session(std::move(*sim), RollbackConfig{});
  const auto braking = rwd::PlayerInput::of(test::CarInput{200, 80, 1});
  EXPECT_EQ(session.add_input(0, 0, braking), InputResult::kAccepted);
  session.advance();
  session.advance();
  EXPECT_EQ(session.used_input(0, 0), braking);
  // Tick 1 is predicted: the same steering and throttle, the brake let go.
  EXPECT_EQ(session.used_input(0, 1), rwd::PlayerInput::of(test::CarInput{200, 80, 0}));
}

TEST(RollbackSession, FinalInputOverridesAConfirmedOneAndResimulates) {
  auto session = make_session();
  for (uint32_t p = 0; p < kPlayers; ++p) (void)session->add_input(p, 0, scripted(p, 0));
  for (Tick t = 0; t < 4; ++t) session->advance();
  const uint64_t before = *session->checksum_after(3);
  EXPECT_EQ(session->add_final_input(1, 0, rwd::stick_input(1000, 1000, 2)),
            InputResult::kAccepted);
  ASSERT_TRUE(session->synchronize());
  EXPECT_EQ(session->stats().rollbacks, 1u);
  EXPECT_EQ(session->stats().resimulated_ticks, 4u);
  EXPECT_NE(*session->checksum_after(3), before);
  EXPECT_EQ(session->used_input(1, 0), rwd::stick_input(1000, 1000, 2));
}

TEST(RollbackSession, RollbackBeyondTheRingIsReportedNotGuessed) {
  auto session = make_session(/*snapshot_ticks=*/16);
  for (Tick t = 0; t < 30; ++t) session->advance();
  EXPECT_EQ(session->add_input(0, 2, rwd::stick_input(500, 0)), InputResult::kAccepted);
  EXPECT_FALSE(session->synchronize());
}

TEST(RollbackSession, SerializedStateResetsAnotherSession) {
  auto a = make_session();
  auto b = make_session();
  for (Tick t = 0; t < 20; ++t) {
    for (uint32_t p = 0; p < kPlayers; ++p) (void)a->add_input(p, t, scripted(p, t));
    a->advance();
  }
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(a->serialize_state_at(15, bytes));
  ASSERT_TRUE(b->reset_from(bytes).ok());
  EXPECT_EQ(b->current_tick(), 15);
  EXPECT_EQ(b->final_tick(), 14);
  for (Tick t = 15; t < 20; ++t) {
    for (uint32_t p = 0; p < kPlayers; ++p) (void)b->add_input(p, t, scripted(p, t));
    b->advance();
  }
  EXPECT_EQ(b->simulation().checksum(), a->simulation().checksum());

  // Garbage leaves the session as it was.
  const uint64_t checksum = b->simulation().checksum();
  bytes.resize(bytes.size() / 2);
  EXPECT_FALSE(b->reset_from(bytes).ok());
  EXPECT_EQ(b->simulation().checksum(), checksum);
  EXPECT_EQ(b->current_tick(), 20);
}

TEST(RollbackSession, StepHookRunsOnEveryResimulationOfItsTick) {
  auto session = make_session();
  int calls_at_2 = 0;
  session->set_step_hook([&](game::Simulation&, Tick tick) { calls_at_2 += tick == 2; });
  for (Tick t = 0; t < 5; ++t) session->advance();
  EXPECT_EQ(calls_at_2, 1);
  (void)session->add_input(0, 1, rwd::stick_input(1000, 0));
  ASSERT_TRUE(session->synchronize());
  EXPECT_EQ(calls_at_2, 2);
}

// A late input that makes the rules fail during re-simulation stops the
// session there: the error is kept, and nothing steps past it.
TEST(RollbackSession, TheRulesFirstErrorStopsTheSession) {
  using test::FailingGame;
  auto sim = game::Simulation::create(
      std::make_unique<FailingGame>(FailingGame::Where::kApplyOnTrigger, 0), {2, 1});
  ASSERT_TRUE(sim.ok()) << sim.status().message();
  RollbackSession session(std::move(*sim), RollbackConfig{});
  for (Tick t = 0; t < 6; ++t) session.advance();  // predicted inputs: all neutral
  EXPECT_TRUE(session.game_error().ok());
  const rwd::PlayerInput trigger = rwd::stick_input(FailingGame::kTrigger, 0);
  ASSERT_EQ(session.add_input(0, 2, trigger), InputResult::kAccepted);
  session.advance();
  ASSERT_FALSE(session.game_error().ok());
  EXPECT_NE(session.game_error().message().find("tick 2: score table out of range"),
            std::string::npos)
      << session.game_error().message();
  EXPECT_EQ(session.current_tick(), 2);
  session.advance();
  EXPECT_TRUE(session.synchronize());
  EXPECT_EQ(session.current_tick(), 2) << "a failed session steps no more";
}

}  // namespace
}  // namespace rwd::net
