// SPDX-License-Identifier: MIT
// A tokenless match behind its TokenlessGateway. Nothing is sent to an
// address that has not answered a cookie, and the cookie itself is never
// larger than the Hello that asked for it; a join without the address's
// cookie takes no seat (a lobby slot, a spectator seat, a late-join slot)
// and gets no answer; a real client (ClientProtocol) joins through the
// cookie on its own; a forged datagram does not unseat a player; a lobby
// seat whose holder goes silent or says goodbye is free again.
#include <gtest/gtest.h>

#include <map>

#include "rewind/client/client_protocol.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/server/match_host.h"
#include "rewind/server/tokenless_gateway.h"

namespace rwd::server {
namespace {

Endpoint at(uint16_t port, const char* address = "127.0.0.1") {
  return Endpoint(asio::ip::make_address(address), port);
}

struct Joined {
  Endpoint endpoint;
  uint64_t connection_id = 0;
  uint32_t player = 0;
  uint32_t sequence = 1;
};

class TokenlessMatch {
 public:
  explicit TokenlessMatch(MatchConfig config)
      : gateway_(
            [this](const Endpoint& to, std::span<const uint8_t> bytes) { record(to, bytes); }) {
    config.secure = false;
    now_ = net::SteadyClock::now();
    auto host = MatchHost::create(
        config, [this](const Endpoint& to, std::span<const uint8_t> b) { record(to, b); }, now_);
    EXPECT_TRUE(host.ok()) << host.status().message();
    host_ = std::move(*host);
  }

  void to_server(const Endpoint& from, std::span<const uint8_t> bytes) {
    bytes_from_[from] += bytes.size();
    gateway_.on_datagram(
        bytes, from, now_,
        [this](std::span<const uint8_t> envelope, const Endpoint& sender, const Admission* who) {
          host_->on_datagram(envelope, sender, now_, who);
        });
  }

  std::vector<uint8_t> encode(v1::Envelope envelope) {
    envelope.set_protocol_version(net::kProtocolVersion);
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(net::encode_envelope(envelope, bytes).ok());
    return bytes;
  }

  static v1::Envelope join_request(uint64_t nonce, bool spectator = false) {
    v1::Envelope e;
    e.mutable_join_request()->set_game("crates");
    e.mutable_join_request()->set_nonce(nonce);
    e.mutable_join_request()->set_spectator(spectator);
    return e;
  }

  // The cookie `from` gets for a Hello.
  net::AddressCookie cookie_for(const Endpoint& from) {
    to_server(from, net::make_hello());
    EXPECT_EQ(wire_[from].size(), 1u);
    std::optional<net::AddressCookie> cookie = net::read_cookie(wire_[from].back());
    EXPECT_TRUE(cookie.has_value());
    wire_[from].clear();
    return cookie.value_or(net::AddressCookie{});
  }

  // Hello, cookie, join: the seat taken.
  Joined join(const Endpoint& from, bool spectator = false) {
    const net::AddressCookie cookie = cookie_for(from);
    std::vector<uint8_t> framed;
    net::frame_join(cookie, encode(join_request(from.port(), spectator)), framed);
    to_server(from, framed);
    Joined out;
    out.endpoint = from;
    for (const std::vector<uint8_t>& bytes : wire_[from]) {
      auto e = net::decode_envelope(bytes);
      if (e.ok() && e->has_join_accept()) {
        out.connection_id = e->join_accept().connection_id();
        out.player = e->join_accept().player();
      }
    }
    EXPECT_NE(out.connection_id, 0u) << "no JoinAccept";
    wire_[from].clear();
    return out;
  }

  void send(Joined& c, v1::Envelope envelope, const Endpoint* spoofed_from = nullptr) {
    envelope.set_connection_id(c.connection_id);
    envelope.set_sequence(c.sequence++);
    to_server(spoofed_from != nullptr ? *spoofed_from : c.endpoint, encode(envelope));
  }

  void ping(Joined& c) {
    v1::Envelope e;
    e.mutable_ping()->set_client_time_us(1);
    send(c, e);
  }

  // Ticks every 50 ms for `span`; `talking` ping each tick.
  void pass(std::chrono::milliseconds span, std::vector<Joined*> talking = {}) {
    for (auto t = std::chrono::milliseconds(0); t < span; t += std::chrono::milliseconds(50)) {
      now_ += std::chrono::milliseconds(50);
      for (Joined* c : talking) ping(*c);
      host_->on_tick(now_);
    }
  }

  size_t bytes_to(const Endpoint& to) { return bytes_to_[to]; }
  size_t bytes_from(const Endpoint& from) { return bytes_from_[from]; }

  TimePoint now_;
  TokenlessGateway gateway_;
  std::unique_ptr<MatchHost> host_;
  std::map<Endpoint, std::vector<std::vector<uint8_t>>> wire_;

