// SPDX-License-Identifier: MIT
#pragma once
// The client protocol's test harness: a ClientProtocol with no socket and no
// clock, a fake server (fake_server.h) that reads what it sends and makes
// what it receives with the server's codec, and time given by the test.
#include <chrono>
#include <map>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "fake_server.h"
#include "rewind/client/client_protocol.h"
#include "rewind/core/stick_input.h"
#include "rewind/net/address_cookie.h"

namespace rwd::test {

using client::ClientConfig;
using client::ClientEvent;
using client::ClientEventType;
using client::ClientPhase;
using client::ClientProtocol;
using net::TimePoint;

inline constexpr uint64_t kNonce = 0x5EED'0000'0000'0042ull;
inline constexpr auto kTick = std::chrono::microseconds(16'667);

inline rwd::PlayerInput own_input(Tick tick) {
  return rwd::stick_input(static_cast<int16_t>((tick * 37) % 2001 - 1000),
                          static_cast<int16_t>(tick % 7), static_cast<uint32_t>(tick % 3));
}

inline ClientProtocol make_protocol(const ClientConfig& config) {
  auto protocol = ClientProtocol::create(config, kNonce);
  if (!protocol.ok()) throw std::runtime_error(protocol.status().message());
  return std::move(*protocol);
}

struct Harness {
  explicit Harness(const ClientConfig& config = {}, const FakeMatch& match = {})
      : server(match), protocol(make_protocol(config)) {
    protocol.set_input_provider([this](Tick tick) {
      ++provided[tick];
      return own_input(tick);
    });
  }

  /// What the client queued, read by the server (undecodable ones fail).
  /// A tokenless client's Hello is answered with a cookie at once (unless
  /// answer_hellos is off) and counted, not returned.
  std::vector<v1::Envelope> sent() {
    std::vector<v1::Envelope> out;
    while (auto datagram = protocol.next_datagram()) {
      if (net::cookie_packet_kind(*datagram) == net::CookiePacket::kHello) {
        EXPECT_EQ(datagram->size(), net::kHelloBytes);
        ++hellos;
        if (answer_hellos) deliver(cookie_reply);
        continue;
      }
      auto envelope = server.read(*datagram, now);
      EXPECT_TRUE(envelope.has_value()) << "the client sent something the server cannot read";
      if (envelope) out.push_back(std::move(*envelope));
    }
    return out;
  }
  std::vector<ClientEvent> events() {
    std::vector<ClientEvent> out;
    ClientEvent event;
    while (protocol.poll_event(event)) out.push_back(event);
    return out;
  }
  void deliver(std::span<const uint8_t> bytes) { protocol.receive(bytes, now); }
  int advance(std::chrono::microseconds by) {
    now += by;
    return protocol.update(now);
  }
  Tick client_tick() const { return protocol.rollback()->current_tick(); }
  /// Steps the server through every tick the client has simulated, with
  /// the client's own inputs and `others` for the rest.
  void catch_up_server(rwd::PlayerInput others = {}) {
    while (server.next_tick() < client_tick()) {
      server.step({own_input(server.next_tick()), others});
    }
  }

  void join() {
    protocol.connect(now);
    const auto out = sent();
    ASSERT_EQ(out.size(), 1u);
    ASSERT_TRUE(out[0].has_join_request());
    EXPECT_EQ(out[0].join_request().nonce(), kNonce);
    deliver(server.join_accept(kNonce, 0, now));
    ASSERT_EQ(protocol.phase(), ClientPhase::kLobby);
  }
  void join_and_start() {
    join();
    deliver(server.match_start(0, now));
    ASSERT_EQ(protocol.phase(), ClientPhase::kRunning);
    (void)sent();
    (void)events();
  }
  /// Joins, runs 12 ticks, then the server sends final ticks 0..5 and ends
  /// the match at tick 9: the client is left ending, waiting for 6..9.
  void start_ending() {
    join_and_start();
    run(12);
    deliver(server.final_ticks(0, 5, 11, now));
    deliver(server.match_end(9, now));
    advance(std::chrono::microseconds(0));
  }
  /// Runs the client for `ticks` tick periods and the server alongside.
  void run(int ticks) {
    for (int i = 0; i < ticks; ++i) advance(kTick);
    catch_up_server();
  }

  FakeServer server;
  ClientProtocol protocol;
  TimePoint now = TimePoint{} + std::chrono::seconds(1000);
  std::map<Tick, int> provided;
  bool answer_hellos = true;
  size_t hellos = 0;
  const std::vector<uint8_t> cookie_reply = [] {
    std::vector<uint8_t> reply(net::kCookieReplyBytes, 0x5A);
    reply[0] = static_cast<uint8_t>(net::CookiePacket::kCookie);
    return reply;
  }();
};

inline std::vector<ClientEventType> types_of(const std::vector<ClientEvent>& events) {
  std::vector<ClientEventType> out;
  for (const ClientEvent& e : events) out.push_back(e.type);
  return out;
}

}  // namespace rwd::test
