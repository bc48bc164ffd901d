// SPDX-License-Identifier: MIT
// A long 16-player crates match on a simulated clock: the real MatchHost,
// one client SDK session and fifteen scripted protocol peers over a lossy
// simulated network (tests/support/headless_match.h), aggressive scripted
// play (everyone into the same corner, jumps and dashes), the SDK client
// corrupted late in the match. The client must verify every final tick
// but the ones its resync skips, the desync must be detected, reported and
// resynced, the replay must verify to its last tick and every keyframe
// must load. Plays 100,000 ticks (28 minutes at 60 Hz) unless
// REWIND_LONG_MATCH_TICKS says otherwise (sanitizer builds play fewer).
//
// One SDK client, not more: each one simulates the whole match again (and
// re-simulates on every misprediction), which is most of this test's time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include "headless_match.h"
#include "rewind/game/crates_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"
#include "rewind/proto/input_wire.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_verifier.h"
#include "scratch_dir.h"

namespace rwd::test {
namespace {

// crates runs the 3D lane; these checks read its world.
const sim::World3D& world3d(const game::Simulation& simulation) {
  return *game::world_of<sim::World3D>(simulation.lane());
}

using client::ClientEventType;

Tick match_ticks() {
  const char* text = std::getenv("REWIND_LONG_MATCH_TICKS");
  const long value = text != nullptr ? std::strtol(text, nullptr, 10) : 0;
  return value >= 3000 ? static_cast<Tick>(value) : 100'000;
}

// Where the pushers are at a keyframe. Those that left the arena (over a
// wall, or through a gap) are reported, not judged: the game's rules decide
// what happens to them, and the match, its replay and its resyncs must go
// on either way.
struct ArenaCheck {
  uint32_t keyframes_with_escapes = 0;
  uint32_t most_outside = 0;
  uint32_t most_in_one_corner = 0;   // pushers within 3 m of a corner on both axes: the pile-up
  Tick first_escape_tick = kNoTick;  // exact, found by stepping from the keyframe before
  uint32_t first_escape_player = 0;
  sim::Vec3 first_escape_position;
};

bool outside_arena(const game::Simulation& sim, sim::BodyId pusher) {
  const sim::Vec3 pos = world3d(sim).position(pusher);
  return !world3d(sim).is_enabled(pusher) || pos.y < -1.0f || std::abs(pos.x) > 11.0f ||
         std::abs(pos.z) > 11.0f;
}

game::CratesState crates_state(const game::Simulation& sim) {
  game::CratesState state;
  std::memcpy(&state, sim.game_state().data(), sizeof(state));
  return state;
}

// Counts the pushers outside the arena; the first one found sets where.
uint32_t count_outside(const game::Simulation& sim, uint32_t* first) {
  const game::CratesState state = crates_state(sim);
  uint32_t outside = 0;
  for (uint32_t p = state.player_count; p-- > 0;) {
    if (outside_arena(sim, state.pushers[p])) {
      ++outside;
      *first = p;
    }
  }
  return outside;
}

void check_keyframe(const game::Simulation& sim, ArenaCheck& out) {
  ASSERT_EQ(sim.game_state().size(), sizeof(game::CratesState));
  const game::CratesState state = crates_state(sim);
  uint32_t first = 0;
  const uint32_t outside = count_outside(sim, &first);
  if (outside > 0) ++out.keyframes_with_escapes;
  out.most_outside = std::max(out.most_outside, outside);
  std::map<int, uint32_t> corners;
  for (uint32_t p = 0; p < state.player_count; ++p) {
    const sim::Vec3 pos = world3d(sim).position(state.pushers[p]);
    if (!outside_arena(sim, state.pushers[p]) && std::abs(pos.x) > 7.0f && std::abs(pos.z) > 7.0f) {
      ++corners[(pos.x > 0 ? 1 : 0) + (pos.z > 0 ? 2 : 0)];
    }
  }
  for (const auto& [corner, count] : corners) {
    out.most_in_one_corner = std::max(out.most_in_one_corner, count);
  }
}

Result<std::unique_ptr<game::Simulation>> load_state(uint64_t seed, const std::string& bytes) {
  auto sim = game::Simulation::create("crates", {16, seed});
  if (!sim.ok()) return sim.status();
  if (Status status = (*sim)->deserialize(
          std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
      !status.ok()) {
    return status;
  }
  return std::move(*sim);
}

TEST(LongMatch, SixteenPlayersAggressivePlayLateDesyncResyncsAndReplayVerifies) {
  const Tick ticks = match_ticks();
  const Tick corrupt_at = ticks - 2000;
  ScratchDir dir("long_match");
  const std::string replay_path = (dir.path() / "match.rwr").string();

  HeadlessConfig config;
  config.match.players = 16;
  config.match.tick_rate_hz = 60;
  config.match.window_ticks = 8;
  config.match.max_ticks = ticks;
  config.match.keyframe_interval = 300;
  config.match.replay_path = replay_path;
  config.match.desync_dir = (dir.path() / "desyncs").string();
  config.sdk_clients = 1;
  config.corrupt_client = 0;
  config.corrupt_at_tick = corrupt_at;
  config.latency_ms = 20;
  config.jitter_ms = 5;
  config.loss = 0.05;  // as in the match that broke
  config.seed = 16;
  config.inputs = [](uint32_t player, Tick tick) {
    return aggressive_crates_input(16, player, tick);
  };

  const auto started = std::chrono::steady_clock::now();
  auto match = HeadlessMatch::create(config);
  ASSERT_TRUE(match.ok()) << match.status().message();
  const HeadlessResult result = (*match)->run();
  const double match_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("match: %d ticks (%.0f s simulated) in %.1f s; %s\n", ticks, result.simulated_seconds,
              match_s, result.server.to_json().c_str());

  ASSERT_EQ(result.clients.size(), 1u);
  const SdkClientResult& client = result.clients[0];
  std::printf(
      "client (player %u): %llu rollbacks, %llu ticks re-simulated, %llu final ticks "
      "verified\n",
      client.player, static_cast<unsigned long long>(client.stats.rollbacks),
      static_cast<unsigned long long>(client.stats.resimulated_ticks),
      static_cast<unsigned long long>(client.stats.final_ticks_verified));

  // The match ran to its budget and everyone left cleanly.
  ASSERT_FALSE(result.timed_out);
  EXPECT_EQ(result.server.ticks_final, ticks);
  EXPECT_EQ(result.server.end_reason, "tick budget reached");
  EXPECT_EQ(result.server.players_joined, 16u);
  EXPECT_EQ(result.scripted_peers_finished, 15u);
  // Redundant inputs survive 5 % loss: substitutions stay rare.
  EXPECT_LT(result.server.substituted_inputs, static_cast<uint64_t>(ticks) * 16 / 100);
  // Nothing on the resync path failed.
  EXPECT_EQ(result.server.resync_snapshot_failures, 0u);
  EXPECT_EQ(result.server.resyncs_refused, 0u);
  EXPECT_EQ(result.server.desync_dumps_unreadable, 0u);
  EXPECT_EQ(result.server.desync_report_write_failures, 0u);
  EXPECT_EQ(result.server.keyframe_load_failures, 0u);
  EXPECT_TRUE(result.server.problems().empty()) << result.server.problems();

  // The client: in step up to its corruption, detected there, reported,
  // resynced, and in step again to the end.
  std::vector<std::pair<ClientEventType, Tick>> episode;
  for (const client::ClientEvent& e : client.events) {
    if (e.type == ClientEventType::kDesync || e.type == ClientEventType::kResynced ||
        e.type == ClientEventType::kResyncRefused) {
      episode.emplace_back(e.type, e.tick);
    }
  }
  ASSERT_EQ(episode.size(), 2u) << "expected one desync and one resync";
  EXPECT_EQ(episode[0], std::make_pair(ClientEventType::kDesync, corrupt_at));
  EXPECT_EQ(episode[1].first, ClientEventType::kResynced);
  const Tick resumed_at = episode[1].second;  // the snapshot's tick
  EXPECT_GT(resumed_at, corrupt_at);
  EXPECT_LT(resumed_at, corrupt_at + 120) << "the resync took more than two seconds";
  EXPECT_EQ(client.stats.desyncs, 1u);
  EXPECT_TRUE(client.ended);
  EXPECT_EQ(client.stats.last_final_tick, ticks - 1);
  EXPECT_EQ(client.stats.final_ticks_verified,
            static_cast<uint64_t>(corrupt_at) + static_cast<uint64_t>(ticks - resumed_at))
      << "every final tick but the desynced one and those the snapshot skipped";
  EXPECT_EQ(result.server.desync_reports, 1u);
  EXPECT_EQ(result.server.resyncs_sent, 1u);
  bool report_stored = false;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path() / "desyncs")) {
    if (entry.path().extension() != ".txt") continue;
    std::FILE* file = std::fopen(entry.path().c_str(), "r");
    ASSERT_NE(file, nullptr);
    char line[256] = {};
    const bool read = std::fgets(line, sizeof(line), file) != nullptr;
    std::fclose(file);
    EXPECT_TRUE(read);
    EXPECT_NE(std::string(line).find("desync at tick " + std::to_string(corrupt_at)),
              std::string::npos)
        << line;
    report_stored = true;
  }
  EXPECT_TRUE(report_stored) << "no desync report stored";

