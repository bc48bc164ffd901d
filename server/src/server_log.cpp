// SPDX-License-Identifier: MIT
#include "rewind/server/server_log.h"

#include <cstdio>
#include <ctime>

#include "rewind/cli/json_text.h"

namespace rwd::server {
namespace {

// Process-wide because a log is: every part of the server writes to the one
// stderr, and main() sets the format once before anything runs.
LogFormat g_format = LogFormat::kText;
thread_local std::string_view t_match;

const char* level_name(LogLevel level) {
  switch (level) {
    case LogLevel::kWarning:
      return "warning";
    case LogLevel::kError:
      return "error";
    case LogLevel::kInfo:
      break;
  }
  return "info";
}

}  // namespace

void set_log_format(LogFormat format) {
  g_format = format;
}

LogMatchScope::LogMatchScope(std::string_view match) : previous_(t_match) {
  t_match = match;
}

LogMatchScope::~LogMatchScope() {
  t_match = previous_;
}

std::string log_json_line(LogLevel level, std::string_view text,
                          std::chrono::system_clock::time_point when, std::string_view match) {
  using namespace std::chrono;
  const auto since_epoch_ms = duration_cast<milliseconds>(when.time_since_epoch()).count();
  const std::time_t seconds = static_cast<std::time_t>(since_epoch_ms / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char ts[48];
  const size_t length = std::strftime(ts, sizeof ts, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(ts + length, sizeof ts - length, ".%03dZ", static_cast<int>(since_epoch_ms % 1000));
  std::string line = std::string("{\"ts\":\"") + ts + "\",\"level\":\"" + level_name(level) + "\",";
  if (!match.empty()) line += "\"match\":" + cli::json_string(match) + ",";
  return line + "\"msg\":" + cli::json_string(text) + "}";
}

void write_log(LogLevel level, std::string_view text) {
  // One fprintf a line: stdio locks the stream for each call, so lines from
  // several matches' threads never interleave.
  if (g_format == LogFormat::kJson) {
    const std::string line = log_json_line(level, text, std::chrono::system_clock::now(), t_match);
    std::fprintf(stderr, "%s\n", line.c_str());
    return;
  }
  std::string prefixed;
  if (!t_match.empty()) {
    prefixed.append(t_match).append(": ").append(text);
    text = prefixed;
  }
  const int size = static_cast<int>(text.size());
  if (level == LogLevel::kError) {
    std::fprintf(stderr, "rewind-server: %.*s\n", size, text.data());
  } else {
    std::fprintf(stderr, "[rewind-server] %s%.*s\n", level == LogLevel::kWarning ? "WARNING: " : "",
                 size, text.data());
  }
}

}  // namespace rwd::server
