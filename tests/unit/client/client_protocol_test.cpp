// SPDX-License-Identifier: MIT
// ClientProtocol with no socket and no clock: every datagram it receives is
// made by the server's codec (fake_server.h) and every time is given, so
// each step of join, lobby, final ticks, desync, resync and the end of the
// match is checked exactly (inputs and acknowledgements:
// client_inputs_test.cpp; the harness: client_protocol_harness.h).
#include "rewind/client/client_protocol.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <map>

#include "client_protocol_harness.h"
#include "fake_server.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/chunked_transfer.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"

namespace rwd::test {
namespace {

TEST(ClientProtocol, JoinsWaitsInTheLobbyAndStarts) {
  Harness h;
  h.protocol.connect(h.now);
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kJoining);
  auto out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(out[0].has_join_request());
  EXPECT_EQ(out[0].join_request().nonce(), kNonce);
  EXPECT_EQ(out[0].join_request().game(), "crates");

  // Unanswered, the request is resent every 250 ms and not more often.
  h.advance(std::chrono::milliseconds(100));
  EXPECT_TRUE(h.sent().empty());
  h.advance(std::chrono::milliseconds(150));
  out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_join_request());

  // Another join's answer changes nothing.
  h.deliver(h.server.join_accept(kNonce + 1, 0, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kJoining);
  h.deliver(h.server.join_accept(kNonce, 1, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kLobby);
  EXPECT_EQ(h.protocol.player(), 1u);
  EXPECT_EQ(types_of(h.events()), std::vector<ClientEventType>{ClientEventType::kJoined});
  ASSERT_NE(h.protocol.simulation(), nullptr);

  // The lobby pings the server; no inputs before the start.
  h.advance(std::chrono::milliseconds(10));
  out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_ping());
  EXPECT_EQ(h.client_tick(), 0);

  h.deliver(h.server.match_start(0, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kRunning);
  const auto events = h.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ClientEventType::kMatchStarted);
}

// A tokenless server answers nothing before the client's address has
// echoed its cookie: the client asks with a padded Hello, joins with the
// cookie at once, and asks again before the cookie grows too old.
TEST(ClientProtocol, TokenlessJoinFetchesAnAddressCookieFirst) {
  Harness h;
  h.answer_hellos = false;
  h.protocol.connect(h.now);
  EXPECT_TRUE(h.sent().empty());
  EXPECT_EQ(h.hellos, 1u);
  h.advance(std::chrono::milliseconds(250));
  EXPECT_TRUE(h.sent().empty());
  EXPECT_EQ(h.hellos, 2u);  // unanswered: asked again, nothing else sent

  h.deliver(h.cookie_reply);
  auto datagram = h.protocol.next_datagram();
  ASSERT_TRUE(datagram.has_value());
  ASSERT_EQ(net::cookie_packet_kind(*datagram), net::CookiePacket::kJoin);
  EXPECT_TRUE(std::equal(h.cookie_reply.begin() + 1, h.cookie_reply.end(), datagram->begin() + 1));
  auto join = net::decode_envelope(datagram->subspan(net::kJoinOverhead));
  ASSERT_TRUE(join.ok());
  EXPECT_EQ(join->join_request().nonce(), kNonce);
  // A second cookie (the answer to the resent Hello) sends nothing more.
  h.deliver(h.cookie_reply);
  EXPECT_FALSE(h.protocol.next_datagram().has_value());
  // Unanswered, the join is resent with the same cookie...
  h.advance(std::chrono::milliseconds(250));
  auto out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_join_request());
  // ... until the cookie is 3 s old: then a fresh one is asked for.
  for (int i = 0; i < 11; ++i) h.advance(std::chrono::milliseconds(250));
  (void)h.sent();
  EXPECT_EQ(h.hellos, 3u);

