// SPDX-License-Identifier: MIT
// DesyncRecovery with a bare RollbackSession and ServerChannel: the desync
// report (the state dump in chunks) sent a few times and then only as a
// request, a snapshot that does not load named in the requests until
// another comes, and one that loads replacing the session's state.
#include "desync_recovery.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/game/simulation.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

constexpr uint32_t kRecoveryPlayers = 2;

std::unique_ptr<game::Simulation> recovery_match() {
  auto sim = game::Simulation::create("crates", {kRecoveryPlayers, 3});
  if (!sim.ok()) throw std::runtime_error(sim.status().message());
  return std::move(*sim);
}

std::vector<rwd::PlayerInput> recovery_inputs(Tick tick) {
  return {rwd::stick_input(static_cast<int16_t>(tick * 20), 0),
          rwd::stick_input(0, static_cast<int16_t>(-tick * 30))};
}

std::vector<v1::Envelope> recovery_sent(ServerChannel& channel) {
  std::vector<v1::Envelope> out;
  while (auto datagram = channel.next_datagram()) {
    auto envelope = net::decode_envelope(*datagram);
    EXPECT_TRUE(envelope.ok());
    if (envelope.ok()) out.push_back(std::move(*envelope));
  }
  return out;
}

/// The snapshot `state` at `tick` as the server's ResyncChunk messages.
std::vector<v1::ResyncChunk> snapshot_chunks(uint32_t snapshot_id, Tick tick,
                                             const std::vector<uint8_t>& state, uint64_t checksum) {
  const Result<uint32_t> count = net::plan_chunks(state.size(), net::kResyncChunkLimits);
  if (!count.ok()) throw std::runtime_error(count.status().message());
  std::vector<v1::ResyncChunk> out(*count);
  for (uint32_t i = 0; i < *count; ++i) {
    const std::span<const uint8_t> part = net::chunk_at(state, i, net::kResyncChunkLimits);
    out[i].set_snapshot_id(snapshot_id);
    out[i].set_tick(tick);
    out[i].set_checksum(checksum);
    out[i].set_chunk_index(i);
    out[i].set_chunk_count(*count);
    out[i].set_total_size(static_cast<uint32_t>(state.size()));
    out[i].set_chunk(part.data(), part.size());
  }
  return out;
}

struct RecoveryRig {
  std::unique_ptr<net::RollbackSession> session;
  ServerChannel channel{64};
  DesyncRecovery recovery;
  net::TimePoint now = net::TimePoint{} + std::chrono::seconds(50);

  RecoveryRig() {
    channel.start(now);
    channel.set_connection_id(0xC0FFEE);  // as a JoinAccept sets it
    session = std::make_unique<net::RollbackSession>(recovery_match(), net::RollbackConfig{});
    for (Tick t = 0; t < 10; ++t) {
      const std::vector<rwd::PlayerInput> row = recovery_inputs(t);
      for (uint32_t p = 0; p < kRecoveryPlayers; ++p) (void)session->add_input(p, t, row[p]);
      EXPECT_TRUE(session->advance());
    }
  }
};

TEST(DesyncRecovery, ReportsTheStateAFewTimesThenOnlyAsks) {
  RecoveryRig rig;
  std::vector<uint8_t> state_after_4;
  ASSERT_TRUE(rig.session->serialize_state_at(5, state_after_4));

  rig.recovery.on_desync(*rig.session, 4, 0x1111, 0x2222, rig.channel, rig.now);
  EXPECT_TRUE(rig.recovery.awaiting());
  std::vector<uint8_t> reported;
  for (const v1::Envelope& e : recovery_sent(rig.channel)) {
    ASSERT_TRUE(e.has_desync_report());
    EXPECT_EQ(e.desync_report().tick(), 4);
    EXPECT_EQ(e.desync_report().client_checksum(), 0x1111u);
    EXPECT_EQ(e.desync_report().server_checksum(), 0x2222u);
    EXPECT_EQ(e.desync_report().total_size(), state_after_4.size());
    reported.insert(reported.end(), e.desync_report().chunk().begin(),
                    e.desync_report().chunk().end());
  }
  EXPECT_EQ(reported, state_after_4);

  // Not again before 500 ms; then the whole report twice more; then only a
  // short request naming the tick.
  rig.recovery.resend_if_due(rig.channel, rig.now + std::chrono::milliseconds(499));
  EXPECT_TRUE(recovery_sent(rig.channel).empty());
  for (int resend = 1; resend <= 3; ++resend) {
    rig.recovery.resend_if_due(rig.channel, rig.now + resend * std::chrono::milliseconds(500));
    const std::vector<v1::Envelope> sent = recovery_sent(rig.channel);
    ASSERT_FALSE(sent.empty());
    if (resend < 3) {
      EXPECT_TRUE(sent.front().has_desync_report()) << "resend " << resend;
    } else {
      ASSERT_EQ(sent.size(), 1u);
      ASSERT_TRUE(sent.front().has_resync_request());
      EXPECT_EQ(sent.front().resync_request().desync_tick(), 4);
    }
  }
}

