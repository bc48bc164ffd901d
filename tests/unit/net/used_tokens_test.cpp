// SPDX-License-Identifier: MIT
// The tokens a server accepted: each is used once until it expires; the
// memory is bounded, pruning expired tokens first and refusing new ones
// rather than forgetting one that has not expired.
#include "rewind/net/used_tokens.h"

#include <gtest/gtest.h>

namespace rwd::net {
namespace {

constexpr int64_t kNow = 1'800'000'000;

TokenMac mac(uint8_t n) {
  TokenMac m{};
  m.fill(n);
  m[15] = static_cast<uint8_t>(n ^ 0xA5);
  return m;
}

TEST(UsedTokens, ATokenIsUsedOnceUntilItExpires) {
  UsedTokens used;
  EXPECT_FALSE(used.used(mac(1), kNow));
  EXPECT_EQ(used.record(mac(1), kNow + 60, kNow), UsedTokens::Outcome::kRecorded);
  EXPECT_TRUE(used.used(mac(1), kNow + 59));
  EXPECT_EQ(used.record(mac(1), kNow + 60, kNow + 30), UsedTokens::Outcome::kAlreadyUsed);
  EXPECT_FALSE(used.used(mac(2), kNow));
  EXPECT_FALSE(used.used(mac(1), kNow + 60));  // expired: the token opens no more anyway
}

TEST(UsedTokens, WhenFullExpiredTokensGoAndUnexpiredOnesStay) {
  UsedTokens used(3);
  EXPECT_EQ(used.record(mac(1), kNow + 10, kNow), UsedTokens::Outcome::kRecorded);
  EXPECT_EQ(used.record(mac(2), kNow + 100, kNow), UsedTokens::Outcome::kRecorded);
  EXPECT_EQ(used.record(mac(3), kNow + 100, kNow), UsedTokens::Outcome::kRecorded);
  // Full of unexpired tokens: a fourth is refused, and none is forgotten.
  EXPECT_EQ(used.record(mac(4), kNow + 100, kNow + 5), UsedTokens::Outcome::kFull);
  EXPECT_TRUE(used.used(mac(1), kNow + 5));
  EXPECT_EQ(used.size(), 3u);
  // Once the first expires it is pruned to make room.
  EXPECT_EQ(used.record(mac(4), kNow + 100, kNow + 10), UsedTokens::Outcome::kRecorded);
  EXPECT_EQ(used.size(), 3u);
  EXPECT_TRUE(used.used(mac(2), kNow + 10));
  EXPECT_TRUE(used.used(mac(4), kNow + 10));
  EXPECT_EQ(used.record(mac(5), kNow + 100, kNow + 10), UsedTokens::Outcome::kFull);
}

}  // namespace
}  // namespace rwd::net
