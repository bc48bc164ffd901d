// SPDX-License-Identifier: MIT
// Secure connections: tokens mint, serialize and open only for their own
// server, match, slot and expiry; the handshake connects a key holder and
// nobody else (a stolen token, a spoofed or replayed response, another
// address, an expired challenge); payload packets refuse forgeries,
// alterations and replays, and a sequence jump cannot lock a peer out; no
// answer to an unauthenticated packet is larger than the packet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"

namespace rwd::net {
namespace {

constexpr int64_t kNow = 1'800'000'000;

PeerAddress address(uint8_t last, uint16_t port) {
  PeerAddress a;
  a.ip[10] = 0xff;
  a.ip[11] = 0xff;
  a.ip[12] = 127;
  a.ip[15] = last;
  a.port = port;
  return a;
}

struct Fixture {
  Key server_key = generate_key();
  uint64_t tag = connect_match_tag("match-1");
  ServerGate gate{server_key, generate_key(), tag};

  ConnectToken token(uint32_t slot, uint64_t client = 7, int64_t expiry = kNow + 60) {
    auto t = make_connect_token(server_key, "match-1", slot, client, expiry, kNow);
    EXPECT_TRUE(t.ok()) << t.status().message();
    return *t;
  }

  // A full handshake from `from`; the server's and the client's ends.
  std::pair<ConnectedClient, SecureSession> connect(const ConnectToken& t,
                                                    const PeerAddress& from) {
    ClientHandshake client(t);
    std::vector<uint8_t> challenge;
    EXPECT_TRUE(gate.on_request(client.request(), from, kNow, challenge).ok());
    std::vector<uint8_t> response;
    EXPECT_TRUE(client.on_challenge(challenge, response).ok());
    auto connected = gate.on_response(response, from, kNow);
    EXPECT_TRUE(connected.ok()) << connected.status().message();
    return {std::move(*connected), *client.session()};
  }
};

TEST(ConnectToken, RoundTripsAndRefusesBadInput) {
  const Key key = generate_key();
  auto t = make_connect_token(key, "m", 3, 99, kNow + 30, kNow);
  ASSERT_TRUE(t.ok());
  const std::vector<uint8_t> bytes = write_connect_token(*t);
  ASSERT_EQ(bytes.size(), kConnectTokenBytes);
  auto back = read_connect_token(bytes);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->slot, 3u);
  EXPECT_EQ(back->client_id, 99u);
  EXPECT_EQ(back->client_to_server_key, t->client_to_server_key);
  EXPECT_NE(t->client_to_server_key, t->server_to_client_key);
  auto hex = from_hex(to_hex(bytes) + "\n");
  ASSERT_TRUE(hex.ok());
  EXPECT_EQ(*hex, bytes);

  EXPECT_FALSE(make_connect_token(key, "", 0, 1, kNow + 30, kNow).ok());
  EXPECT_FALSE(make_connect_token(key, "m", 0, 0, kNow + 30, kNow).ok());
  EXPECT_FALSE(make_connect_token(key, "m", 0, 1, kNow, kNow).ok());
  EXPECT_FALSE(make_connect_token(key, "m", 0, 1, kNow + kMaxTokenLifetimeS + 1, kNow).ok());
  std::vector<uint8_t> shorter(bytes.begin(), bytes.end() - 1);
  EXPECT_EQ(read_connect_token(shorter).status().code(), ErrorCode::kCorrupt);
  EXPECT_FALSE(from_hex("abc").ok());
  EXPECT_FALSE(from_hex("zz").ok());
  EXPECT_FALSE(key_from_hex("00ff").ok());
}

TEST(ConnectToken, OpensOnlyForItsServerMatchSlotAndTime) {
  const Key key = generate_key();
  const ConnectToken t = *make_connect_token(key, "m", 2, 5, kNow + 30, kNow);
  const auto open = [&](const Key& k, uint64_t tag, int64_t expiry, uint32_t slot, int64_t now) {
    return open_private_token(k, tag, expiry, slot, t.nonce, t.sealed, now);
  };
  auto ok = open(key, t.match_tag, t.expiry_unix_s, 2, kNow);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->client_id, 5u);
  EXPECT_EQ(ok->client_to_server_key, t.client_to_server_key);
  EXPECT_FALSE(open(generate_key(), t.match_tag, t.expiry_unix_s, 2, kNow).ok());
  EXPECT_FALSE(open(key, connect_match_tag("other"), t.expiry_unix_s, 2, kNow).ok());
  EXPECT_FALSE(open(key, t.match_tag, t.expiry_unix_s + 3600, 2, kNow).ok());  // extended
  EXPECT_FALSE(open(key, t.match_tag, t.expiry_unix_s, 3, kNow).ok());         // another slot
  EXPECT_FALSE(open(key, t.match_tag, t.expiry_unix_s, 2, t.expiry_unix_s).ok());
}

