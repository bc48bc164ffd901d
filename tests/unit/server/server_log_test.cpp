// SPDX-License-Identifier: MIT
// --log-json lines: a UTC timestamp with milliseconds, the level by name and
// the message as a properly escaped JSON string.
#include "rewind/server/server_log.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

std::chrono::system_clock::time_point at_ms(int64_t ms_since_epoch) {
  return std::chrono::system_clock::time_point(std::chrono::milliseconds(ms_since_epoch));
}

TEST(LogJsonLine, HasTimestampLevelAndMessage) {
  // 2024-05-01T12:34:56.789Z
  EXPECT_EQ(log_json_line(LogLevel::kInfo, "match ends: tick budget reached", at_ms(1714566896789)),
            "{\"ts\":\"2024-05-01T12:34:56.789Z\",\"level\":\"info\","
            "\"msg\":\"match ends: tick budget reached\"}");
  EXPECT_EQ(log_json_line(LogLevel::kWarning, "x", at_ms(5)),
            "{\"ts\":\"1970-01-01T00:00:00.005Z\",\"level\":\"warning\",\"msg\":\"x\"}");
  EXPECT_EQ(log_json_line(LogLevel::kError, "", at_ms(0)),
            "{\"ts\":\"1970-01-01T00:00:00.000Z\",\"level\":\"error\",\"msg\":\"\"}");
}

TEST(LogJsonLine, EscapesTheMessage) {
  const std::string line =
      log_json_line(LogLevel::kInfo, "a \"quoted\" \\path\\\nnext\tline\x01", at_ms(0));
  EXPECT_NE(line.find("\"msg\":\"a \\\"quoted\\\" \\\\path\\\\\\nnext\\tline\\u0001\"}"),
            std::string::npos)
      << line;
  EXPECT_EQ(line.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace rwd::server
