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
/// kJson: log_json_line() at the current time. Inside a LogMatchScope the
/// line names its match: "[rewind-server] <match>: text", or a "match" key.
/// Safe from any thread; each line is written whole.
void write_log(LogLevel level, std::string_view text);

/// Names the match whose work this thread is doing in every line it logs
/// until the scope ends. A process hosts several matches on a pool of
/// threads, each match's handlers one at a time, so the name is per thread.
/// `match` must outlive the scope. Scopes nest; the innermost wins.
class LogMatchScope {
 public:
  explicit LogMatchScope(std::string_view match);
  ~LogMatchScope();
  LogMatchScope(const LogMatchScope&) = delete;
  LogMatchScope& operator=(const LogMatchScope&) = delete;

 private:
  std::string_view previous_;
};

/// One log line as a JSON object, without the newline:
/// {"ts":"2024-05-01T12:00:00.123Z","level":"info","msg":"..."}; `ts` is UTC
/// with milliseconds, `level` is "info", "warning" or "error". A non-empty
/// `match` adds "match":"<match>" after the level.
std::string log_json_line(LogLevel level, std::string_view text,
                          std::chrono::system_clock::time_point when, std::string_view match = {});

}  // namespace rwd::server
