// SPDX-License-Identifier: MIT
// The replay player: re-simulation gives the recorded checksum at every
// tick, a seek anywhere (back through its snapshots or forward) lands on
// the state a straight run reaches, a forged checksum is found at its
// tick, and a desync report names the bodies that differ.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rewind/game/simulation.h"
#include "rewind/viewer/replay_player.h"

namespace rwd::viewer {
namespace {

/// A match of `game` played with inputs that change every few ticks,
/// recorded as the server would: inputs and the checksum after each tick.
ViewBundle played(const std::string& game_name, uint32_t players, Tick ticks) {
  ViewBundle b;
  b.game = game_name;
  b.setup.player_count = players;
  b.setup.seed = 11;
  auto sim = game::Simulation::create(game_name, b.setup);
  EXPECT_TRUE(sim.ok());
  std::vector<rwd::PlayerInput> inputs(players);
  for (Tick t = 0; t < ticks; ++t) {
    for (uint32_t p = 0; p < players; ++p) {
      inputs[p] =
          rwd::stick_input(static_cast<int16_t>(((t / 13 + static_cast<Tick>(p)) % 3 - 1) * 1000),
                           static_cast<int16_t>(((t / 29 + static_cast<Tick>(p)) % 3 - 1) * 700),
                           (t + static_cast<Tick>(p)) % 40 == 0 ? 1u : 0u);
    }
    EXPECT_TRUE((*sim)->step(inputs).ok());
    b.inputs.insert(b.inputs.end(), inputs.begin(), inputs.end());
    b.checksums.push_back((*sim)->checksum());
    b.substituted_masks.push_back(0);
  }
  return b;
}

TEST(ReplayPlayer, EveryTickOfEveryGameMatchesItsRecord) {
  for (const char* name : {"crates", "arena", "joust"}) {
    auto player = ReplayPlayer::create(played(name, 3, 150), 40);
    ASSERT_TRUE(player.ok()) << name << ": " << player.status().message();
    ReplayPlayer& p = **player;
    EXPECT_EQ(p.position(), 0);
    EXPECT_FALSE(p.recorded_checksum().has_value());
    EXPECT_EQ(p.check(0), TickCheck::kUnchecked);
    while (p.step()) {
      ASSERT_EQ(p.checksum(), *p.recorded_checksum()) << name << " at " << p.position();
    }
    EXPECT_EQ(p.position(), 150);
    EXPECT_FALSE(p.first_mismatch().has_value());
    EXPECT_EQ(p.check(150), TickCheck::kMatch);
    EXPECT_EQ(p.check(151), TickCheck::kUnchecked);
  }
}

TEST(ReplayPlayer, SeekingAnywhereLandsOnTheStraightRunsState) {
  const ViewBundle bundle = played("crates", 2, 200);
  auto player = ReplayPlayer::create(bundle, 32);
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  for (Tick target : {Tick{170}, Tick{3}, Tick{64}, Tick{65}, Tick{0}, Tick{199}, Tick{1},
                      Tick{500}, Tick{-4}, Tick{128}, Tick{127}}) {
    p.seek(target);
    const Tick expect = std::clamp(target, Tick{0}, Tick{200});
    ASSERT_EQ(p.position(), expect);
    if (expect > 0) {
      EXPECT_EQ(p.checksum(), bundle.checksums[static_cast<size_t>(expect) - 1]) << target;
    } else {
      auto fresh = game::Simulation::create("crates", bundle.setup);
      EXPECT_EQ(p.checksum(), (*fresh)->checksum());
    }
  }
}

TEST(ReplayPlayer, AForgedChecksumIsFoundAtItsTick) {
  ViewBundle bundle = played("joust", 2, 120);
  bundle.checksums[76] ^= 1;  // position 77
  bundle.checksums[100] ^= 1;
  auto player = ReplayPlayer::create(bundle);
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  p.seek(120);
  ASSERT_TRUE(p.first_mismatch().has_value());
  EXPECT_EQ(*p.first_mismatch(), 77);
  EXPECT_EQ(p.check(76), TickCheck::kMatch);
  EXPECT_EQ(p.check(77), TickCheck::kMismatch);
  EXPECT_EQ(p.check(78), TickCheck::kMatch);
  EXPECT_EQ(p.check(101), TickCheck::kMismatch);
}

TEST(ReplayPlayer, DrawsItsWorld) {
  auto player = ReplayPlayer::create(played("crates", 2, 30));
  ASSERT_TRUE(player.ok());
  (*player)->seek(30);
  rwd::DebugDrawBuffers out;
  (*player)->draw({}, out);
  EXPECT_FALSE(out.lines.empty());
  EXPECT_GT((*player)->stats().bodies, 2u);
}

TEST(ReplayPlayer, ADesyncReportNamesTheBodiesThatDiffer) {
  ViewBundle bundle = played("crates", 2, 120);
  // The client's state after tick 80, one body nudged as a desync would.
  auto client = game::Simulation::create("crates", bundle.setup);
  for (Tick t = 0; t <= 80; ++t) {
    ASSERT_TRUE((*client)
                    ->step(std::span<const rwd::PlayerInput>(bundle.inputs)
                               .subspan(static_cast<size_t>(t) * 2, 2))
                    .ok());
  }
  ASSERT_TRUE((*client)->lane().perturb_for_drill());
  ViewDesync d;
  d.tick = 80;
  d.player = 1;
  d.headline = "player 1 desync at tick 80";
  (*client)->serialize(d.client_state);
  bundle.desync = d;
  auto player = ReplayPlayer::create(bundle);
  ASSERT_TRUE(player.ok());
  auto view = (*player)->open_desync();
  ASSERT_TRUE(view.ok()) << view.status().message();
  EXPECT_EQ(view->position, 81);
  EXPECT_EQ((*player)->position(), 81);
  EXPECT_EQ(view->replay_checksum, bundle.checksums[80]);
  EXPECT_NE(view->client_checksum, view->replay_checksum);
  ASSERT_FALSE(view->differences.empty());
  ASSERT_EQ(view->bodies.size(), 1u);  // the drill nudges one body
  for (const rwd::FieldDifference& f : view->differences) {
    EXPECT_EQ(f.body_index, view->bodies[0]);
    EXPECT_NE(f.expected, f.actual);
  }

  bundle.desync->client_state.resize(10);
  auto broken = ReplayPlayer::create(bundle);
  auto refused = (*broken)->open_desync();
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kCorrupt);
  EXPECT_EQ((*broken)->position(), 0);  // nothing moved
}

TEST(ReplayPlayer, FindsABodysCentreInEitherLane) {
  for (const char* name : {"crates", "arena"}) {
    auto player = ReplayPlayer::create(played(name, 2, 20));
    ASSERT_TRUE(player.ok());
    (*player)->seek(20);
    std::vector<rwd::BodyField> fields;
    (*player)->simulation().dump_bodies(fields);
    const uint32_t last = fields.back().body_index;
    const auto at = (*player)->body_center(last);
    ASSERT_TRUE(at.has_value()) << name;
    bool matched = false;
    for (const rwd::BodyField& f : fields) {
      if (f.body_index == last && (f.name == "position.x" || f.name == "center.x")) {
        EXPECT_EQ((*at)[0], f.value()) << name;
        matched = true;
      }
    }
    EXPECT_TRUE(matched) << name;
    EXPECT_FALSE((*player)->body_center(100000).has_value());
  }
}

/// The part of `whole` from tick `from` on, starting from the state a
/// straight run reaches there, as a live server hands a joining viewer.
ViewBundle joined_at(const ViewBundle& whole, Tick from, Tick through) {
  ViewBundle b = whole;
  const uint32_t players = whole.setup.player_count;
  auto sim = game::Simulation::create(whole.game, whole.setup);
  for (Tick t = 0; t < from; ++t) {
    EXPECT_TRUE((*sim)
                    ->step(std::span<const rwd::PlayerInput>(whole.inputs)
                               .subspan(static_cast<size_t>(t) * players, players))
                    .ok());
  }
  (*sim)->serialize(b.start_state);
  b.first_tick = from;
  const auto first = static_cast<ptrdiff_t>(from);
  const auto last = static_cast<ptrdiff_t>(through);
  b.checksums.assign(whole.checksums.begin() + first, whole.checksums.begin() + last);
  b.substituted_masks.assign(whole.substituted_masks.begin() + first,
                             whole.substituted_masks.begin() + last);
  b.inputs.assign(whole.inputs.begin() + first * players, whole.inputs.begin() + last * players);
  return b;
}

LiveTicks batch_of(const ViewBundle& whole, Tick from, Tick through) {
  LiveTicks batch;
  batch.player_count = whole.setup.player_count;
  batch.first_tick = from;
  batch.newest_final = through - 1;
  const uint32_t players = whole.setup.player_count;
  for (Tick t = from; t < through; ++t) {
    batch.checksums.push_back(whole.checksums[static_cast<size_t>(t)]);
    batch.substituted_masks.push_back(0);
    for (uint32_t p = 0; p < players; ++p) {
      batch.inputs.push_back(whole.inputs[static_cast<size_t>(t) * players + p]);
    }
  }
  return batch;
}

TEST(ReplayPlayer, AViewerJoiningMidwayFollowsTheLiveTicks) {
  for (const char* name : {"crates", "arena"}) {
    const ViewBundle whole = played(name, 2, 260);
    auto player = ReplayPlayer::create(joined_at(whole, 90, 130), 25, 3);
    ASSERT_TRUE(player.ok()) << name << ": " << player.status().message();
    ReplayPlayer& p = **player;
    EXPECT_EQ(p.start(), 90);
    EXPECT_EQ(p.position(), 90);
    EXPECT_EQ(p.length(), 130);
    EXPECT_FALSE(p.recorded_checksum().has_value());
    // Polls that overlap what the player has, or come in pieces.
    ASSERT_TRUE(p.append(batch_of(whole, 120, 180)).ok());
    LiveTicks named = batch_of(whole, 180, 260);
    named.player_names = {"ann", "bo"};
    ASSERT_TRUE(p.append(named).ok());
    EXPECT_EQ(p.bundle().player_names, named.player_names);
    EXPECT_EQ(p.length(), 260);
    while (p.step()) {
      ASSERT_EQ(p.checksum(), *p.recorded_checksum()) << name << " at " << p.position();
    }
    EXPECT_FALSE(p.first_mismatch().has_value());
    EXPECT_EQ(p.check(90), TickCheck::kUnchecked);
    EXPECT_EQ(p.check(91), TickCheck::kMatch);
    // Back through the few snapshots it keeps, and to the start.
    for (Tick target : {Tick{200}, Tick{91}, Tick{0}, Tick{259}, Tick{140}}) {
      p.seek(target);
      const Tick expect = std::max(target, Tick{90});
      ASSERT_EQ(p.position(), expect) << name;
      EXPECT_EQ(p.checksum(), whole.checksums[static_cast<size_t>(expect) - 1]) << name;
    }
  }
}

TEST(ReplayPlayer, ABatchWithAGapOrOtherPlayersIsRefused) {
  const ViewBundle whole = played("arena", 2, 80);
  auto player = ReplayPlayer::create(joined_at(whole, 10, 40));
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  auto gap = p.append(batch_of(whole, 41, 60));
  EXPECT_EQ(gap.code(), ErrorCode::kInvalidArgument);
  LiveTicks three = batch_of(whole, 40, 41);
  three.player_count = 3;
  three.inputs.push_back({});
  EXPECT_EQ(p.append(three).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(p.length(), 40);  // nothing taken
  EXPECT_EQ(p.bundle().inputs.size(), 60u);
}

TEST(ReplayPlayer, AStartStateThatDoesNotFitIsRefused) {
  const ViewBundle whole = played("crates", 2, 60);
  ViewBundle wrong_tick = joined_at(whole, 30, 50);
  wrong_tick.first_tick = 31;  // the state is at 30
  auto refused = ReplayPlayer::create(wrong_tick);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kCorrupt);
  ViewBundle broken = joined_at(whole, 30, 50);
  broken.start_state.resize(broken.start_state.size() / 2);
  refused = ReplayPlayer::create(broken);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kCorrupt);
  ViewBundle stateless = joined_at(whole, 30, 50);
  stateless.start_state.clear();
  refused = ReplayPlayer::create(stateless);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
}