 private:
  void record(const Endpoint& to, std::span<const uint8_t> bytes) {
    wire_[to].emplace_back(bytes.begin(), bytes.end());
    bytes_to_[to] += bytes.size();
  }
  std::map<Endpoint, size_t> bytes_to_;
  std::map<Endpoint, size_t> bytes_from_;
};

MatchConfig small_config() {
  MatchConfig config;
  config.players = 2;
  config.max_spectators = 2;
  config.start_delay_s = 0;
  config.peer_timeout_s = 1.0;
  return config;
}

// Every way a join can come without this address's cookie.
void spoofed_joins(TokenlessMatch& m, const Endpoint& victim) {
  const std::vector<uint8_t> plain = m.encode(TokenlessMatch::join_request(1));
  m.to_server(victim, plain);
  m.to_server(victim, m.encode(TokenlessMatch::join_request(2, /*spectator=*/true)));
  m.to_server(victim, std::vector<uint8_t>{0x08, 0x02, 0x52, 0x00});  // a 4-byte join
  std::vector<uint8_t> framed;
  net::frame_join(net::AddressCookie{}, plain, framed);  // a made-up cookie
  m.to_server(victim, framed);
  // A cookie the attacker got for its own address, or for the victim's
  // address but another port.
  const Endpoint attacker = at(40000, "127.0.0.2");
  net::frame_join(m.cookie_for(attacker), plain, framed);
  m.to_server(victim, framed);
  const Endpoint next_port(victim.address(), static_cast<uint16_t>(victim.port() + 1));
  net::frame_join(m.cookie_for(next_port), plain, framed);
  m.to_server(victim, framed);
}

TEST(TokenlessGateway, AHelloGetsOneCookieNoLargerThanItself) {
  TokenlessMatch m(small_config());
  const Endpoint client = at(5000);
  m.to_server(client, net::make_hello());
  ASSERT_EQ(m.wire_[client].size(), 1u);
  EXPECT_EQ(m.wire_[client][0].size(), net::kCookieReplyBytes);
  EXPECT_LE(net::kCookieReplyBytes, net::kHelloBytes);
  EXPECT_TRUE(net::read_cookie(m.wire_[client][0]).has_value());
  // Hellos of another size or version get nothing.
  const Endpoint other = at(5001);
  std::vector<uint8_t> hello = net::make_hello();
  m.to_server(other, std::span<const uint8_t>(hello).first(4));
  hello.resize(1000);
  m.to_server(other, hello);
  hello = net::make_hello();
  hello[1] = 99;
  m.to_server(other, hello);
  m.to_server(other, std::vector<uint8_t>{0xB2, 1, 2, 3});  // a cookie sent to the server
  EXPECT_TRUE(m.wire_[other].empty());
  EXPECT_EQ(m.gateway_.stats().cookies, 1u);
  EXPECT_EQ(m.gateway_.stats().refused, 4u);
}

TEST(TokenlessGateway, AJoinWithoutTheAddresssCookieGetsNothingAndTakesNoSeat) {
  TokenlessMatch m(small_config());
  const Endpoint victim = at(6000);
  spoofed_joins(m, victim);
  m.pass(std::chrono::milliseconds(500));
  EXPECT_EQ(m.bytes_to(victim), 0u) << "the server answered an unproven address";
  EXPECT_EQ(m.host_->stats().players_joined, 0u);
  for (uint32_t slot = 0; slot < 4; ++slot) EXPECT_FALSE(m.host_->seated(slot, victim));
  EXPECT_EQ(m.gateway_.stats().admitted, 0u);
  // The same address with its own cookie joins.
  const Joined real = m.join(victim);
  EXPECT_EQ(real.player, 0u);
  EXPECT_EQ(m.host_->stats().players_joined, 1u);
}

TEST(TokenlessGateway, MidMatchASpoofedJoinTakesNeitherALateJoinSlotNorASeat) {
  MatchConfig config = small_config();
  config.start_players = 1;  // slot 1 stays open for a late joiner
  TokenlessMatch m(config);
  Joined a = m.join(at(6100));
  m.pass(std::chrono::milliseconds(200), {&a});
  ASSERT_EQ(m.host_->phase(), MatchHost::Phase::kRunning);
  const Endpoint victim = at(6101);
  spoofed_joins(m, victim);
  m.pass(std::chrono::milliseconds(1000), {&a});
  EXPECT_EQ(m.bytes_to(victim), 0u);
  EXPECT_FALSE(m.host_->seated(1, victim));
  EXPECT_FALSE(m.host_->seated(2, victim));
  // Every byte an address that never answered a cookie got back (here,
  // none) is at most what it sent.
  EXPECT_LE(m.bytes_to(victim), m.bytes_from(victim));
}

TEST(TokenlessGateway, AForgedDatagramDoesNotUnseatAPlayer) {
  TokenlessMatch m(small_config());
  Joined a = m.join(at(6200));
  Joined b = m.join(at(6201));
  ASSERT_EQ(m.host_->phase(), MatchHost::Phase::kRunning);
  // A goodbye with a's connection id from another address; a join from
  // a's address without its cookie; a join from the attacker's own
  // address (it may take a free seat, never a's).
  const Endpoint attacker = at(6202, "127.0.0.3");
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("forged");
  m.send(a, bye, &attacker);
  m.to_server(a.endpoint, m.encode(TokenlessMatch::join_request(99)));
  const Joined watcher = m.join(attacker, /*spectator=*/true);
  EXPECT_GE(watcher.player, 2u);
  m.pass(std::chrono::milliseconds(300), {&a, &b});
  EXPECT_TRUE(m.host_->seated(a.player, a.endpoint));
  EXPECT_TRUE(m.host_->seated(b.player, b.endpoint));
  EXPECT_EQ(m.host_->players_connected(), 2u);
}

TEST(TokenlessGateway, ALobbySeatIsFreedWhenItsHolderGoesSilentOrLeaves) {
  MatchConfig config = small_config();
  config.players = 3;
  TokenlessMatch m(config);
  Joined a = m.join(at(6300));
  Joined squatter = m.join(at(6301));
  Joined leaver = m.join(at(6302), /*spectator=*/true);
  ASSERT_EQ(squatter.player, 1u);
  EXPECT_EQ(m.host_->stats().players_joined, 2u);
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("bye");
  m.send(leaver, bye);
  m.pass(std::chrono::milliseconds(100), {&a, &squatter});
  EXPECT_FALSE(m.host_->seated(leaver.player, leaver.endpoint));  // gone at once
  // The squatter stops talking: past the peer timeout its seat is free.
  m.pass(std::chrono::milliseconds(900), {&a});
  EXPECT_TRUE(m.host_->seated(1, squatter.endpoint));
  m.pass(std::chrono::milliseconds(300), {&a});
  EXPECT_FALSE(m.host_->seated(1, squatter.endpoint));
  EXPECT_EQ(m.host_->stats().players_joined, 1u);
  EXPECT_EQ(m.host_->phase(), MatchHost::Phase::kLobby);
  // The freed seat goes to the next joiner; the old connection is void.
  Joined next = m.join(at(6303));
  EXPECT_EQ(next.player, 1u);
  const uint64_t rejected = m.host_->stats().rejected_packets;
  m.ping(squatter);
  EXPECT_EQ(m.host_->stats().rejected_packets, rejected + 1);
}

TEST(TokenlessGateway, ARealClientJoinsThroughTheCookieOnItsOwn) {
  TokenlessMatch m(small_config());
  std::vector<client::ClientProtocol> clients;
  for (uint64_t i = 0; i < 2; ++i) {
    client::ClientConfig config;
    auto protocol = client::ClientProtocol::create(config, 0x1000 + i);
    ASSERT_TRUE(protocol.ok());
    clients.push_back(std::move(*protocol));
  }
  // Every datagram is carried at once, both ways, until nothing moves.
  size_t hellos = 0;
  const auto exchange = [&] {
    for (bool moved = true; moved;) {
      moved = false;
      for (size_t i = 0; i < clients.size(); ++i) {
        const Endpoint from = at(static_cast<uint16_t>(6400 + i));
        while (auto datagram = clients[i].next_datagram()) {
          hellos += net::cookie_packet_kind(*datagram) == net::CookiePacket::kHello;
          m.to_server(from, *datagram);
          moved = true;
        }
        std::vector<std::vector<uint8_t>> replies = std::move(m.wire_[from]);
        m.wire_[from].clear();
        for (const std::vector<uint8_t>& bytes : replies) clients[i].receive(bytes, m.now_);
      }
    }
  };
  for (client::ClientProtocol& c : clients) c.connect(m.now_);
  for (int step = 0; step < 40; ++step) {
    exchange();
    m.now_ += std::chrono::milliseconds(16);
    m.host_->on_tick(m.now_);
    exchange();
    for (client::ClientProtocol& c : clients) c.update(m.now_);
  }
  EXPECT_EQ(hellos, 2u);  // one each: the cookie came back at once
  EXPECT_EQ(m.gateway_.stats().admitted, 2u);
  EXPECT_EQ(m.host_->stats().players_joined, 2u);
  for (const client::ClientProtocol& c : clients) {
    EXPECT_EQ(c.phase(), client::ClientPhase::kRunning);
  }
}

}  // namespace
}  // namespace rwd::server
