// SPDX-License-Identifier: MIT
// A secure match host: clients connect through the SecureGateway with
// connect tokens and take the slots their tokens name. A token connects
// once (a copy of it, keys included, is refused, and so is the token itself
// when its client comes back); a request for a connected client id is
// ignored; another client's token never cuts a holder off, talking or
// silent, and takes the slot exactly when the match has dropped its
// holder; a client that comes back with a fresh token for its client id
// takes its slot again (mid-match, from a snapshot); the remembered tokens
// are bounded; clear-text datagrams reach nothing and get no answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  uint32_t sequence = 1;
};

class SecureMatch {
 public:
  explicit SecureMatch(uint32_t players, size_t used_token_capacity = 64) {
    MatchConfig config;
    config.players = players;
    config.match_id = "secure-test";
    config.secure = true;
    config.peer_timeout_s = 1.0;
    config.start_delay_s = 0;
    now_ = net::SteadyClock::now();
    SecureGateway::Options options;
    options.slots = players + config.max_spectators;
    options.join_grace_s = static_cast<int64_t>(std::ceil(config.peer_timeout_s));
    options.seated = [this](uint32_t slot, const Endpoint& e) { return host_->seated(slot, e); };
    options.used_token_capacity = used_token_capacity;
    gateway_ =
        std::make_unique<SecureGateway>(key_, config.match_id, std::move(options),
                                        [this](const Endpoint& to, std::span<const uint8_t> bytes) {
                                          wire_[to].emplace_back(bytes.begin(), bytes.end());
                                        });
    auto host = MatchHost::create(
        config, [this](const Endpoint& to, std::span<const uint8_t> b) { gateway_->send(to, b); },
        now_);
    EXPECT_TRUE(host.ok()) << host.status().message();
    host_ = std::move(*host);
  }

  net::ConnectToken token(uint32_t slot, uint64_t client_id, int64_t lifetime_s = 60) {
    return *net::make_connect_token(key_, "secure-test", slot, client_id, kNow + lifetime_s, kNow);
  }

  void to_server(const Endpoint& from, std::span<const uint8_t> bytes) {
    gateway_->on_datagram(
        bytes, from, unix_now_,
        [this](std::span<const uint8_t> env, const Endpoint& sender, const Admission& who) {
          host_->on_datagram(env, sender, now_, &who);
        });
  }

  // Sends the request; true when a challenge came back, which is answered.
  bool handshake(SecureClient& c) {
    to_server(c.endpoint, c.handshake.request());
    std::vector<std::vector<uint8_t>> answers = std::move(wire_[c.endpoint]);
    wire_[c.endpoint].clear();
    if (answers.empty()) return false;
    EXPECT_EQ(answers.size(), 1u);
    std::vector<uint8_t> response;
    EXPECT_TRUE(c.handshake.on_challenge(answers[0], response).ok());
    to_server(c.endpoint, response);
    return true;
  }

  // Handshake, then a JoinRequest; collects what the server answers.
  void connect_and_join(SecureClient& c) {
    ASSERT_TRUE(handshake(c)) << "no challenge";
    v1::Envelope join;
    join.mutable_join_request()->set_game("crates");
    join.mutable_join_request()->set_nonce(c.endpoint.port());
    send(c, join);
    read(c);
  }

  // A sealed envelope from `c` (a connected client).
  void send(SecureClient& c, v1::Envelope envelope) {
    envelope.set_protocol_version(net::kProtocolVersion);
    envelope.set_connection_id(c.connection_id);
    if (!envelope.has_join_request()) envelope.set_sequence(c.sequence++);
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(net::encode_envelope(envelope, bytes).ok());
    std::vector<uint8_t> sealed;
    c.handshake.session()->seal(bytes, sealed);
    to_server(c.endpoint, sealed);
  }

  void ping(SecureClient& c) {
    v1::Envelope e;
    e.mutable_ping()->set_client_time_us(1);
    send(c, e);
  }