/// `bundle` with the state after every `every`th tick as recorded keyframes.
ViewBundle with_keyframes(ViewBundle bundle, Tick every) {
  auto sim = game::Simulation::create(bundle.game, bundle.setup);
  const uint32_t players = bundle.setup.player_count;
  for (Tick t = 0; t < bundle.end_position(); ++t) {
    EXPECT_TRUE((*sim)
                    ->step(std::span<const rwd::PlayerInput>(bundle.inputs)
                               .subspan(static_cast<size_t>(t) * players, players))
                    .ok());
    if ((t + 1) % every == 0) {
      ViewKeyframe k;
      k.position = t + 1;
      (*sim)->serialize(k.state);
      bundle.keyframes.push_back(std::move(k));
    }
  }
  return bundle;
}

TEST(ReplayPlayer, SeeksJumpThroughTheRecordedKeyframes) {
  for (const char* name : {"crates", "arena"}) {
    const ViewBundle bundle = with_keyframes(played(name, 2, 300), 100);
    auto player = ReplayPlayer::create(bundle, 1000);
    ASSERT_TRUE(player.ok());
    ReplayPlayer& p = **player;
    p.seek(250);  // from the state recorded at 200: ticks 1..200 never stepped
    EXPECT_EQ(p.checksum(), bundle.checksums[249]) << name;
    EXPECT_EQ(p.check(200), TickCheck::kMatch);
    EXPECT_EQ(p.check(150), TickCheck::kUnchecked);
    EXPECT_EQ(p.check(250), TickCheck::kMatch);
    p.seek(120);  // back: from the one at 100
    EXPECT_EQ(p.checksum(), bundle.checksums[119]) << name;
    EXPECT_EQ(p.check(99), TickCheck::kUnchecked);
    EXPECT_FALSE(p.first_mismatch().has_value());
    EXPECT_EQ(p.verified_through(), 0);
    // Verifying when idle fills in what the jumps passed over.
    EXPECT_EQ(p.verify(40), 40);
    EXPECT_EQ(p.check(40), TickCheck::kMatch);
    EXPECT_EQ(p.check(41), TickCheck::kUnchecked);
    while (p.verify(100) < p.length()) {
    }
    for (Tick t = 1; t <= 300; ++t) ASSERT_EQ(p.check(t), TickCheck::kMatch) << name << " " << t;
    EXPECT_EQ(p.position(), 120);  // the view did not move
    EXPECT_EQ(p.checksum(), bundle.checksums[119]);
  }
}