TEST(SecureChannel, HandshakeConnectsAndPayloadsFlowBothWays) {
  Fixture f;
  const ConnectToken t = f.token(1, 42);
  auto [server, client] = f.connect(t, address(1, 5000));
  EXPECT_EQ(server.client_id, 42u);
  EXPECT_EQ(server.slot, 1u);
  std::vector<uint8_t> packet;
  std::vector<uint8_t> out;
  const std::vector<uint8_t> hello = {1, 2, 3, 4, 5};
  client.seal(hello, packet);
  EXPECT_EQ(packet.size(), hello.size() + kPayloadOverhead);
  ASSERT_TRUE(server.session.open(packet, out).ok());
  EXPECT_EQ(out, hello);
  server.session.seal(hello, packet);
  ASSERT_TRUE(client.open(packet, out).ok());
  EXPECT_EQ(out, hello);
  // A packet never opens with the key of the other direction.
  client.seal(hello, packet);
  EXPECT_FALSE(client.open(packet, out).ok());
}

TEST(SecureChannel, NoAnswerIsLargerThanTheRequestAndBadRequestsGetNone) {
  Fixture f;
  ClientHandshake client(f.token(0));
  std::vector<uint8_t> challenge;
  ASSERT_TRUE(f.gate.on_request(client.request(), address(1, 5000), kNow, challenge).ok());
  EXPECT_EQ(client.request().size(), kRequestBytes);
  EXPECT_LT(challenge.size(), client.request().size());
  // Truncated, flipped, another match's, expired: no reply at all.
  std::vector<uint8_t> bad = client.request();
  bad.pop_back();
  EXPECT_FALSE(f.gate.on_request(bad, address(1, 5000), kNow, challenge).ok());
  EXPECT_TRUE(challenge.empty());
  for (size_t at : {size_t{2}, size_t{12}, size_t{22}, size_t{40}, size_t{100}}) {
    bad = client.request();
    bad[at] ^= 0x01;
    EXPECT_FALSE(f.gate.on_request(bad, address(1, 5000), kNow, challenge).ok()) << at;
    EXPECT_TRUE(challenge.empty());
  }
  EXPECT_FALSE(f.gate.on_request(client.request(), address(1, 5000), kNow + 61, challenge).ok());
  ServerGate other(f.server_key, generate_key(), connect_match_tag("match-2"));
  EXPECT_FALSE(other.on_request(client.request(), address(1, 5000), kNow, challenge).ok());
}

TEST(SecureChannel, AStolenRequestIsUselessWithoutTheKeys) {
  Fixture f;
  const ConnectToken t = f.token(0);
  ClientHandshake victim(t);
  // The thief replays the victim's request from its own address: the
  // challenge it gets is sealed with a key it does not have.
  std::vector<uint8_t> challenge;
  ASSERT_TRUE(f.gate.on_request(victim.request(), address(9, 6000), kNow, challenge).ok());
  ConnectToken guessed = t;
  guessed.server_to_client_key = generate_key();
  guessed.client_to_server_key = generate_key();
  ClientHandshake thief(guessed);
  std::vector<uint8_t> response;
  EXPECT_FALSE(thief.on_challenge(challenge, response).ok());
  // Forging a response around the challenge token it cannot read: the
  // server refuses the tag.
  std::vector<uint8_t> forged(kResponseBytes, 0);
  forged[0] = static_cast<uint8_t>(SecurePacket::kResponse);
  EXPECT_FALSE(f.gate.on_response(forged, address(9, 6000), kNow).ok());
}

TEST(SecureChannel, ResponsesCountOnlyFromTheChallengedAddressInTime) {
  Fixture f;
  ClientHandshake client(f.token(0));
  std::vector<uint8_t> challenge;
  std::vector<uint8_t> response;
  ASSERT_TRUE(f.gate.on_request(client.request(), address(1, 5000), kNow, challenge).ok());
  ASSERT_TRUE(client.on_challenge(challenge, response).ok());
  EXPECT_FALSE(f.gate.on_response(response, address(1, 5001), kNow).ok());
  EXPECT_FALSE(f.gate.on_response(response, address(2, 5000), kNow).ok());
  EXPECT_FALSE(f.gate.on_response(response, address(1, 5000), kNow + kChallengeLifetimeS).ok());
  std::vector<uint8_t> altered = response;
  altered.back() ^= 0x80;
  EXPECT_FALSE(f.gate.on_response(altered, address(1, 5000), kNow).ok());
  auto a = f.gate.on_response(response, address(1, 5000), kNow);
  ASSERT_TRUE(a.ok());
  // The same response again (duplicated or replayed) names the same salt,
  // so the host can tell it from a new handshake.
  auto b = f.gate.on_response(response, address(1, 5000), kNow + 1);
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(a->salt, b->salt);
  // A second challenge (the request was resent) gives the same response.
  std::vector<uint8_t> challenge2;
  std::vector<uint8_t> response2;
  ASSERT_TRUE(f.gate.on_request(client.request(), address(1, 5000), kNow, challenge2).ok());
  ASSERT_TRUE(client.on_challenge(challenge2, response2).ok());
  EXPECT_EQ(response2, response);
}