  void send_input(SecureClient& c, Tick tick) {
    v1::Envelope e;
    e.mutable_input_frame()->set_player(c.player);
    e.mutable_input_frame()->set_first_tick(tick);
    e.mutable_input_frame()->add_inputs();
    e.mutable_input_frame()->set_last_final_tick_seen(host_->last_final_tick());
    send(c, e);
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

  // Time passes in ticks of 50 ms; `talking` keep sending (pings in the
  // lobby, inputs while running), everybody else is silent.
  void pass(std::chrono::milliseconds span, std::vector<SecureClient*> talking = {}) {
    for (auto elapsed = std::chrono::milliseconds(0); elapsed < span;
         elapsed += std::chrono::milliseconds(50)) {
      now_ += std::chrono::milliseconds(50);
      unix_ms_ += 50;
      unix_now_ = kNow + unix_ms_ / 1000;
      for (SecureClient* c : talking) {
        if (host_->phase() == MatchHost::Phase::kRunning) {
          send_input(*c, std::max<Tick>(host_->current_tick(), 0));
        } else {
          ping(*c);
        }
      }
      host_->on_tick(now_);
      wire_.clear();
    }
  }

  net::Key key_ = net::generate_key();
  TimePoint now_;
  int64_t unix_now_ = kNow;
  int64_t unix_ms_ = 0;
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

bool delivered(SecureMatch& match, SecureClient& c) {
  const uint64_t dropped = match.gateway_->stats().dropped;
  match.ping(c);
  return match.gateway_->stats().dropped == dropped;
}

TEST(SecureGateway, AnotherClientsTokenNeverCutsTheHolderOff) {
  SecureMatch match(3);
  SecureClient b(at(5001), match.token(2, 12));
  match.connect_and_join(b);
  EXPECT_EQ(b.player, 2u);
  EXPECT_NE(b.connection_id, 0u);
  SecureClient a(at(5000), match.token(0, 10));
  match.connect_and_join(a);
  EXPECT_EQ(a.player, 0u);
  // Someone else's valid token for slot 2 (a second token minted for it):
  // no challenge while the holder holds it, talking...
  SecureClient rival(at(5002), match.token(2, 99));
  const uint64_t refused = match.gateway_->stats().refused;
  EXPECT_FALSE(match.handshake(rival));
  EXPECT_EQ(match.gateway_->stats().refused, refused + 1);
  // ... or silent, as long as the match has not dropped it.
  match.pass(std::chrono::milliseconds(900), {&a});
  ASSERT_TRUE(match.host_->seated(2, b.endpoint));
  SecureClient rival2(at(5003), match.token(2, 99));
  EXPECT_FALSE(match.handshake(rival2));
  EXPECT_EQ(match.gateway_->sessions(), 2u);
  EXPECT_TRUE(delivered(match, b));
  // Silent past the peer timeout: the match frees the lobby seat, and then
  // (only then) another client's token takes it; the holder's session ends.
  match.pass(std::chrono::milliseconds(1200), {&a});
  ASSERT_FALSE(match.host_->seated(2, b.endpoint));
  SecureClient rival3(at(5004), match.token(2, 99));
  match.connect_and_join(rival3);
  EXPECT_EQ(rival3.player, 2u);
  EXPECT_TRUE(match.host_->seated(2, rival3.endpoint));
  EXPECT_FALSE(delivered(match, b));
  EXPECT_TRUE(delivered(match, a));
  EXPECT_EQ(match.host_->stats().players_joined, 2u);
}

TEST(SecureGateway, ACopiedTokenIsRefusedAfterItsOwnerConnected) {
  SecureMatch match(2);
  const net::ConnectToken token = match.token(1, 21);
  SecureClient owner(at(6000), token);
  match.connect_and_join(owner);
  ASSERT_EQ(owner.player, 1u);
  EXPECT_EQ(match.gateway_->used_tokens(), 1u);
  // A copy of the whole token, keys included, from another address: no
  // challenge, and the owner keeps its slot and session.
  SecureClient copy(at(6001), token);
  EXPECT_FALSE(match.handshake(copy));
  EXPECT_EQ(match.gateway_->stats().reused, 1u);
  EXPECT_EQ(match.gateway_->sessions(), 1u);
  EXPECT_TRUE(match.host_->seated(1, owner.endpoint));
  EXPECT_TRUE(delivered(match, owner));
  // Even once the owner is gone, the token stays used: neither the copy
  // nor the owner itself (restarted) connects with it again.
  match.pass(std::chrono::milliseconds(1500));
  ASSERT_FALSE(match.host_->seated(1, owner.endpoint));
  SecureClient copy_again(at(6002), token);
  EXPECT_FALSE(match.handshake(copy_again));
  SecureClient restarted(at(6003), token);
  EXPECT_FALSE(match.handshake(restarted));
  EXPECT_EQ(match.gateway_->stats().reused, 3u);
  // A fresh token minted for the same client id and slot: back in.
  SecureClient fresh(at(6004), match.token(1, 21));
  match.connect_and_join(fresh);
  EXPECT_EQ(fresh.player, 1u);
  EXPECT_NE(fresh.connection_id, owner.connection_id);
  EXPECT_EQ(match.gateway_->sessions(), 1u);
  EXPECT_EQ(match.host_->stats().players_joined, 1u);
}

TEST(SecureGateway, ARequestForAConnectedClientIdIsIgnored) {
  SecureMatch match(2);
  SecureClient a(at(6100), match.token(0, 31));
  match.connect_and_join(a);
  // A fresh token for the same client id, for its slot or another one,
  // from another address: ignored while a is connected.
  SecureClient same_slot(at(6101), match.token(0, 31));
  EXPECT_FALSE(match.handshake(same_slot));
  SecureClient other_slot(at(6102), match.token(1, 31));
  EXPECT_FALSE(match.handshake(other_slot));
  EXPECT_EQ(match.gateway_->stats().reused, 0u);
  EXPECT_EQ(match.gateway_->sessions(), 1u);
  EXPECT_TRUE(delivered(match, a));
  EXPECT_EQ(match.host_->stats().players_joined, 1u);
  // The tokens were not used, so either still works later.
  match.pass(std::chrono::milliseconds(1500));
  match.connect_and_join(other_slot);
  EXPECT_EQ(other_slot.player, 1u);
}

TEST(SecureGateway, AResponseIsCheckedAgainWhenItArrives) {
  SecureMatch match(2);
  // The rival gets its challenge while slot 0 is free...
  SecureClient rival(at(6200), match.token(0, 41));
  match.to_server(rival.endpoint, rival.handshake.request());
  ASSERT_EQ(match.wire_[rival.endpoint].size(), 1u);
  std::vector<uint8_t> response;
  ASSERT_TRUE(rival.handshake.on_challenge(match.wire_[rival.endpoint][0], response).ok());
  match.wire_.clear();
  // ... the holder connects and joins first...
  SecureClient holder(at(6201), match.token(0, 42));
  match.to_server(holder.endpoint, holder.handshake.request());
  ASSERT_EQ(match.wire_[holder.endpoint].size(), 1u);
  std::vector<uint8_t> holder_response;
  ASSERT_TRUE(holder.handshake.on_challenge(match.wire_[holder.endpoint][0], holder_response).ok());
  match.wire_.clear();
  match.to_server(holder.endpoint, holder_response);
  v1::Envelope join;
  join.mutable_join_request()->set_game("crates");
  join.mutable_join_request()->set_nonce(1);
  match.send(holder, join);
  match.read(holder);
  ASSERT_EQ(holder.player, 0u);
  ASSERT_NE(holder.connection_id, 0u);
  // ... so the rival's response is refused: no session, the holder stays.
  const uint64_t connects = match.gateway_->stats().connects;
  match.to_server(rival.endpoint, response);
  EXPECT_EQ(match.gateway_->stats().connects, connects);
  EXPECT_EQ(match.gateway_->sessions(), 1u);
  EXPECT_TRUE(delivered(match, holder));
  // The holder's own response again (a client resends it until the server
  // speaks): the same handshake, so its session stands, used token or not.
  match.to_server(holder.endpoint, holder_response);
  EXPECT_EQ(match.gateway_->stats().connects, connects);
  EXPECT_EQ(match.gateway_->stats().reused, 0u);
  EXPECT_TRUE(delivered(match, holder));
}

TEST(SecureGateway, MidMatchTheSlotGoesToAFreshTokenOnceTheMatchDropsItsHolder) {
  SecureMatch match(2);
  SecureClient a(at(6300), match.token(0, 51));
  SecureClient b(at(6301), match.token(1, 52));
  match.connect_and_join(a);
  match.connect_and_join(b);
  ASSERT_EQ(match.host_->phase(), MatchHost::Phase::kRunning);
  match.pass(std::chrono::milliseconds(3000), {&a, &b});
  ASSERT_GT(match.host_->last_final_tick(), 40);
  // b's process dies. While the match still counts b in, neither b's
  // fresh token nor another client's is taken.
  match.pass(std::chrono::milliseconds(500), {&a});
  SecureClient early(at(6302), match.token(1, 52));
  EXPECT_FALSE(match.handshake(early));
  SecureClient other(at(6303), match.token(1, 77));
  EXPECT_FALSE(match.handshake(other));
  // Past the peer timeout the match drops b, and b's fresh token takes the
  // slot back: a snapshot follows.
  match.pass(std::chrono::milliseconds(800), {&a});
  ASSERT_FALSE(match.host_->seated(1, b.endpoint));
  SecureClient again(at(6304), match.token(1, 52));
  match.connect_and_join(again);
  EXPECT_EQ(again.player, 1u);
  EXPECT_NE(again.connection_id, b.connection_id);
  EXPECT_TRUE(std::any_of(again.inbox.begin(), again.inbox.end(),
                          [](const v1::Envelope& e) { return e.has_match_start(); }));
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

TEST(SecureGateway, MidMatchAnotherClientTakesASlotTheMatchDropped) {
  SecureMatch match(2);
  SecureClient a(at(6400), match.token(0, 61));
  SecureClient b(at(6401), match.token(1, 62));
  match.connect_and_join(a);
  match.connect_and_join(b);
  match.pass(std::chrono::milliseconds(2000), {&a});  // b silent: dropped at 1 s
  ASSERT_FALSE(match.host_->seated(1, b.endpoint));
  // The gateway and the match agree: the slot is free for another client.
  SecureClient other(at(6402), match.token(1, 63));
  match.connect_and_join(other);
  EXPECT_FALSE(rejected(other, "held by another client"));
  EXPECT_EQ(other.player, 1u);
  EXPECT_TRUE(match.host_->seated(1, other.endpoint));
  EXPECT_FALSE(delivered(match, b));
}

TEST(SecureGateway, RemembersTokensUpToItsCapacityAndThenRefuses) {
  SecureMatch match(3, /*used_token_capacity=*/2);
  SecureClient a(at(6500), match.token(0, 71, 30));
  SecureClient b(at(6501), match.token(1, 72, 30));
  match.connect_and_join(a);
  match.connect_and_join(b);
  EXPECT_EQ(match.gateway_->used_tokens(), 2u);
  // Full of unexpired tokens: a new one is refused rather than one of them
  // forgotten (a forgotten token's copies would connect).
  SecureClient c(at(6502), match.token(2, 73, 120));
  ASSERT_TRUE(match.handshake(c));
  EXPECT_EQ(match.gateway_->sessions(), 2u);
  EXPECT_FALSE(match.host_->seated(2, c.endpoint));
  // Once those expire they are pruned and the next token fits.
  match.unix_now_ = kNow + 31;
  SecureClient d(at(6503), match.token(2, 73, 120));
  ASSERT_TRUE(match.handshake(d));
  EXPECT_EQ(match.gateway_->sessions(), 3u);
  EXPECT_EQ(match.gateway_->used_tokens(), 1u);
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
