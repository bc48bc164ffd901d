// SPDX-License-Identifier: MIT
#pragma once
// The server's log lines on stderr, readable by people (the default) or one
// JSON object per line for a log pipeline (--log-json).
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace rwd::server {

enum class LogLevel : uint8_t { kInfo, kWarning, kError };
enum class LogFormat : uint8_t { kText, kJson };

/// Chooses how every later log line reads; set once at start-up, before the
/// server logs anything. The default is kText.
void set_log_format(LogFormat format);

/// Writes one line to stderr. kText: "[rewind-server] text", warnings as
/// "[rewind-server] WARNING: text", errors as "rewind-server: text".
/// kJson: log_json_line() at the current time.
void write_log(LogLevel level, std::string_view text);

/// One log line as a JSON object, without the newline:
/// {"ts":"2024-05-01T12:00:00.123Z","level":"info","msg":"..."}; `ts` is UTC
/// with milliseconds, `level` is "info", "warning" or "error".
std::string log_json_line(LogLevel level, std::string_view text,
                          std::chrono::system_clock::time_point when);

}  // namespace rwd::server