TEST(DesyncRecovery, NamesARefusedSnapshotUntilOneLoads) {
  RecoveryRig rig;
  rig.recovery.request(rig.channel, rig.now);
  ASSERT_TRUE(rig.recovery.awaiting());
  (void)recovery_sent(rig.channel);

  // The server's state at the start of tick 8, from a match of its own.
  std::unique_ptr<game::Simulation> server = recovery_match();
  for (Tick t = 0; t < 8; ++t) ASSERT_TRUE(server->step(recovery_inputs(t)).ok());
  std::vector<uint8_t> state;
  server->serialize(state);
  const uint64_t checksum = server->checksum();

  // Snapshot 7 claims a checksum its state does not have: refused, and the
  // request says so.
  const std::vector<v1::ResyncChunk> bad = snapshot_chunks(7, 8, state, checksum ^ 1);
  DesyncRecovery::ChunkOutcome outcome;
  for (const v1::ResyncChunk& chunk : bad) {
    outcome = rig.recovery.on_chunk(*rig.session, chunk, kNoTick, kNoTick, rig.channel, rig.now);
  }
  EXPECT_EQ(outcome.outcome, DesyncRecovery::Outcome::kRefused);
  EXPECT_EQ(outcome.tick, 8);
  EXPECT_FALSE(outcome.reason.empty());
  EXPECT_TRUE(rig.recovery.awaiting());
  std::vector<v1::Envelope> sent = recovery_sent(rig.channel);
  ASSERT_EQ(sent.size(), 1u);
  ASSERT_TRUE(sent[0].has_resync_request());
  EXPECT_EQ(sent[0].resync_request().refused_snapshot_id(), 7u);
  // Its resends are ignored while the server has not heard.
  EXPECT_EQ(rig.recovery.on_chunk(*rig.session, bad.back(), kNoTick, kNoTick, rig.channel, rig.now)
                .outcome,
            DesyncRecovery::Outcome::kNone);

  // Snapshot 8 loads: the session's state is the server's, and nothing
  // more is asked.
  for (const v1::ResyncChunk& chunk : snapshot_chunks(8, 8, state, checksum)) {
    outcome = rig.recovery.on_chunk(*rig.session, chunk, kNoTick, kNoTick, rig.channel, rig.now);
  }
  EXPECT_EQ(outcome.outcome, DesyncRecovery::Outcome::kLoaded);
  EXPECT_EQ(outcome.tick, 8);
  EXPECT_EQ(outcome.checksum, checksum);
  EXPECT_FALSE(rig.recovery.awaiting());
  EXPECT_EQ(rig.session->current_tick(), 8);
  EXPECT_EQ(rig.session->simulation().checksum(), checksum);
  rig.recovery.resend_if_due(rig.channel, rig.now + std::chrono::seconds(5));
  EXPECT_TRUE(recovery_sent(rig.channel).empty());

  // A snapshot no later than what is now final is a stale duplicate.
  EXPECT_EQ(rig.recovery
                .on_chunk(*rig.session, snapshot_chunks(9, 7, state, checksum).front(), kNoTick,
                          kNoTick, rig.channel, rig.now)
                .outcome,
            DesyncRecovery::Outcome::kNone);
}

}  // namespace
}  // namespace rwd::client
