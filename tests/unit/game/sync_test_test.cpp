// SPDX-License-Identifier: MIT
// The sync test: the built-in games pass it, and games with the mistakes
// it exists for are caught by the check that should catch them, at a tick
// and a body field: state kept outside the state block (a rollback
// re-simulates differently) and rules that read the instance's address
// (a second copy of the match, or a reloaded state, differs).
#include "rewind/game/sync_test.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

#include "rewind/game/crates_game.h"
#include "rewind/game/game_registry.h"

namespace rwd::game {
namespace {

/// Crates with one mistake in how it reads its inputs; everything else is
/// the real game's.
class MistakenCrates : public Game {
 public:
  uint32_t rules_version() const override { return crates_.rules_version(); }
  std::unique_ptr<Lane> make_lane() const override { return crates_.make_lane(); }
  bool accepts_lane(const Lane& lane) const override { return crates_.accepts_lane(lane); }
  void encode_world_config(std::vector<uint8_t>& out) const override {
    crates_.encode_world_config(out);
  }
  Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
      std::span<const uint8_t> bytes) const override {
    return crates_.describe_world_config(bytes);
  }
  size_t state_size() const override { return crates_.state_size(); }
  Status build(const MatchSetup& setup, Lane& lane, std::span<std::byte> state) const override {
    return crates_.build(setup, lane, state);
  }
  Status apply_inputs(Tick tick, std::span<const PlayerInput> inputs, Lane& lane,
                      std::span<std::byte> state) const override {
    std::vector<PlayerInput> in(inputs.begin(), inputs.end());
    StickInput first = in[0].as<StickInput>();
    first.axis_x = static_cast<int16_t>(first.axis_x / 2 + tweak());
    in[0] = PlayerInput::of(first);
    return crates_.apply_inputs(tick, in, lane, state);
  }
  Status after_step(Tick tick, Lane& lane, std::span<std::byte> state) const override {
    return crates_.after_step(tick, lane, state);
  }
  void hash_state(std::span<const std::byte> state, rwd::StateHasher& hasher) const override {
    crates_.hash_state(state, hasher);
  }
  Status validate_state(const MatchSetup& setup, std::span<const std::byte> state) const override {
    return crates_.validate_state(setup, state);
  }

 protected:
  /// What the mistake adds to player 0's x axis, in [-500, 500].
  virtual int16_t tweak() const = 0;

 private:
  CratesGame crates_;
};

/// Counts its calls in a member: state outside the state block, so a
/// rollback's re-simulation sees other counts than the first run.
class CountingCrates final : public MistakenCrates {
 public:
  std::string_view name() const override { return "sync-counting-crates"; }

 private:
  int16_t tweak() const override { return static_cast<int16_t>((++calls_ % 5) * 100); }
  mutable uint64_t calls_ = 0;
};

/// Reads its own address: the same on every re-simulation of one match,
/// different in a second copy of it.
class AddressCrates final : public MistakenCrates {
 public:
  std::string_view name() const override { return "sync-address-crates"; }

 private:
  int16_t tweak() const override {
    return static_cast<int16_t>(reinterpret_cast<uintptr_t>(this) / 16 % 1000 - 500);
  }
};

void register_mistaken_games() {
  static const bool registered = [] {
    EXPECT_TRUE(register_game("sync-counting-crates", [] {
                  return std::make_unique<CountingCrates>();
                }).ok());
    EXPECT_TRUE(register_game("sync-address-crates", [] {
                  return std::make_unique<AddressCrates>();
                }).ok());
    return true;
  }();
  (void)registered;
}

TEST(SyncTest, TheBuiltInGamesAreDeterministic) {
  SyncTestOptions options;
  options.ticks = 150;
  options.check_distance = 3;
  for (const char* name : {"crates", "arena", "joust"}) {
    auto report = run_sync_test(name, {3, 5}, options);
    ASSERT_TRUE(report.ok()) << name << ": " << report.status().message();
    EXPECT_FALSE(report->failure.has_value()) << name << ": " << report->failure->describe();
    EXPECT_EQ(report->ticks, 150u);
    // Every tick after the first two re-simulated three times.
    EXPECT_EQ(report->resimulated_ticks, 1u + 2u + 148u * 3u) << name;
    EXPECT_EQ(report->round_trips, 149u) << name;
  }
}

TEST(SyncTest, StateOutsideTheStateBlockFailsTheRollbackCheck) {
  register_mistaken_games();
  SyncTestOptions options;
  options.ticks = 200;
  auto report = run_sync_test("sync-counting-crates", {2, 1}, options);
  ASSERT_TRUE(report.ok()) << report.status().message();
  ASSERT_TRUE(report->failure.has_value());
  const SyncTestFailure& f = *report->failure;
  EXPECT_EQ(f.check, SyncCheck::kRollback);
  EXPECT_NE(f.expected, f.actual);
  ASSERT_FALSE(f.fields.empty()) << f.describe();
  EXPECT_NE(f.describe().find("rollback check after tick " + std::to_string(f.tick)),
            std::string::npos)
      << f.describe();
  EXPECT_NE(f.describe().find("body " + std::to_string(f.fields[0].body_index)), std::string::npos);
  EXPECT_LT(report->ticks, 200u);  // stopped at the failure
}

TEST(SyncTest, AnAddressInTheRulesFailsTheSecondInstanceCheck) {
  register_mistaken_games();
  SyncTestOptions options;
  options.ticks = 120;
  auto report = run_sync_test("sync-address-crates", {2, 1}, options);
  ASSERT_TRUE(report.ok()) << report.status().message();
  ASSERT_TRUE(report->failure.has_value());
  EXPECT_EQ(report->failure->check, SyncCheck::kSecondInstance) << report->failure->describe();
  EXPECT_FALSE(report->failure->fields.empty());

  // A state reloaded into another instance steps differently too.
  options.second_instance = false;
  report = run_sync_test("sync-address-crates", {2, 1}, options);
  ASSERT_TRUE(report.ok());
  ASSERT_TRUE(report->failure.has_value());
  EXPECT_EQ(report->failure->check, SyncCheck::kRoundTrip) << report->failure->describe();

  // Within one instance nothing can see it.
  options.round_trip_every = 0;
  report = run_sync_test("sync-address-crates", {2, 1}, options);
  ASSERT_TRUE(report.ok());
  EXPECT_FALSE(report->failure.has_value());
}

TEST(SyncTest, GivenInputsAreUsedAndBadOptionsRefused) {
  SyncTestOptions options;
  options.ticks = 30;
  int calls = 0;
  auto report = run_sync_test("arena", {2, 1}, options, [&calls](Tick, std::span<PlayerInput> in) {
    ++calls;
    for (PlayerInput& i : in) i = stick_input(700, -300, 1);
  });
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(calls, 30);
  EXPECT_FALSE(report->failure.has_value());

  for (auto bad : {SyncTestOptions{0, 2, 1, true, 1}, SyncTestOptions{10, 0, 1, true, 1},
                   SyncTestOptions{10, 65, 1, true, 1}}) {
    auto refused = run_sync_test("crates", {2, 1}, bad);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  }
  auto unknown = run_sync_test("chess", {2, 1}, options);
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::game
