// SPDX-License-Identifier: MIT
#pragma once
// Logging helpers shared by the match host's source files.
#include <cstdint>
#include <cstdio>
#include <string>

#include "rewind/server/server_log.h"

namespace rwd::server::detail {

inline void log_line(const std::string& text) {
  write_log(LogLevel::kInfo, text);
}
inline void log_warning(const std::string& text) {
  write_log(LogLevel::kWarning, text);
}

// Text that came from a client goes into our logs only printable and short,
// so nobody can forge log lines or flood them with one long string.
inline std::string printable(const std::string& text) {
  std::string out;
  for (char c : text.substr(0, 64)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out;
}

// A failure that repeats (every resend of every waiting client) is logged
// the first few times and then at each power of two, so it stays loud
// without burying the log.
inline bool worth_logging(uint64_t count) {
  return count <= 3 || (count & (count - 1)) == 0;
}

inline std::string hex64(uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof(text), "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace rwd::server::detail