  // Joined, a cookie is nobody's business.
  h.answer_hellos = true;
  h.advance(std::chrono::milliseconds(250));
  (void)h.sent();
  h.deliver(h.server.join_accept(kNonce, 0, h.now));
  ASSERT_EQ(h.protocol.phase(), ClientPhase::kLobby);
  const uint64_t rejected = h.protocol.stats().packets_rejected;
  h.deliver(h.cookie_reply);
  EXPECT_EQ(h.protocol.stats().packets_rejected, rejected + 1);
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kLobby);
}

TEST(ClientProtocol, JoinRejectEndsTheSessionAndSilenceTimesItOut) {
  Harness rejected;
  rejected.protocol.connect(rejected.now);
  rejected.deliver(rejected.server.join_reject(kNonce + 1, "not yours"));
  EXPECT_EQ(rejected.protocol.phase(), ClientPhase::kJoining);
  rejected.deliver(rejected.server.join_reject(kNonce, "match full"));
  EXPECT_EQ(rejected.protocol.phase(), ClientPhase::kEnded);
  const auto events = rejected.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ClientEventType::kRejected);
  EXPECT_EQ(events[0].reason, "match full");

  Harness silent;
  silent.join_and_start();
  silent.advance(std::chrono::milliseconds(4900));
  EXPECT_EQ(silent.protocol.phase(), ClientPhase::kRunning);
  silent.advance(std::chrono::milliseconds(200));
  EXPECT_EQ(silent.protocol.phase(), ClientPhase::kEnded);
  ASSERT_FALSE(silent.events().empty());
}

TEST(ClientProtocol, VerifiesFinalTicksInOrderEvenWhenTheyArriveOutOfOrder) {
  Harness h;
  h.join_and_start();
  h.run(12);
  ASSERT_GE(h.client_tick(), 10);
  // Ticks 5..9 first: held until 0..4 arrive.
  h.deliver(h.server.final_ticks(5, 9, 9, h.now));
  h.advance(std::chrono::microseconds(0));
  EXPECT_TRUE(h.events().empty());
  h.deliver(h.server.final_ticks(0, 4, 9, h.now));
  h.advance(std::chrono::microseconds(0));
  const auto events = h.events();
  ASSERT_EQ(events.size(), 10u);
  for (Tick t = 0; t < 10; ++t) {
    EXPECT_EQ(events[t].type, ClientEventType::kFinalTick);
    EXPECT_EQ(events[t].tick, t);
    EXPECT_EQ(events[t].local_checksum, h.server.checksum_after(t));
    EXPECT_EQ(events[t].server_checksum, h.server.checksum_after(t));
  }
  EXPECT_EQ(h.protocol.stats().final_ticks_verified, 10u);
  EXPECT_EQ(h.protocol.stats().last_final_tick, 9);
  EXPECT_EQ(h.protocol.stats().desyncs, 0u);
}

TEST(ClientProtocol, RelayedInputsRollThePredictionBack) {
  Harness h;
  h.join_and_start();
  for (int i = 0; i < 10; ++i) h.advance(kTick);
  const Tick simulated = h.client_tick();
  // Player 1 really pushed right from tick 0; we predicted it idle.
  const rwd::PlayerInput push = rwd::stick_input(700, -300, 1);
  while (h.server.next_tick() < simulated) h.server.step({own_input(h.server.next_tick()), push});
  FakeServer::Relayed run{1, 0,
                          std::vector<rwd::PlayerInput>(static_cast<size_t>(simulated), push)};
  h.deliver(h.server.final_ticks(0, -1, 0, h.now, std::nullopt, {run}));
  h.advance(kTick);  // the next step re-simulates first
  EXPECT_GE(h.protocol.stats().rollbacks, 1u);
  EXPECT_EQ(h.protocol.rollback()->used_input(1, simulated - 1), push);
  EXPECT_EQ(h.protocol.rollback()->checksum_after(simulated - 1),
            h.server.checksum_after(simulated - 1));
}