TEST(ReplayPlayer, VerifyingFindsAMismatchASeekJumpedOver) {
  ViewBundle bundle = with_keyframes(played("arena", 2, 200), 100);
  bundle.checksums[30] ^= 1;  // position 31: the recording says otherwise
  auto player = ReplayPlayer::create(bundle);
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  p.seek(150);
  EXPECT_FALSE(p.first_mismatch().has_value());
  for (int i = 0; i < 10; ++i) p.verify(25);
  ASSERT_TRUE(p.first_mismatch().has_value());
  EXPECT_EQ(*p.first_mismatch(), 31);
  EXPECT_EQ(p.verified_through(), 200);
}

TEST(ReplayPlayer, SteppingFromTheStartCountsAsVerified) {
  auto player = ReplayPlayer::create(played("crates", 2, 50));
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  p.seek(30);
  EXPECT_EQ(p.verified_through(), 30);
  p.seek(10);
  p.step();
  EXPECT_EQ(p.verified_through(), 30);
  EXPECT_EQ(p.verify(5), 35);
}

TEST(ReplayPlayer, ARecordedKeyframeThatDoesNotFitIsPassedOver) {
  ViewBundle bundle = with_keyframes(played("crates", 2, 200), 50);
  std::swap(bundle.keyframes[2].state, bundle.keyframes[1].state);         // 150 holds 100's state
  bundle.keyframes[0].state.resize(bundle.keyframes[0].state.size() / 2);  // 50 does not load
  auto player = ReplayPlayer::create(bundle, 1000);
  ASSERT_TRUE(player.ok());
  ReplayPlayer& p = **player;
  p.seek(170);  // 150 is unusable: from the one at 100 (which holds 150's state: unusable too)
  EXPECT_EQ(p.position(), 170);
  EXPECT_EQ(p.checksum(), bundle.checksums[169]);
  EXPECT_FALSE(p.first_mismatch().has_value());
  p.seek(60);  // 50 does not load: from the start
  EXPECT_EQ(p.checksum(), bundle.checksums[59]);
  EXPECT_EQ(p.check(10), TickCheck::kMatch);
  p.seek(199);
  EXPECT_EQ(p.checksum(), bundle.checksums[198]);
  EXPECT_FALSE(p.first_mismatch().has_value());
}

TEST(ReplayPlayer, AnUnknownGameIsRefused) {
  ViewBundle bundle = played("crates", 2, 5);
  bundle.game = "chess";
  auto player = ReplayPlayer::create(bundle);
  ASSERT_FALSE(player.ok());
  EXPECT_EQ(player.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::viewer
