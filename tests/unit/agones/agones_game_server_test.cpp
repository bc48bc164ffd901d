// SPDX-License-Identifier: MIT
// Reading the GameServer record: the shape the REST API documents, types
// checked where the server reads, and the whole document held to RFC 8259
// with its size, depth and keys bounded.
#include "rewind/server/agones_game_server.h"

#include <gtest/gtest.h>

#include <string>

namespace rwd::server {
namespace {

// The GET /gameserver answer as the REST API documents it.
constexpr std::string_view kDocumented = R"({
  "object_meta": {
    "name": "local", "namespace": "default", "uid": "1234", "resource_version": "v1",
    "generation": "1", "creation_timestamp": "1531795395",
    "annotations": {"annotation": "true", "rewind.dev/players": "4"},
    "labels": {"islocal": "true"}
  },
  "status": {"state": "Ready", "address": "127.0.0.1",
             "ports": [{"name": "default", "port": 7777}, {"name": "alt", "port": "7778"}]}
})";

// The error message for `json`, which must be refused as kCorrupt.
std::string refused(std::string_view json) {
  auto gs = parse_agones_game_server(json);
  EXPECT_FALSE(gs.ok()) << "accepted: " << json;
  if (gs.ok()) return "";
  EXPECT_EQ(gs.status().code(), ErrorCode::kCorrupt) << json;
  return gs.status().message();
}

TEST(AgonesGameServer, ReadsTheDocumentedShape) {
  auto gs = parse_agones_game_server(kDocumented);
  ASSERT_TRUE(gs.ok()) << gs.status().message();
  EXPECT_EQ(gs->name, "local");
  EXPECT_EQ(gs->state, "Ready");
  EXPECT_EQ(gs->address, "127.0.0.1");
  ASSERT_EQ(gs->ports.size(), 2u);
  EXPECT_EQ(gs->ports[0].name, "default");
  EXPECT_EQ(gs->ports[0].port, 7777);
  EXPECT_EQ(gs->ports[1].port, 7778);
  EXPECT_EQ(gs->annotations.at("rewind.dev/players"), "4");
  EXPECT_EQ(gs->labels.at("islocal"), "true");
}

TEST(AgonesGameServer, AbsentFieldsReadAsEmpty) {
  auto gs = parse_agones_game_server(R"({"status":{"state":"Scheduled","ports":null}})");
  ASSERT_TRUE(gs.ok()) << gs.status().message();
  EXPECT_EQ(gs->state, "Scheduled");
  EXPECT_TRUE(gs->name.empty());
  EXPECT_TRUE(gs->ports.empty());
  EXPECT_TRUE(gs->annotations.empty());
  EXPECT_TRUE(parse_agones_game_server("{}").ok());
  EXPECT_TRUE(parse_agones_game_server(" \t\r\n{}\n").ok());
}

TEST(AgonesGameServer, PortsAreIntegersInRange) {
  auto gs = parse_agones_game_server(
      R"({"status":{"ports":[{"port":0},{"port":65535},{"port":7.0e3},{"port":"00080"},{}]}})");
  ASSERT_TRUE(gs.ok()) << gs.status().message();
  ASSERT_EQ(gs->ports.size(), 5u);
  EXPECT_EQ(gs->ports[0].port, 0);
  EXPECT_EQ(gs->ports[1].port, 65535);
  EXPECT_EQ(gs->ports[2].port, 7000);
  EXPECT_EQ(gs->ports[3].port, 80);
  EXPECT_EQ(gs->ports[4].port, 0);
  for (std::string_view bad :
       {"70000", "-1", "7777.5", "\"7a\"", "\"\"", "\"123456\"", "true", "[7777]", "1e300"}) {
    EXPECT_EQ(refused(R"({"status":{"ports":[{"port":)" + std::string(bad) + "}]}}"),
              "GameServer: status.ports[].port is not a port number in [0, 65535]")
        << bad;
  }
}

TEST(AgonesGameServer, WrongTypesAreRefused) {
  EXPECT_EQ(refused("[]"), "GameServer: the document is not an object");
  EXPECT_EQ(refused("\"x\""), "GameServer: the document is not an object");
  EXPECT_EQ(refused(R"({"status":{"state":3}})"),
            "GameServer: status.state is a number, not a string");
  EXPECT_EQ(refused(R"({"object_meta":{"labels":{"a":1}}})"),
            "GameServer: object_meta.labels[\"a\"] is not a string");
  EXPECT_EQ(refused(R"({"object_meta":"x"})"),
            "GameServer: object_meta is a string, not an object");
  EXPECT_EQ(refused(R"({"status":{"ports":{}}})"),
            "GameServer: status.ports is an object, not an array");
  EXPECT_EQ(refused(R"({"status":{"ports":[7777]}})"),
            "GameServer: status.ports[] is not an object");
  EXPECT_EQ(refused(R"({"object_meta":{"annotations":[]}})"),
            "GameServer: object_meta.annotations is an array, not an object");
}