TEST(ClientProtocol, WrongChecksumIsReportedWithTheStateAndResyncLoadsFromChunks) {
  Harness h;
  h.join_and_start();
  h.run(12);
  h.deliver(h.server.final_ticks(0, 5, 11, h.now, std::make_pair(Tick{5}, uint64_t{0xBAD})));
  h.advance(std::chrono::microseconds(0));
  auto events = h.events();
  ASSERT_EQ(events.size(), 6u);
  EXPECT_EQ(events[4].type, ClientEventType::kFinalTick);
  ASSERT_EQ(events[5].type, ClientEventType::kDesync);
  EXPECT_EQ(events[5].tick, 5);
  EXPECT_EQ(events[5].server_checksum, 0xBADu);
  EXPECT_EQ(events[5].local_checksum, h.server.checksum_after(5));

  // The report carries our state after tick 5, in chunks the server's
  // assembler takes.
  net::ChunkAssembler assembler(net::kDesyncChunkLimits);
  size_t reports = 0;
  for (const v1::Envelope& e : h.sent()) {
    if (!e.has_desync_report()) continue;
    ++reports;
    const v1::DesyncReport& r = e.desync_report();
    EXPECT_EQ(r.tick(), 5);
    EXPECT_EQ(r.client_checksum(), h.server.checksum_after(5));
    const net::ChunkHeader header{
        r.report_id(), r.chunk_index(), r.chunk_count(), r.total_size(), {}};
    EXPECT_NE(assembler.add(header,
                            {reinterpret_cast<const uint8_t*>(r.chunk().data()), r.chunk().size()}),
              net::ChunkResult::kRejected);
  }
  ASSERT_GT(reports, 1u) << "a crates state should take more than one chunk";
  ASSERT_TRUE(assembler.complete());
  EXPECT_EQ(std::vector<uint8_t>(assembler.blob().begin(), assembler.blob().end()),
            h.server.state_at(6));
  EXPECT_EQ(h.protocol.stats().desyncs, 1u);

  // While waiting, final ticks are not applied.
  h.run(2);
  h.deliver(h.server.final_ticks(6, 8, 11, h.now));
  h.advance(std::chrono::microseconds(0));
  EXPECT_TRUE(h.events().empty());
  (void)h.sent();

  // The snapshot at tick 6, its chunks reversed, duplicated and mixed with
  // a chunk of the wrong length: it loads only once every chunk is in.
  auto chunks = h.server.resync_chunks(7, 6, h.now);
  ASSERT_GT(chunks.size(), 1u);
  const uint64_t rejected_before = h.protocol.stats().packets_rejected;
  {
    v1::Envelope bad;
    v1::ResyncChunk* c = bad.mutable_resync_chunk();
    c->set_snapshot_id(7);
    c->set_tick(6);
    c->set_checksum(h.server.checksum_at(6));
    c->set_chunk_index(0);
    c->set_chunk_count(static_cast<uint32_t>(chunks.size()));
    c->set_total_size(static_cast<uint32_t>(h.server.state_at(6).size()));
    c->set_chunk("short");
    h.deliver(h.server.encode(bad, h.now));
  }
  EXPECT_EQ(h.protocol.stats().packets_rejected, rejected_before + 1);
  for (size_t i = chunks.size(); i-- > 1;) {
    h.deliver(chunks[i]);
    h.deliver(chunks[i]);  // a duplicate datagram: dropped by sequence
  }
  EXPECT_TRUE(h.events().empty());
  h.deliver(chunks[0]);
  events = h.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ClientEventType::kResynced);
  EXPECT_EQ(events[0].tick, 6);
  EXPECT_EQ(events[0].local_checksum, h.server.checksum_at(6));
  EXPECT_EQ(events[0].server_checksum, h.server.checksum_at(6));
  EXPECT_EQ(h.protocol.stats().resyncs, 1u);
  // Ticks 0-4 verified; tick 5 (the desynced one) passed over by the
  // snapshot of tick 6.
  EXPECT_EQ(h.protocol.stats().final_ticks_verified, 5u);
  EXPECT_EQ(h.protocol.stats().final_ticks_resynced, 1u);

  // Back in step: the final ticks from 6 on verify.
  h.run(4);
  h.deliver(h.server.final_ticks(6, 11, 11, h.now));
  h.advance(std::chrono::microseconds(0));
  events = h.events();
  ASSERT_EQ(events.size(), 6u);
  for (const ClientEvent& e : events) {
    EXPECT_EQ(e.type, ClientEventType::kFinalTick);
    EXPECT_EQ(e.local_checksum, e.server_checksum);
  }
  EXPECT_EQ(h.protocol.stats().last_final_tick, 11);
}

