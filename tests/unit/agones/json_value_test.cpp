// SPDX-License-Identifier: MIT
// The strict JSON reader: every kind of value, escapes and UTF-8, and each
// thing RFC 8259 forbids refused with a message naming it and where.
#include "rewind/server/json_value.h"

#include <gtest/gtest.h>

#include <string>

namespace rwd::server {
namespace {

using Kind = JsonValue::Kind;

JsonValue parse_ok(std::string_view text) {
  auto value = parse_json(text);
  EXPECT_TRUE(value.ok()) << text << ": " << value.status().message();
  return value.ok() ? *value : JsonValue::null();
}

// The error message for `text`, which must be refused as kCorrupt.
std::string refused(std::string_view text) {
  auto value = parse_json(text);
  EXPECT_FALSE(value.ok()) << "accepted: " << text;
  if (value.ok()) return "";
  EXPECT_EQ(value.status().code(), ErrorCode::kCorrupt) << text;
  return value.status().message();
}

TEST(JsonValue, ReadsEveryKind) {
  const JsonValue v =
      parse_ok(R"( {"s":"text","n":-12.5e1,"t":true,"f":false,"z":null,"a":[1,"two",[]],"o":{}} )");
  ASSERT_TRUE(v.is(Kind::kObject));
  EXPECT_EQ(v.keys(), (std::vector<std::string>{"s", "n", "t", "f", "z", "a", "o"}));
  EXPECT_EQ(v.find("s")->as_string(), "text");
  EXPECT_EQ(v.find("n")->as_number(), -125.0);
  EXPECT_TRUE(v.find("t")->as_bool());
  EXPECT_TRUE(v.find("f")->is(Kind::kBool));
  EXPECT_FALSE(v.find("f")->as_bool());
  EXPECT_TRUE(v.find("z")->is(Kind::kNull));
  const JsonValue& a = *v.find("a");
  ASSERT_EQ(a.items().size(), 3u);
  EXPECT_EQ(a.items()[0].as_number(), 1.0);
  EXPECT_EQ(a.items()[1].as_string(), "two");
  EXPECT_TRUE(a.items()[2].is(Kind::kArray));
  EXPECT_TRUE(v.find("o")->is(Kind::kObject));
  EXPECT_EQ(v.find("missing"), nullptr);
  EXPECT_EQ(a.find("s"), nullptr);  // not an object
}

TEST(JsonValue, TopLevelScalars) {
  EXPECT_EQ(parse_ok("0").as_number(), 0.0);
  EXPECT_EQ(parse_ok("\"x\"").as_string(), "x");
  EXPECT_TRUE(parse_ok("null").is(Kind::kNull));
  EXPECT_EQ(parse_ok("\n\t 7 \r\n").as_number(), 7.0);
}

TEST(JsonValue, Numbers) {
  EXPECT_EQ(parse_ok("0.5").as_number(), 0.5);
  EXPECT_EQ(parse_ok("-0").as_number(), 0.0);
  EXPECT_EQ(parse_ok("1E3").as_number(), 1000.0);
  EXPECT_EQ(parse_ok("2e+2").as_number(), 200.0);
  EXPECT_EQ(parse_ok("7777").as_number(), 7777.0);
  EXPECT_EQ(parse_ok("1e-400").as_number(), 0.0);  // underflow is a tiny number
  EXPECT_NE(refused("1e400").find("number out of range"), std::string::npos);
  EXPECT_NE(refused("-1e999").find("number out of range"), std::string::npos);
  EXPECT_NE(refused("01").find("leading zero"), std::string::npos);
  EXPECT_NE(refused("1.").find("digit after '.'"), std::string::npos);
  EXPECT_NE(refused(".5").find("unexpected character"), std::string::npos);
  EXPECT_NE(refused("1e").find("exponent"), std::string::npos);
  EXPECT_NE(refused("-").find("expected a digit"), std::string::npos);
  refused("+1");
  refused("0x10");
  refused("NaN");
  refused("Infinity");
}

TEST(JsonValue, StringsAndEscapes) {
  EXPECT_EQ(parse_ok(R"("a\"b\\c\/d\b\f\n\r\t")").as_string(), "a\"b\\c/d\b\f\n\r\t");
  EXPECT_EQ(parse_ok(R"("\u0041\u00e9\u20AC")").as_string(), "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(parse_ok(R"("\ud83d\ude00")").as_string(), "\xF0\x9F\x98\x80");
  EXPECT_EQ(parse_ok("\"\xC3\xA9\xF0\x9F\x98\x80\"").as_string(), "\xC3\xA9\xF0\x9F\x98\x80");
  EXPECT_EQ(parse_ok(R"("\u0000")").as_string(), std::string(1, '\0'));
  EXPECT_NE(refused(R"("\ud83d")").find("without its low half"), std::string::npos);
  EXPECT_NE(refused(R"("\ud83dx")").find("without its low half"), std::string::npos);
  EXPECT_NE(refused(R"("\ude00")").find("lone low surrogate"), std::string::npos);
  EXPECT_NE(refused(R"("\u12")").find("escape"), std::string::npos);
  EXPECT_NE(refused(R"("\uZZZZ")").find("bad hex digit"), std::string::npos);
  EXPECT_NE(refused(R"("\x")").find("unknown escape"), std::string::npos);
  EXPECT_NE(refused("\"a\nb\"").find("control character"), std::string::npos);
  EXPECT_NE(refused("\"abc").find("unterminated string"), std::string::npos);
  EXPECT_NE(refused("\"\\").find("unterminated string"), std::string::npos);
}

TEST(JsonValue, InvalidUtf8IsRefused) {
  for (std::string_view bad : {"\"\xC0\x80\"", "\"\xE0\x80\x80\"", "\"\xED\xA0\x80\"",
                               "\"\xF4\x90\x80\x80\"", "\"\xFF\"", "\"\x80\"", "\"\xC3\""}) {
    EXPECT_NE(refused(bad).find("invalid UTF-8"), std::string::npos) << bad;
  }
}

TEST(JsonValue, StructureErrorsNameWhereTheyAre) {
  EXPECT_EQ(refused("[1,]"), "JSON: unexpected character at byte 3");
  EXPECT_NE(refused("{\"a\":1,}").find("expected a string key"), std::string::npos);
  EXPECT_NE(refused("{\"a\" 1}").find("expected ':'"), std::string::npos);
  EXPECT_NE(refused("{a:1}").find("expected a string key"), std::string::npos);
  EXPECT_NE(refused("[1 2]").find("expected ',' or ']'"), std::string::npos);
  EXPECT_NE(refused("[1").find("unterminated array"), std::string::npos);
  EXPECT_NE(refused("{\"a\":1").find("unterminated object"), std::string::npos);
  EXPECT_EQ(refused("{} {}"), "JSON: unexpected data after the value at byte 3");
  EXPECT_NE(refused("// c\n{}").find("unexpected character"), std::string::npos);
  EXPECT_NE(refused("").find("unexpected end of input"), std::string::npos);
  EXPECT_NE(refused("   ").find("unexpected end of input"), std::string::npos);
  EXPECT_NE(refused("tru").find("unexpected character"), std::string::npos);
  EXPECT_NE(refused("nul").find("unexpected character"), std::string::npos);
  EXPECT_NE(refused("[true false]").find("expected ',' or ']'"), std::string::npos);
}

TEST(JsonValue, DuplicateKeysAreRefused) {
  EXPECT_EQ(refused(R"({"b":1,"a":2,"b":3})"), "JSON: duplicate key in the object at byte 0");
  // The same key in different objects is fine.
  parse_ok(R"({"a":{"a":1},"b":{"a":2}})");
}

TEST(JsonValue, DepthIsBounded) {
  JsonLimits limits;
  limits.max_depth = 4;
  EXPECT_TRUE(parse_json("[[[[1]]]]", limits).ok());
  EXPECT_TRUE(parse_json(R"({"a":{"b":[{}]}})", limits).ok());
  auto deep = parse_json("[[[[[1]]]]]", limits);
  ASSERT_FALSE(deep.ok());
  EXPECT_EQ(deep.status().message(), "JSON: nesting deeper than 4 at byte 4");
  // The default bound stops a deep document long before the stack would.
  const std::string hostile = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_NE(refused(hostile).find("nesting deeper than 32"), std::string::npos);
}

TEST(JsonValue, SizeIsBounded) {
  JsonLimits limits;
  limits.max_bytes = 8;
  EXPECT_TRUE(parse_json("[1,2,3]", limits).ok());
  auto big = parse_json("[1,2,3,4]", limits);
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.status().code(), ErrorCode::kCapacity);
  EXPECT_EQ(big.status().message(), "JSON: 9 bytes, more than the limit of 8");
}

TEST(JsonValue, Equality) {
  EXPECT_EQ(parse_ok(R"({"a":[1,"x",null]})"), parse_ok(R"( { "a" : [ 1.0 , "x" , null ] } )"));
  EXPECT_FALSE(parse_ok(R"({"a":1})") == parse_ok(R"({"a":2})"));
  EXPECT_FALSE(parse_ok(R"({"a":1,"b":2})") == parse_ok(R"({"b":2,"a":1})"));  // order kept
}

}  // namespace
}  // namespace rwd::server
