// SPDX-License-Identifier: MIT
// Bearer key files: what parses, what is refused with its line, and which
// Authorization headers name which caller.
#include "rewind/server/api_keys.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

constexpr std::string_view kFile =
    "# callers of the control API\n"
    "\n"
    "backend  0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef\n"
    "ops\tfedcba9876543210fedcba9876543210  admin\r\n";

TEST(ApiKeys, NamesTheCallerOfAKnownKey) {
  auto keys = ApiKeys::parse(kFile);
  ASSERT_TRUE(keys.ok()) << keys.status().message();
  EXPECT_EQ(keys->size(), 2u);
  auto backend =
      keys->authenticate("Bearer 0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef");
  ASSERT_TRUE(backend.has_value());
  EXPECT_EQ(backend->name, "backend");
  EXPECT_FALSE(backend->admin);
  auto ops = keys->authenticate("bearer   fedcba9876543210fedcba9876543210 ");
  ASSERT_TRUE(ops.has_value());
  EXPECT_EQ(ops->name, "ops");
  EXPECT_TRUE(ops->admin);
}

TEST(ApiKeys, AnythingElseNamesNobody) {
  auto keys = ApiKeys::parse(kFile);
  ASSERT_TRUE(keys.ok());
  EXPECT_FALSE(keys->authenticate(""));
  EXPECT_FALSE(keys->authenticate("Bearer "));
  EXPECT_FALSE(keys->authenticate("Basic fedcba9876543210fedcba9876543210"));
  EXPECT_FALSE(keys->authenticate("Bearer fedcba9876543210fedcba987654321"));    // one short
  EXPECT_FALSE(keys->authenticate("Bearer fedcba9876543210fedcba98765432100"));  // one long
  EXPECT_FALSE(keys->authenticate("Bearer FEDCBA9876543210FEDCBA9876543210"));   // keys are exact
  EXPECT_FALSE(keys->authenticate("fedcba9876543210fedcba9876543210"));
}

TEST(ApiKeys, BadFilesNameTheirLine) {
  const std::string key = "0123456789abcdef0123456789abcdef";
  auto expect_bad = [](std::string_view text, std::string_view why) {
    auto keys = ApiKeys::parse(text);
    ASSERT_FALSE(keys.ok()) << text;
    EXPECT_EQ(keys.status().code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(keys.status().message().find(why), std::string::npos) << keys.status().message();
  };
  expect_bad("", "no keys");
  expect_bad("# only a comment\n", "no keys");
  expect_bad("backend\n", "line 1");
  expect_bad("a " + key + "\nb short\n", "line 2");
  expect_bad("a " + key + " root\n", "'admin'");
  expect_bad("a/b " + key + "\n", "name");
  expect_bad("a " + key + "\na " + key + "x\n", "twice");
  expect_bad("a " + key + "\nb " + key + "\n", "twice");
  expect_bad("a " + key + " admin extra\n", "line 1");
}

TEST(ApiKeys, AMissingFileIsAnIoError) {
  auto keys = ApiKeys::load("/nonexistent/rewind/keys");
  ASSERT_FALSE(keys.ok());
  EXPECT_EQ(keys.status().code(), ErrorCode::kIo);
  EXPECT_NE(keys.status().message().find("/nonexistent/rewind/keys"), std::string::npos);
}

}  // namespace
}  // namespace rwd::server
