// SPDX-License-Identifier: MIT
// The client SDK session against the real MatchHost, detached from sockets
// and driven on a simulated clock (tests/support/headless_match.h).
#include "rewind/client/client_session.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "headless_match.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/replay/replay_verifier.h"

namespace rwd::test {
namespace {

using client::ClientEventType;

HeadlessConfig small_match(Tick ticks) {
  HeadlessConfig config;
  config.match.players = 4;
  config.match.max_ticks = ticks;
  config.match.keyframe_interval = 60;
  config.sdk_clients = 2;
  config.loss = 0.05;
  config.seed = 7;
  config.inputs = [](uint32_t player, Tick tick) {
    return aggressive_crates_input(3, player, tick);
  };
  return config;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / (name + "_" + std::to_string(::getpid())))
      .string();
}

TEST(ClientSession, DetachedSessionsPlayAMatchUnderLossAndVerifyEveryFinalTick) {
  auto match = HeadlessMatch::create(small_match(600));
  ASSERT_TRUE(match.ok()) << match.status().message();
  const HeadlessResult result = (*match)->run();
  ASSERT_FALSE(result.timed_out);
  EXPECT_EQ(result.server.ticks_final, 600);
  EXPECT_EQ(result.server.players_joined, 4u);
  EXPECT_EQ(result.scripted_peers_finished, 2u);
  EXPECT_GT(result.server.rollbacks + result.clients[0].stats.rollbacks, 0u)
      << "loss and prediction should have caused rollbacks";
  for (const SdkClientResult& c : result.clients) {
    EXPECT_TRUE(c.ended);
    EXPECT_EQ(c.stats.desyncs, 0u);
    EXPECT_EQ(c.stats.last_final_tick, 599);
    EXPECT_EQ(c.final_tick_events, 600u);
  }
}

TEST(ClientSession, RefusedSnapshotIsReportedAndAnotherOneLoads) {
  const std::string replay = temp_path("refused_snapshot.rwr");
  HeadlessConfig config = small_match(900);
  config.loss = 0.0;  // exactly one damaged snapshot, nothing else in the way
  config.match.replay_path = replay;
  config.corrupt_client = 0;
  config.corrupt_at_tick = 300;
  auto match = HeadlessMatch::create(config);
  ASSERT_TRUE(match.ok()) << match.status().message();
  // The first snapshot the corrupted client gets is damaged on the way (its
  // magic bytes); every later one arrives intact.
  uint32_t damaged_id = 0;
  (*match)->set_link_filter([&](Direction direction, uint32_t peer, std::vector<uint8_t>& bytes) {
    if (direction != Direction::kToClient || peer != 0) return true;
    auto envelope = net::decode_envelope(bytes);
    if (!envelope.ok() || !envelope->has_resync_chunk()) return true;
    v1::ResyncChunk* chunk = envelope->mutable_resync_chunk();
    if (damaged_id == 0) damaged_id = chunk->snapshot_id();
    if (chunk->snapshot_id() != damaged_id || chunk->chunk_index() != 0) return true;
    chunk->mutable_chunk()->replace(0, 5, "XXXXX");
    EXPECT_TRUE(net::encode_envelope(*envelope, bytes).ok());
    return true;
  });
  const HeadlessResult result = (*match)->run();
  ASSERT_FALSE(result.timed_out);
  ASSERT_NE(damaged_id, 0u);

  const SdkClientResult& corrupted = result.clients[0];
  std::vector<ClientEventType> sequence;
  for (const client::ClientEvent& e : corrupted.events) {
    if (e.type == ClientEventType::kDesync || e.type == ClientEventType::kResyncRefused ||
        e.type == ClientEventType::kResynced) {
      sequence.push_back(e.type);
    }
    if (e.type == ClientEventType::kDesync) {
      EXPECT_EQ(e.tick, 300);
    }
    if (e.type == ClientEventType::kResyncRefused) {
      EXPECT_NE(e.reason.find("bad magic"), std::string::npos) << e.reason;
    }
  }
  EXPECT_EQ(sequence,
            (std::vector<ClientEventType>{ClientEventType::kDesync, ClientEventType::kResyncRefused,
                                          ClientEventType::kResynced}));
  EXPECT_EQ(corrupted.stats.resyncs_refused, 1u);
  EXPECT_EQ(corrupted.stats.resyncs, 1u);
  // Back in step after the resync: every later final tick verified.
  EXPECT_TRUE(corrupted.ended);
  EXPECT_EQ(corrupted.stats.last_final_tick, 899);
  EXPECT_EQ(result.clients[1].stats.desyncs, 0u);

  EXPECT_EQ(result.server.resyncs_refused, 1u);
  EXPECT_EQ(result.server.resyncs_sent, 2u);
  EXPECT_EQ(result.server.resync_snapshot_failures, 0u);
  EXPECT_EQ(result.server.desync_reports, 1u);

  const replay::VerifyReport verified = replay::verify_replay(replay);
  EXPECT_TRUE(verified.ok()) << verified.error.value_or("") << verified.framing_error.value_or("");
  EXPECT_EQ(verified.ticks_verified, 900u);
  std::filesystem::remove(replay);
}

TEST(ClientSession, DetachedSessionRefusesWhatNeedsASocket) {
  client::ClientConfig config;
  config.faults = net::FaultConfig{};
  auto with_faults =
      client::ClientSession::create_detached(config, [](std::span<const uint8_t>) {});
  ASSERT_FALSE(with_faults.ok());
  EXPECT_EQ(with_faults.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(client::ClientSession::create_detached({}, nullptr).ok());
  client::ClientConfig shallow;
  shallow.snapshot_ticks = 4;
  EXPECT_FALSE(
      client::ClientSession::create_detached(shallow, [](std::span<const uint8_t>) {}).ok());
  auto fine = client::ClientSession::create_detached({}, [](std::span<const uint8_t>) {});
  ASSERT_TRUE(fine.ok());
  EXPECT_EQ((*fine)->local_port(), 0);
}

}  // namespace
}  // namespace rwd::test
