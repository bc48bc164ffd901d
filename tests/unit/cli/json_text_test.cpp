// SPDX-License-Identifier: MIT
#include "rewind/cli/json_text.h"

#include <gtest/gtest.h>

#include <string>

namespace rwd::cli {
namespace {

TEST(JsonString, QuotesPlainText) {
  EXPECT_EQ(json_string("pile 1000"), "\"pile 1000\"");
  EXPECT_EQ(json_string(""), "\"\"");
}

TEST(JsonString, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(json_string("a \"b\" c\\d"), "\"a \\\"b\\\" c\\\\d\"");
  EXPECT_EQ(json_string("line\nnext\ttab"), "\"line\\nnext\\ttab\"");
  EXPECT_EQ(json_string(std::string("bell\x07") + std::string(1, 0) + "end"),
            "\"bell\\u0007\\u0000end\"");
}

TEST(JsonString, PassesUtf8Through) {
  EXPECT_EQ(json_string("µs per box"), "\"µs per box\"");
}

}  // namespace
}  // namespace rwd::cli