// The token's MAC (its sealed part's tag) names it from the request to the
// connected client, so a server can refuse a token it has seen connect.
TEST(SecureChannel, TheTokensMacTravelsThroughTheHandshake) {
  Fixture f;
  const ConnectToken t = f.token(2, 55);
  ClientHandshake client(t);
  std::vector<uint8_t> challenge;
  RequestedToken requested;
  ASSERT_TRUE(
      f.gate.on_request(client.request(), address(1, 5000), kNow, challenge, &requested).ok());
  EXPECT_EQ(requested.client_id, 55u);
  EXPECT_EQ(requested.slot, 2u);
  EXPECT_EQ(requested.expiry_unix_s, t.expiry_unix_s);
  EXPECT_TRUE(std::equal(requested.mac.begin(), requested.mac.end(),
                         t.sealed.end() - static_cast<std::ptrdiff_t>(kTokenMacBytes)));
  std::vector<uint8_t> response;
  ASSERT_TRUE(client.on_challenge(challenge, response).ok());
  auto connected = f.gate.on_response(response, address(1, 5000), kNow);
  ASSERT_TRUE(connected.ok());
  EXPECT_EQ(connected->token_mac, requested.mac);
  // Another token for the same client and slot has another MAC.
  ClientHandshake other(f.token(2, 55));
  RequestedToken other_requested;
  ASSERT_TRUE(
      f.gate.on_request(other.request(), address(1, 5000), kNow, challenge, &other_requested).ok());
  EXPECT_NE(other_requested.mac, requested.mac);
  // A version 1 request (before tokens carried their MAC through) is refused.
  std::vector<uint8_t> old_version = client.request();
  old_version[1] = 1;
  EXPECT_FALSE(f.gate.on_request(old_version, address(1, 5000), kNow, challenge).ok());
  EXPECT_TRUE(challenge.empty());
}

// At this layer (no memory of its own) a token still handshakes again; the
// server's gateway refuses it (UsedTokens). The keys are fresh each time.
TEST(SecureChannel, ReconnectingWithTheSameTokenGetsFreshKeys) {
  Fixture f;
  const ConnectToken t = f.token(3);
  auto [server1, client1] = f.connect(t, address(1, 5000));
  auto [server2, client2] = f.connect(t, address(1, 5002));
  EXPECT_NE(server1.salt, server2.salt);
  std::vector<uint8_t> packet;
  std::vector<uint8_t> out;
  client1.seal(std::vector<uint8_t>{9}, packet);
  EXPECT_FALSE(server2.session.open(packet, out).ok());
  client2.seal(std::vector<uint8_t>{9}, packet);
  EXPECT_TRUE(server2.session.open(packet, out).ok());
}

TEST(SecureChannel, ForgedAlteredAndReplayedPayloadsAreDropped) {
  Fixture f;
  auto [server, client] = f.connect(f.token(0), address(1, 5000));
  std::vector<uint8_t> packet;
  std::vector<uint8_t> out = {0xAA};
  const std::vector<uint8_t> body = {1, 2, 3};
  client.seal(body, packet);
  // Every single-bit change is refused, and leaves the session as it was.
  for (size_t i = 0; i < packet.size(); ++i) {
    std::vector<uint8_t> bad = packet;
    bad[i] ^= 0x10;
    EXPECT_FALSE(server.session.open(bad, out).ok()) << i;
  }
  EXPECT_EQ(out, std::vector<uint8_t>{0xAA});
  ASSERT_TRUE(server.session.open(packet, out).ok());
  EXPECT_EQ(server.session.open(packet, out).code(), ErrorCode::kInvalidArgument);
  // A forged packet claiming a sequence a million ahead does not move the
  // window: the client's next real packets still arrive.
  std::vector<uint8_t> forged = packet;
  forged[1] = 0x40;
  forged[3] = 0x0F;
  EXPECT_FALSE(server.session.open(forged, out).ok());
  for (int k = 0; k < 5; ++k) {
    client.seal(body, packet);
    ASSERT_TRUE(server.session.open(packet, out).ok()) << k;
  }
  // Out of order inside the window is fine; older than the window is not.
  std::vector<std::vector<uint8_t>> held(300);
  for (auto& p : held) client.seal(body, p);
  EXPECT_TRUE(server.session.open(held[299], out).ok());
  EXPECT_TRUE(server.session.open(held[100], out).ok());
  EXPECT_FALSE(server.session.open(held[10], out).ok());
  EXPECT_FALSE(server.session.open(held[100], out).ok());
}

TEST(ReplayWindow, TracksTheLast256Sequences) {
  ReplayWindow w;
  EXPECT_TRUE(w.fresh(0));
  w.accept(0);
  EXPECT_FALSE(w.fresh(0));
  w.accept(300);
  EXPECT_FALSE(w.fresh(0));
  EXPECT_TRUE(w.fresh(299));
  EXPECT_TRUE(w.fresh(45));
  EXPECT_FALSE(w.fresh(44));
  w.accept(299);
  EXPECT_FALSE(w.fresh(299));
  EXPECT_TRUE(w.fresh(298));
  w.accept(100'000);
  EXPECT_TRUE(w.fresh(99'999));
  EXPECT_FALSE(w.fresh(300));
}

}  // namespace
}  // namespace rwd::net
