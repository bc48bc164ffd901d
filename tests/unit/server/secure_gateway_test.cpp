// SPDX-License-Identifier: MIT
// A secure match host: clients connect through the SecureGateway with
// connect tokens and take the slots their tokens name; another client's
// token for a held slot cannot cut the holder off; a client restarted in the lobby takes
// its slot back from its new address (and the old address loses its
// session), and one restarted mid-match takes it back and is sent a
// snapshot; clear-text datagrams reach nothing and get no answer.
#include <gtest/gtest.h>

#include <algorithm>

#include <map>

#include "rewind/net/envelope_codec.h"
#include "rewind/server/match_host.h"
#include "rewind/server/secure_gateway.h"

namespace rwd::server {
namespace {

constexpr int64_t kNow = 1'800'000'000;

struct SecureClient {
  SecureClient(Endpoint at, const net::ConnectToken& token) : endpoint(at), handshake(token) {}
  Endpoint endpoint;
  net::ClientHandshake handshake;
  std::vector<v1::Envelope> inbox;
  uint64_t connection_id = 0;
  uint32_t player = 0;
};

class SecureMatch {
 public:
  explicit SecureMatch(uint32_t players) {
    MatchConfig config;
    config.players = players;
    config.match_id = "secure-test";
    config.secure = true;
    now_ = net::SteadyClock::now();
    gateway_ = std::make_unique<SecureGateway>(
        key_, config.match_id, players, [this](const Endpoint& to, std::span<const uint8_t> bytes) {
          wire_[to].emplace_back(bytes.begin(), bytes.end());
        });
    auto host = MatchHost::create(
        config, [this](const Endpoint& to, std::span<const uint8_t> b) { gateway_->send(to, b); },
        now_);
    EXPECT_TRUE(host.ok()) << host.status().message();
    host_ = std::move(*host);
  }

  net::ConnectToken token(uint32_t slot, uint64_t client_id) {
    return *net::make_connect_token(key_, "secure-test", slot, client_id, kNow + 60, kNow);
  }

  void to_server(const Endpoint& from, std::span<const uint8_t> bytes) {
    gateway_->on_datagram(
        bytes, from, unix_now_,
        [this](std::span<const uint8_t> env, const Endpoint& sender, const Admission& who) {
          host_->on_datagram(env, sender, now_, &who);
        });
  }

  // Handshake, then a JoinRequest; collects what the server answers.
  void connect_and_join(SecureClient& c) {
    to_server(c.endpoint, c.handshake.request());
    std::vector<uint8_t> response;
    ASSERT_EQ(wire_[c.endpoint].size(), 1u);
    ASSERT_TRUE(c.handshake.on_challenge(wire_[c.endpoint][0], response).ok());
    wire_[c.endpoint].clear();
    to_server(c.endpoint, response);
    v1::Envelope join;
    join.set_protocol_version(net::kProtocolVersion);
    join.mutable_join_request()->set_game("crates");
    join.mutable_join_request()->set_nonce(c.endpoint.port());
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(net::encode_envelope(join, bytes).ok());
    std::vector<uint8_t> sealed;
    c.handshake.session()->seal(bytes, sealed);
    to_server(c.endpoint, sealed);
    read(c);
  }

  void read(SecureClient& c) {
    for (const std::vector<uint8_t>& packet : wire_[c.endpoint]) {
      std::vector<uint8_t> plain;
      ASSERT_TRUE(c.handshake.session()->open(packet, plain).ok());
      auto envelope = net::decode_envelope(plain);
      ASSERT_TRUE(envelope.ok());
      if (envelope->has_join_accept()) {
        c.connection_id = envelope->join_accept().connection_id();
        c.player = envelope->join_accept().player();
      }
      c.inbox.push_back(*envelope);
    }
    wire_[c.endpoint].clear();
  }

