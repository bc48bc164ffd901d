// SPDX-License-Identifier: MIT
// Runs fuzz_secure_packet_one over a deterministic corpus: real requests,
// challenges, responses, payloads and tokens, all their truncations and
// mutations, and random bytes. A broken invariant aborts, failing the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"

namespace {

std::vector<std::vector<uint8_t>> seeds() {
  using namespace rwd::net;
  const Key server = generate_key();
  const ConnectToken token =
      *make_connect_token(server, "seed", 1, 9, 1'900'000'060, 1'900'000'000);
  ServerGate gate(server, generate_key(), connect_match_tag("seed"));
  ClientHandshake client(token);
  PeerAddress from;
  std::vector<uint8_t> challenge;
  std::vector<uint8_t> response;
  EXPECT_TRUE(gate.on_request(client.request(), from, 1'900'000'000, challenge).ok());
  EXPECT_TRUE(client.on_challenge(challenge, response).ok());
  std::vector<uint8_t> payload;
  client.session()->seal(std::vector<uint8_t>(40, 7), payload);
  const std::vector<uint8_t> hex_bytes = [&] {
    const std::string hex = to_hex(write_connect_token(token));
    return std::vector<uint8_t>(hex.begin(), hex.end());
  }();
  // A tokenless server's cookie exchange: the hello, a cookie, a join.
  const AddressCookieGate cookies(generate_key());
  std::vector<uint8_t> cookie_reply;
  EXPECT_TRUE(cookies.on_hello(make_hello(), from, 1'900'000'000, cookie_reply).ok());
  std::vector<uint8_t> join;
  frame_join(*read_cookie(cookie_reply), std::vector<uint8_t>{0x08, 0x02, 0x52, 0x00}, join);
  return {client.request(), challenge,    response,     payload, write_connect_token(token),
          hex_bytes,        make_hello(), cookie_reply, join};
}

TEST(FuzzCorpusSecurePacket, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_secure_packet_one), 0);
}

TEST(FuzzCorpusSecurePacket, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0x5EC0'12E5'0000'0001ull, 5'000,
                                             fuzz_secure_packet_one),
            0);
}

TEST(FuzzCorpusSecurePacket, RandomBytes) {
  rwd::fuzz::CorpusRng rng{7};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 2'000; ++i) {
    bytes.resize(rng.below(1300));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    if (!bytes.empty() && i % 2 == 0) bytes[0] = static_cast<uint8_t>(0xC1 + i % 4);
    if (!bytes.empty() && i % 4 == 1) bytes[0] = static_cast<uint8_t>(0xB1 + i % 3);
    ASSERT_EQ(fuzz_secure_packet_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_secure_packet_one(nullptr, 0), 0);
}

}  // namespace
