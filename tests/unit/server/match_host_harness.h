// SPDX-License-Identifier: MIT
#pragma once
// MatchHost driven without sockets: scripted clients build envelopes by
// hand, and the clock is whatever the test says. Shared by the match host's
// test files.
#include "rewind/server/match_host.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "rewind/game/simulation.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"
#include "rewind/replay/engine_identity.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_verifier.h"
#include "rewind/sim/version.h"
#include "rewind/sim/world3d.h"

namespace rwd::server::host_test {

using asio::ip::make_address;

struct Outbox {
  std::map<Endpoint, std::vector<v1::Envelope>> received;
  void deliver(const Endpoint& to, std::span<const uint8_t> bytes) {
    auto decoded = net::decode_envelope(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    received[to].push_back(*decoded);
  }
};

struct FakeClient {
  Endpoint endpoint;
  uint64_t connection_id = 0;
  uint32_t player = 0;
  uint32_t sequence = 1;
};

inline rwd::PlayerInput scripted(uint32_t player, Tick tick) {
  return rwd::stick_input(static_cast<int16_t>(((tick / 5 + player) % 3 - 1) * 900),
                          static_cast<int16_t>(((tick / 7 + player) % 3 - 1) * 700));
}

class HostHarness {
 public:
  explicit HostHarness(MatchConfig config, MatchEnvironment env = MatchEnvironment::os()) {
    now_ = net::SteadyClock::now();
    auto host = MatchHost::create(
        config, [this](const Endpoint& to, std::span<const uint8_t> b) { outbox_.deliver(to, b); },
        now_, std::move(env));
    EXPECT_TRUE(host.ok()) << host.status().message();
    host_ = std::move(*host);
  }

  std::vector<uint8_t> encode(v1::Envelope envelope) {
    envelope.set_protocol_version(net::kProtocolVersion);
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(net::encode_envelope(envelope, bytes).ok());
    return bytes;
  }
  void raw(const Endpoint& from, std::span<const uint8_t> bytes) {
    host_->on_datagram(bytes, from, now_);
  }
  /// As from an address that answered a cookie (TokenlessGateway): how a
  /// tokenless join reaches the host.
  void admitted(const Endpoint& from, std::span<const uint8_t> bytes) {
    const Admission proven;
    host_->on_datagram(bytes, from, now_, &proven);
  }
  void send(FakeClient& client, v1::Envelope envelope) {
    envelope.set_connection_id(client.connection_id);
    envelope.set_sequence(client.sequence++);
    raw(client.endpoint, encode(envelope));
  }
  FakeClient join(uint16_t port) {
    FakeClient client;
    client.endpoint = Endpoint(make_address("127.0.0.1"), port);
    v1::Envelope envelope;
    envelope.mutable_join_request()->set_game(host_->config().game);
    envelope.mutable_join_request()->set_nonce(port);
    admitted(client.endpoint, encode(envelope));
    for (const v1::Envelope& answer : outbox_.received[client.endpoint]) {
      if (answer.has_join_accept()) {
        client.connection_id = answer.join_accept().connection_id();
        client.player = answer.join_accept().player();
      }
    }
    EXPECT_NE(client.connection_id, 0u);
    return client;
  }
  void send_input(FakeClient& client, Tick tick, rwd::PlayerInput input, uint32_t as_player) {
    v1::Envelope envelope;
    v1::InputFrame* frame = envelope.mutable_input_frame();
    frame->set_player(as_player);
    frame->set_first_tick(tick);
    *frame->add_inputs() = proto::to_wire(input);
    send(client, envelope);
  }
  void tick() {
    now_ += std::chrono::milliseconds(16);
    host_->on_tick(now_);
  }
  /// Lets `by` pass, then ticks once.
  void wait(std::chrono::milliseconds by) {
    now_ += by;
    host_->on_tick(now_);
  }
  /// Both players send on time for `ticks` ticks, acknowledging nothing.
  void play_on_time(FakeClient& a, FakeClient& b, Tick ticks) {
    for (Tick i = 0; i < ticks; ++i) {
      const Tick t = host_->current_tick();
      send_input(a, t, scripted(a.player, t), a.player);
      send_input(b, t, scripted(b.player, t), b.player);
      tick();
    }
  }
  void request_resync(FakeClient& client, uint32_t refused_id = 0) {
    v1::Envelope request;
    request.mutable_resync_request()->set_desync_tick(0);
    request.mutable_resync_request()->set_refused_snapshot_id(refused_id);
    if (refused_id != 0) request.mutable_resync_request()->set_refused_reason("test refusal");
    send(client, request);
  }
  void acknowledge_finals(FakeClient& client, Tick through) {
    v1::Envelope ack;
    ack.mutable_input_frame()->set_player(client.player);
    ack.mutable_input_frame()->set_first_tick(host_->current_tick());
    ack.mutable_input_frame()->set_last_final_tick_seen(through);
    send(client, ack);
  }
  MatchHost& host() { return *host_; }
  Outbox& outbox() { return outbox_; }

 private:
  Outbox outbox_;
  TimePoint now_;
  std::unique_ptr<MatchHost> host_;
};

inline MatchConfig test_config() {
  MatchConfig config;
  config.players = 2;
  config.window_ticks = 4;
  config.keyframe_interval = 0;
  config.start_delay_s = 0;
  return config;
}

// Plays `ticks` ticks with both players sending on time (player 1's input
// two ticks late, to exercise rollback); `attack` runs before every tick.
inline std::map<Tick, uint64_t> play(
    HostHarness& h, Tick ticks,
    const std::function<void(HostHarness&, FakeClient&, FakeClient&, Tick)>& attack) {
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kRunning);
  std::map<Tick, uint64_t> finals;
  for (Tick t = 0; t < ticks; ++t) {
    h.send_input(a, t, scripted(a.player, t), a.player);
    if (t >= 2) h.send_input(b, t - 2, scripted(b.player, t - 2), b.player);
    if (attack) attack(h, a, b, t);
    h.tick();
    for (const v1::FinalTick& f : h.host().recent_finals()) finals[f.tick()] = f.checksum();
  }
  return finals;
}

}  // namespace rwd::server::host_test