TEST(AgonesGameServer, MalformedJsonIsRefusedWithItsPlace) {
  EXPECT_EQ(refused("{"),
            "GameServer: JSON: parse error at line 1, column 2: syntax error while parsing object "
            "key - unexpected end of input; expected string literal");
  EXPECT_EQ(refused(R"({"a":1e400})"), "GameServer: JSON: number overflow parsing '1e400'");
  for (std::string_view bad : {
           R"({"a":1,})",        // trailing comma
           R"([1,])",            // trailing comma
           "// c\n{}",           // comment
           "{} {}",              // data after the value
           R"({"a":01})",        // leading zero
           R"({"a":1e400})",     // beyond a double
           R"({"a":-1e999})",    // beyond a double
           R"({"a":NaN})",       // not JSON
           R"({"a":.5})",        // not JSON
           R"({a:1})",           // unquoted key
           R"({"a":"\ud83d"})",  // lone high surrogate
           R"({"a":"\ude00"})",  // lone low surrogate
           R"({"a":"\x"})",      // unknown escape
           "{\"a\":\"x\ny\"}",   // control character in a string
           "",                   // nothing
           "   ",                // nothing
       }) {
    EXPECT_NE(refused(bad).rfind("GameServer: JSON: ", 0), std::string::npos) << bad;
  }
}

TEST(AgonesGameServer, InvalidUtf8IsRefused) {
  for (std::string_view bad :
       {"\xC0\x80", "\xE0\x80\x80", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xFF", "\x80", "\xC3"}) {
    const std::string message =
        refused(R"({"object_meta":{"labels":{"a":")" + std::string(bad) + R"("}}})");
    EXPECT_NE(message.rfind("GameServer: JSON: ", 0), std::string::npos) << message;
  }
  // Valid UTF-8 and escapes come through decoded.
  auto gs = parse_agones_game_server(
      R"({"object_meta":{"name":"\u00e9\ud83d\ude00\u0041","labels":{"k":"é😀"}}})");
  ASSERT_TRUE(gs.ok()) << gs.status().message();
  EXPECT_EQ(gs->name,
            "\xC3\xA9\xF0\x9F\x98\x80"
            "A");
  EXPECT_EQ(gs->labels.at("k"), "\xC3\xA9\xF0\x9F\x98\x80");
}

TEST(AgonesGameServer, ErrorMessagesArePrintable) {
  // The message quotes where parsing stopped: bytes that are not printable
  // ASCII are masked, so the log line it goes to cannot be forged.
  const std::string message = refused("{\"a\":\"x\x1b[2J\xFF\"}");
  for (const char c : message) {
    EXPECT_TRUE(c >= 0x20 && c < 0x7f) << message;
  }
}

TEST(AgonesGameServer, DuplicateKeysAreRefused) {
  // Two annotations of one name: a reader keeping the first and one keeping
  // the last would disagree on the setting.
  EXPECT_EQ(refused(R"({"object_meta":{"annotations":{"rewind.dev/players":"2",)"
                    R"("rewind.dev/players":"32"}}})"),
            "GameServer: JSON: duplicate key \"rewind.dev/players\" in an object");
  EXPECT_EQ(refused(R"({"status":{},"status":{"state":"Allocated"}})"),
            "GameServer: JSON: duplicate key \"status\" in an object");
  // Anywhere in the document, used or not.
  EXPECT_NE(refused(R"({"x":[{"k":1,"k":2}]})").find("duplicate key"), std::string::npos);
  // The same key in different objects is fine.
  EXPECT_TRUE(parse_agones_game_server(R"({"a":{"a":1},"b":{"a":2},"c":[{"a":1},{"a":2}]})").ok());
}

TEST(AgonesGameServer, DepthIsBounded) {
  auto nested = [](int depth) {
    // The document is one level; the rest are arrays inside it.
    return "{\"x\":" + std::string(static_cast<size_t>(depth - 1), '[') +
           std::string(static_cast<size_t>(depth - 1), ']') + "}";
  };
  EXPECT_TRUE(parse_agones_game_server(nested(kAgonesGameServerMaxDepth)).ok());
  EXPECT_EQ(refused(nested(kAgonesGameServerMaxDepth + 1)),
            "GameServer: JSON: nesting deeper than 32");
  // A hostile depth is refused at the bound, long before memory matters.
  const std::string hostile = std::string(400000, '[') + std::string(400000, ']');
  EXPECT_EQ(refused(hostile), "GameServer: JSON: nesting deeper than 32");
}

TEST(AgonesGameServer, SizeIsBounded) {
  std::string padded = R"({"pad":")" + std::string(kAgonesGameServerMaxBytes, ' ') + R"("})";
  EXPECT_EQ(refused(padded), "GameServer: JSON: " + std::to_string(padded.size()) +
                                 " bytes, more than the limit of " +
                                 std::to_string(kAgonesGameServerMaxBytes));
  padded = R"({"pad":")" + std::string(kAgonesGameServerMaxBytes - 10, ' ') + R"("})";
  EXPECT_TRUE(parse_agones_game_server(padded).ok());
}

}  // namespace
}  // namespace rwd::server
