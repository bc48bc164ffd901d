// SPDX-License-Identifier: MIT
// Address cookies for tokenless servers: a Hello of the right size and
// version gets a cookie no larger than itself, anything else nothing; a
// join opens only with the cookie made for its own address and port, in
// its window or the next, under the same process key.
#include "rewind/net/address_cookie.h"

#include <gtest/gtest.h>

namespace rwd::net {
namespace {

constexpr int64_t kNow = 1'000'000;

PeerAddress address(uint8_t last, uint16_t port) {
  PeerAddress a;
  a.ip[10] = 0xff;
  a.ip[11] = 0xff;
  a.ip[12] = 127;
  a.ip[15] = last;
  a.port = port;
  return a;
}

AddressCookie cookie_from(const AddressCookieGate& gate, const PeerAddress& from, int64_t now) {
  std::vector<uint8_t> reply;
  EXPECT_TRUE(gate.on_hello(make_hello(), from, now, reply).ok());
  EXPECT_LE(reply.size(), kHelloBytes);
  const std::optional<AddressCookie> cookie = read_cookie(reply);
  EXPECT_TRUE(cookie.has_value());
  return cookie.value_or(AddressCookie{});
}

TEST(AddressCookie, AHelloGetsASmallerCookieAndNothingElseDoes) {
  const AddressCookieGate gate(generate_key());
  std::vector<uint8_t> reply;
  const std::vector<uint8_t> hello = make_hello();
  ASSERT_EQ(hello.size(), kHelloBytes);
  ASSERT_TRUE(gate.on_hello(hello, address(1, 5000), kNow, reply).ok());
  EXPECT_EQ(reply.size(), kCookieReplyBytes);
  EXPECT_LT(reply.size(), hello.size());
  EXPECT_EQ(cookie_packet_kind(reply), CookiePacket::kCookie);
  std::vector<uint8_t> bad = hello;
  bad.pop_back();
  EXPECT_FALSE(gate.on_hello(bad, address(1, 5000), kNow, reply).ok());
  EXPECT_TRUE(reply.empty());
  bad = hello;
  bad[1] = kAddressCookieVersion + 1;
  EXPECT_FALSE(gate.on_hello(bad, address(1, 5000), kNow, reply).ok());
  bad = hello;
  bad[0] = static_cast<uint8_t>(CookiePacket::kJoin);
  EXPECT_FALSE(gate.on_hello(bad, address(1, 5000), kNow, reply).ok());
  EXPECT_TRUE(reply.empty());
}

TEST(AddressCookie, AJoinOpensOnlyWithItsAddresssCookieInTime) {
  const AddressCookieGate gate(generate_key());
  const PeerAddress client = address(1, 5000);
  const AddressCookie cookie = cookie_from(gate, client, kNow);
  const std::vector<uint8_t> envelope = {0x08, 0x02, 0x52, 0x00};
  std::vector<uint8_t> join;
  frame_join(cookie, envelope, join);
  ASSERT_EQ(cookie_packet_kind(join), CookiePacket::kJoin);
  auto opened = gate.open_join(join, client, kNow);
  ASSERT_TRUE(opened.ok());
  EXPECT_EQ(std::vector<uint8_t>(opened->begin(), opened->end()), envelope);
  // Another port, another address, another process's key: refused.
  EXPECT_FALSE(gate.open_join(join, address(1, 5001), kNow).ok());
  EXPECT_FALSE(gate.open_join(join, address(2, 5000), kNow).ok());
  EXPECT_FALSE(AddressCookieGate(generate_key()).open_join(join, client, kNow).ok());
  // A byte of the cookie changed, or no envelope after it.
  std::vector<uint8_t> altered = join;
  altered[5] ^= 1;
  EXPECT_FALSE(gate.open_join(altered, client, kNow).ok());
  frame_join(cookie, {}, altered);
  EXPECT_FALSE(gate.open_join(altered, client, kNow).ok());
  // Good through the next window; two windows on, too old.
  const int64_t window_end = (kNow / kCookieWindowS + 1) * kCookieWindowS;
  EXPECT_TRUE(gate.open_join(join, client, window_end + kCookieWindowS - 1).ok());
  EXPECT_FALSE(gate.open_join(join, client, window_end + kCookieWindowS).ok());
}

}  // namespace
}  // namespace rwd::net