  net::Key key_ = net::generate_key();
  TimePoint now_;
  int64_t unix_now_ = kNow;
  std::map<Endpoint, std::vector<std::vector<uint8_t>>> wire_;
  std::unique_ptr<SecureGateway> gateway_;
  std::unique_ptr<MatchHost> host_;
};

Endpoint at(uint16_t port) {
  return Endpoint(asio::ip::make_address("127.0.0.1"), port);
}

bool rejected(const SecureClient& c, const std::string& reason) {
  for (const v1::Envelope& e : c.inbox) {
    if (e.has_join_reject() && e.join_reject().reason().find(reason) != std::string::npos) {
      return true;
    }
  }
  return false;
}

TEST(SecureGateway, TokensNameTheSlotsAndAnotherClientCannotTakeOne) {
  SecureMatch match(3);
  SecureClient b(at(5001), match.token(2, 12));
  match.connect_and_join(b);
  EXPECT_EQ(b.player, 2u);
  EXPECT_NE(b.connection_id, 0u);
  SecureClient a(at(5000), match.token(0, 10));
  match.connect_and_join(a);
  EXPECT_EQ(a.player, 0u);
  // Someone else's valid token for slot 2 (a second token minted for it):
  // the slot's holder is talking, so the handshake is refused and the
  // holder keeps its session.
  SecureClient rival(at(5002), match.token(2, 99));
  match.to_server(rival.endpoint, rival.handshake.request());
  std::vector<uint8_t> response;
  ASSERT_TRUE(rival.handshake.on_challenge(match.wire_[rival.endpoint].at(0), response).ok());
  match.wire_[rival.endpoint].clear();
  const uint64_t refused = match.gateway_->stats().refused;
  match.to_server(rival.endpoint, response);
  EXPECT_EQ(match.gateway_->stats().refused, refused + 1);
  EXPECT_EQ(match.gateway_->sessions(), 2u);
  EXPECT_EQ(match.host_->phase(), MatchHost::Phase::kLobby);
  // Past the quiet time a holder that went silent gives way, and the host
  // then refuses the rival's join: the slot is held by another client.
  match.unix_now_ += SecureGateway::kHolderQuietS;
  SecureClient rival2(at(5003), match.token(2, 99));
  match.connect_and_join(rival2);
  EXPECT_TRUE(rejected(rival2, "held by another client"));
}

TEST(SecureGateway, AClientRestartedInTheLobbyTakesItsSlotBack) {
  SecureMatch match(2);
  const net::ConnectToken token = match.token(1, 21);
  SecureClient first(at(6000), token);
  match.connect_and_join(first);
  ASSERT_EQ(first.player, 1u);
  SecureClient restarted(at(6001), token);
  match.connect_and_join(restarted);
  EXPECT_EQ(restarted.player, 1u);
  EXPECT_NE(restarted.connection_id, first.connection_id);
  EXPECT_EQ(match.gateway_->sessions(), 1u);
  EXPECT_EQ(match.host_->stats().players_joined, 1u);
  // The old address's session is gone: what it sends is dropped.
  const uint64_t dropped = match.gateway_->stats().dropped;
  std::vector<uint8_t> sealed;
  first.handshake.session()->seal(std::vector<uint8_t>{1, 2, 3}, sealed);
  match.to_server(first.endpoint, sealed);
  EXPECT_EQ(match.gateway_->stats().dropped, dropped + 1);
}

TEST(SecureGateway, AClientRestartedMidMatchRejoinsItsSlotFromASnapshot) {
  SecureMatch match(2);
  SecureClient a(at(6100), match.token(0, 31));
  SecureClient b(at(6101), match.token(1, 32));
  match.connect_and_join(a);
  match.connect_and_join(b);
  ASSERT_EQ(match.host_->phase(), MatchHost::Phase::kRunning);
  // Play a while: both send inputs; the final ticks of the early ticks
  // are acknowledged, so the history moves on.
  const auto send_input = [&](SecureClient& c, Tick tick, Tick seen) {
    v1::Envelope e;
    e.set_protocol_version(net::kProtocolVersion);
    e.set_connection_id(c.connection_id);
    e.set_sequence(static_cast<uint32_t>(tick + 2));
    e.mutable_input_frame()->set_player(c.player);
    e.mutable_input_frame()->set_first_tick(tick);
    e.mutable_input_frame()->add_inputs();
    e.mutable_input_frame()->set_last_final_tick_seen(seen);
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(net::encode_envelope(e, bytes).ok());
    std::vector<uint8_t> sealed;
    c.handshake.session()->seal(bytes, sealed);
    match.to_server(c.endpoint, sealed);
  };
  for (Tick t = 0; t < 80; ++t) {
    const Tick tick = std::max<Tick>(match.host_->current_tick(), 0);
    send_input(a, tick, match.host_->last_final_tick());
    send_input(b, tick, match.host_->last_final_tick());
    match.now_ += std::chrono::milliseconds(16);
    match.host_->on_tick(match.now_);
    match.wire_.clear();
  }
  ASSERT_GT(match.host_->last_final_tick(), 40);
  // b's process dies and starts again from a new port, with its token.
  SecureClient again(at(6102), match.token(1, 32));
  match.connect_and_join(again);
  EXPECT_EQ(again.player, 1u);
  EXPECT_NE(again.connection_id, b.connection_id);
  EXPECT_TRUE(std::any_of(again.inbox.begin(), again.inbox.end(),
                          [](const v1::Envelope& e) { return e.has_match_start(); }));
  // The next broadcasts bring it a snapshot to start from.
  bool snapshot = false;
  for (int t = 0; t < 5 && !snapshot; ++t) {
    match.now_ += std::chrono::milliseconds(16);
    match.host_->on_tick(match.now_);
    match.read(again);
    for (const v1::Envelope& e : again.inbox) snapshot = snapshot || e.has_resync_chunk();
  }
  EXPECT_TRUE(snapshot);
  EXPECT_EQ(match.host_->stats().players_joined, 2u);
}

TEST(SecureGateway, ClearTextReachesNothing) {
  SecureMatch match(2);
  v1::Envelope join;
  join.set_protocol_version(net::kProtocolVersion);
  join.mutable_join_request()->set_game("crates");
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(net::encode_envelope(join, bytes).ok());
  for (uint16_t port = 7000; port < 7004; ++port) match.to_server(at(port), bytes);
  EXPECT_TRUE(match.wire_.empty());
  EXPECT_EQ(match.gateway_->stats().dropped, 4u);
  // A host in secure mode ignores a datagram that did not come through
  // the gateway.
  match.host_->on_datagram(bytes, at(7000), match.now_);
  EXPECT_EQ(match.host_->stats().players_joined, 0u);
  EXPECT_TRUE(match.wire_.empty());
}

}  // namespace
}  // namespace rwd::server