TEST(ClientProtocol, SnapshotThatDoesNotLoadIsRefusedByName) {
  Harness h;
  h.join_and_start();
  h.run(12);
  h.deliver(h.server.final_ticks(0, 5, 11, h.now, std::make_pair(Tick{5}, uint64_t{1})));
  h.advance(std::chrono::microseconds(0));
  (void)h.sent();
  (void)h.events();
  // Right bytes, wrong checksum: it must not replace anything.
  auto chunks = h.server.resync_chunks(3, 6, h.now);
  const uint64_t local_before = h.protocol.simulation()->checksum();
  for (auto& c : chunks) {
    auto envelope = net::decode_envelope(c);
    ASSERT_TRUE(envelope.ok());
    envelope->mutable_resync_chunk()->set_checksum(0xDEAD);
    h.deliver(h.server.encode(*envelope, h.now));
  }
  auto events = h.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ClientEventType::kResyncRefused);
  EXPECT_EQ(h.protocol.simulation()->checksum(), local_before);
  bool named = false;
  for (const v1::Envelope& e : h.sent()) {
    named |= e.has_resync_request() && e.resync_request().refused_snapshot_id() == 3;
  }
  EXPECT_TRUE(named);
  // The next snapshot loads.
  for (const auto& c : h.server.resync_chunks(4, 6, h.now)) h.deliver(c);
  events = h.events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, ClientEventType::kResynced);
}

TEST(ClientProtocol, GarbageDuplicatesAndStrangersLeaveStateIntact) {
  Harness h;
  h.join_and_start();
  h.run(8);
  const auto finals = h.server.final_ticks(0, 3, 7, h.now);
  h.deliver(finals);
  h.advance(std::chrono::microseconds(0));
  ASSERT_EQ(h.events().size(), 4u);
  (void)h.sent();

  const client::ClientStats before = h.protocol.stats();
  const Tick tick_before = h.client_tick();
  FakeMatch other;
  other.connection_id = 99;
  FakeServer stranger(other);
  const std::vector<uint8_t> garbage{0x08, 0x01, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  std::vector<uint8_t> truncated = finals;
  truncated.resize(finals.size() / 2);
  const std::vector<uint8_t> empty;
  h.deliver(garbage);
  h.deliver(truncated);
  h.deliver(empty);
  h.deliver(stranger.match_end(3, h.now));            // another connection's
  h.deliver(stranger.disconnect("bye", h.now));       // ... not ours to obey
  h.deliver(finals);                                  // a duplicate datagram
  h.deliver(h.server.join_accept(kNonce, 1, h.now));  // a late copy of the join's answer
  h.deliver(h.server.match_start(500, h.now));        // not in the lobby any more
  h.advance(std::chrono::microseconds(0));

  const client::ClientStats after = h.protocol.stats();
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kRunning);
  EXPECT_EQ(h.protocol.player(), 0u);
  EXPECT_EQ(h.client_tick(), tick_before);
  EXPECT_TRUE(h.events().empty());
  EXPECT_EQ(after.final_ticks_verified, before.final_ticks_verified);
  EXPECT_EQ(after.last_final_tick, 3);
  EXPECT_EQ(after.packets_received, before.packets_received + 8);
  // Garbage, truncated, empty, two strangers and the late JoinAccept.
  EXPECT_EQ(after.packets_rejected, before.packets_rejected + 6);
}

