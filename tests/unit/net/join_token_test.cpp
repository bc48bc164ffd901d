// SPDX-License-Identifier: MIT
#include "rewind/net/join_token.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rwd::net {
namespace {

constexpr std::string_view kSecret = "server-secret-for-tests";
constexpr int64_t kNow = 1'700'000'000;

std::vector<uint8_t> token(uint32_t slot = 3, std::string_view match = "match-42",
                           int64_t expiry = kNow + 60) {
  Result<std::vector<uint8_t>> t = make_join_token(kSecret, slot, match, expiry);
  EXPECT_TRUE(t.ok()) << t.status().message();
  return t.ok() ? *t : std::vector<uint8_t>{};
}

void expect_error(const Result<uint32_t>& r, ErrorCode code, const std::string& needle) {
  ASSERT_FALSE(r.ok()) << "accepted, expected " << needle;
  EXPECT_EQ(r.status().code(), code);
  EXPECT_NE(r.status().message().find(needle), std::string::npos) << r.status().message();
}

TEST(JoinToken, MakeAndVerify) {
  for (uint32_t slot : {0u, 1u, 31u, 0xFFFF'FFFFu}) {
    const std::vector<uint8_t> t = token(slot);
    ASSERT_EQ(t.size(), kJoinTokenBytes);
    Result<uint32_t> r = verify_join_token(kSecret, t, "match-42", kNow);
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_EQ(*r, slot);
  }
  // Deterministic, and different inputs give different tokens.
  EXPECT_EQ(token(1), token(1));
  EXPECT_NE(token(1), token(2));
}

TEST(JoinToken, Expiry) {
  const std::vector<uint8_t> t = token(3, "match-42", kNow + 60);
  EXPECT_TRUE(verify_join_token(kSecret, t, "match-42", kNow + 59).ok());
  expect_error(verify_join_token(kSecret, t, "match-42", kNow + 60), ErrorCode::kInvalidArgument,
               "expired");
  expect_error(verify_join_token(kSecret, t, "match-42", kNow + 100'000),
               ErrorCode::kInvalidArgument, "expired");
}

TEST(JoinToken, WrongMatch) {
  expect_error(verify_join_token(kSecret, token(), "match-43", kNow), ErrorCode::kInvalidArgument,
               "wrong match");
}

TEST(JoinToken, BadLength) {
  std::vector<uint8_t> t = token();
  t.pop_back();
  expect_error(verify_join_token(kSecret, t, "match-42", kNow), ErrorCode::kCorrupt,
               "bad length 36");
  expect_error(verify_join_token(kSecret, {}, "match-42", kNow), ErrorCode::kCorrupt,
               "bad length 0");
  t = token();
  t.push_back(0);
  expect_error(verify_join_token(kSecret, t, "match-42", kNow), ErrorCode::kCorrupt, "bad length");
}

TEST(JoinToken, AnyTamperedBitIsRejected) {
  const std::vector<uint8_t> good = token();
  for (size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> t = good;
      t[byte] ^= static_cast<uint8_t>(1u << bit);
      Result<uint32_t> r = verify_join_token(kSecret, t, "match-42", kNow);
      ASSERT_FALSE(r.ok()) << "byte " << byte << " bit " << bit;
      // Byte 0 is the version; everything else fails the MAC.
      EXPECT_EQ(r.status().code(), byte == 0 ? ErrorCode::kCorrupt : ErrorCode::kInvalidArgument);
      if (byte != 0) {
        EXPECT_NE(r.status().message().find("bad MAC"), std::string::npos);
      }
    }
  }
}

TEST(JoinToken, RaisingSlotOrExpiryWithoutSecretFails) {
  // An attacker edits the slot and the expiry in place: the tag no longer matches.
  std::vector<uint8_t> t = token(3);
  t[1] = 0;      // slot 3 -> 0
  t[12] = 0x7F;  // expiry far in the future
  expect_error(verify_join_token(kSecret, t, "match-42", kNow), ErrorCode::kInvalidArgument,
               "bad MAC");
}

TEST(JoinToken, OtherSecretFails) {
  expect_error(verify_join_token("another-secret", token(), "match-42", kNow),
               ErrorCode::kInvalidArgument, "bad MAC");
  // A prefix of the real secret is a different key too.
  expect_error(verify_join_token(kSecret.substr(0, 10), token(), "match-42", kNow),
               ErrorCode::kInvalidArgument, "bad MAC");
}

TEST(JoinToken, EmptySecretRefused) {
  EXPECT_FALSE(make_join_token("", 1, "m", kNow).ok());
  expect_error(verify_join_token("", token(), "match-42", kNow), ErrorCode::kInvalidArgument,
               "empty server secret");
}

}  // namespace
}  // namespace rwd::net