  // The replay verifies to its last tick.
  const auto verify_started = std::chrono::steady_clock::now();
  const replay::VerifyReport verified = replay::verify_replay(replay_path);
  const double verify_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - verify_started).count();
  std::printf("verify: %llu ticks, %llu keyframes in %.1f s\n",
              static_cast<unsigned long long>(verified.ticks_verified),
              static_cast<unsigned long long>(verified.keyframes_verified), verify_s);
  EXPECT_TRUE(verified.ok()) << "first divergent tick "
                             << verified.first_divergent_tick.value_or(kNoTick) << "; "
                             << verified.error.value_or("") << verified.framing_error.value_or("");
  EXPECT_EQ(verified.ticks_verified, static_cast<uint64_t>(ticks));
  EXPECT_TRUE(verified.ended_cleanly);

  // Every keyframe loads into a fresh simulation and reproduces the
  // checksum recorded for its tick.
  auto reader = replay::ReplayReader::open(replay_path);
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  std::map<Tick, uint64_t> checksums;
  uint64_t keyframes = 0;
  ArenaCheck arena;
  std::string previous_keyframe;  // to find the exact tick of the first escape
  std::vector<std::vector<rwd::PlayerInput>> inputs_since;
  for (;;) {
    auto record = reader->next();
    ASSERT_TRUE(record.ok()) << record.status().message();
    if (!record->has_value()) break;
    const v1::ReplayRecord& r = **record;
    if (r.has_tick()) {
      checksums[r.tick().tick()] = r.tick().checksum();
      if (arena.first_escape_tick == kNoTick) {
        inputs_since.emplace_back();
        for (const v1::Input& in : r.tick().inputs()) {
          auto input = proto::from_wire(in);
          ASSERT_TRUE(input.ok());
          inputs_since.back().push_back(*input);
        }
      }
    }
    if (!r.has_keyframe()) continue;
    const Tick tick = r.keyframe().tick();
    auto sim = load_state(config.match.seed, r.keyframe().state());
    ASSERT_TRUE(sim.ok()) << "keyframe after tick " << tick << ": " << sim.status().message();
    EXPECT_EQ((*sim)->tick(), tick + 1);
    if (tick != kNoTick) {
      ASSERT_TRUE(checksums.count(tick));
      EXPECT_EQ((*sim)->checksum(), checksums[tick]) << "keyframe after tick " << tick;
    }
    check_keyframe(**sim, arena);
    ++keyframes;
    if (arena.first_escape_tick == kNoTick && arena.keyframes_with_escapes > 0) {
      // Step from the keyframe before with the recorded inputs to the tick
      // the first pusher crossed out.
      auto step = load_state(config.match.seed, previous_keyframe);
      ASSERT_TRUE(step.ok());
      for (const auto& inputs : inputs_since) {
        const Tick t = (*step)->tick();
        EXPECT_TRUE((*step)->step(inputs).ok());
        uint32_t player = 0;
        if (count_outside(**step, &player) > 0) {
          arena.first_escape_tick = t;
          arena.first_escape_player = player;
          arena.first_escape_position =
              world3d(**step).position(crates_state(**step).pushers[player]);
          break;
        }
      }
      ASSERT_NE(arena.first_escape_tick, kNoTick);
    }
    previous_keyframe = r.keyframe().state();
    inputs_since.clear();
  }
  EXPECT_EQ(keyframes, static_cast<uint64_t>(ticks / 300 + 1));
  std::printf("arena: at most %u pushers piled in one corner; ", arena.most_in_one_corner);
  if (arena.first_escape_tick == kNoTick) {
    std::printf("no pusher left the arena\n");
  } else {
    std::printf(
        "pushers outside the arena in %u of %llu keyframes (at most %u at once); the first, "
        "player %u, left at tick %d (at %.2f %.2f %.2f after it)\n",
        arena.keyframes_with_escapes, static_cast<unsigned long long>(keyframes),
        arena.most_outside, arena.first_escape_player, arena.first_escape_tick,
        arena.first_escape_position.x, arena.first_escape_position.y,
        arena.first_escape_position.z);
  }
}

}  // namespace
}  // namespace rwd::test