TEST(ClientProtocol, MatchEndWaitsForTheLastFinalTickThenSaysGoodbye) {
  Harness h;
  h.start_ending();
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kEnding);
  (void)h.sent();
  h.deliver(h.server.final_ticks(6, 9, 11, h.now));
  h.advance(std::chrono::microseconds(0));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kEnded);
  const auto events = h.events();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().type, ClientEventType::kMatchEnded);
  EXPECT_EQ(events.back().tick, 9);
  EXPECT_EQ(h.protocol.stats().last_final_tick, 9);
  auto out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_disconnect());
  // A MatchEnd resent (our goodbye was lost) gets another goodbye.
  h.deliver(h.server.match_end(9, h.now));
  out = h.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_disconnect());
}

TEST(ClientProtocol, SecureHandshakeThenEverythingSealed) {
  const net::Key server_key = net::generate_key();
  const int64_t unix_now = 1'900'000'000;
  const auto token = net::make_connect_token(server_key, "m1", 0, 77, unix_now + 60, unix_now);
  ASSERT_TRUE(token.ok());
  ClientConfig config;
  config.connect_token = net::write_connect_token(*token);
  Harness h(config);
  net::ServerGate gate(server_key, net::generate_key(), net::connect_match_tag("m1"));
  net::PeerAddress from;
  from.port = 5000;

  h.protocol.connect(h.now);
  auto request = h.protocol.next_datagram();
  ASSERT_TRUE(request.has_value());
  std::vector<uint8_t> challenge;
  ASSERT_TRUE(gate.on_request(*request, from, unix_now, challenge).ok());
  EXPECT_FALSE(h.protocol.next_datagram().has_value()) << "nothing goes out in the clear";

  h.deliver(challenge);
  auto response = h.protocol.next_datagram();
  ASSERT_TRUE(response.has_value());
  auto connected = gate.on_response(*response, from, unix_now);
  ASSERT_TRUE(connected.ok()) << connected.status().message();
  h.server.use_secure_session(std::move(connected->session));

  // The join follows on the next update, sealed (with the response again,
  // until the server is heard).
  h.advance(std::chrono::milliseconds(1));
  std::vector<uint8_t> response_again, join;
  while (auto d = h.protocol.next_datagram()) {
    (net::secure_packet_kind(*d) == net::SecurePacket::kPayload ? join : response_again)
        .assign(d->begin(), d->end());
  }
  ASSERT_FALSE(join.empty());
  EXPECT_FALSE(response_again.empty());
  auto envelope = h.server.read(join, h.now);
  ASSERT_TRUE(envelope.has_value());
  ASSERT_TRUE(envelope->has_join_request());

  h.deliver(h.server.join_accept(kNonce, 0, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kLobby);
  // An unsealed datagram is refused even when it is well formed.
  FakeServer clear{FakeMatch{}};
  const uint64_t rejected = h.protocol.stats().packets_rejected;
  h.deliver(clear.match_start(0, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kLobby);
  EXPECT_EQ(h.protocol.stats().packets_rejected, rejected + 1);
  h.deliver(h.server.match_start(0, h.now));
  EXPECT_EQ(h.protocol.phase(), ClientPhase::kRunning);
}

TEST(ClientProtocol, RefusesBadConfigurationAndBoundsItsQueue) {
  ClientConfig shallow;
  shallow.snapshot_ticks = 8;
  EXPECT_EQ(ClientProtocol::create(shallow, 1).status().code(), ErrorCode::kInvalidArgument);
  ClientConfig bad_token;
  bad_token.connect_token = {1, 2, 3};
  EXPECT_EQ(ClientProtocol::create(bad_token, 1).status().code(), ErrorCode::kInvalidArgument);

  // A caller that never drains: the lobby's pings stop queueing at the bound.
  ClientConfig patient;
  patient.server_timeout_s = 1e6;
  Harness h(patient);
  h.join();
  for (size_t i = 0; i < ClientProtocol::kMaxQueuedDatagrams + 10; ++i) {
    h.advance(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(h.protocol.stats().datagrams_dropped, 10u);
  size_t queued = 0;
  while (h.protocol.next_datagram()) ++queued;
  EXPECT_EQ(queued, ClientProtocol::kMaxQueuedDatagrams);
}

}  // namespace
}  // namespace rwd::test
