// SPDX-License-Identifier: MIT
#pragma once
// What a match host takes from the world outside it besides datagrams and
// the steady time it is handed: the wall clock (only to date a replay) and
// files (desync reports). Passed in, so the host never reaches for either
// itself and tests can stand in for both (a fixed clock, a disk that
// fails). The replay file itself is written by replay::ReplayWriter.
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "rewind/core/status.h"

namespace rwd::server {

struct MatchEnvironment {
  /// Milliseconds since the Unix epoch, now.
  std::function<int64_t()> unix_ms;
  /// Creates a directory and its parents; Ok when it exists already.
  std::function<Status(const std::string& path)> create_directories;
  /// Writes a whole file, replacing one of that name; kIo on any failure.
  std::function<Status(const std::string& path, std::span<const uint8_t> bytes)> write_file;

  /// The operating system's clock and files.
  static MatchEnvironment os();
};

}  // namespace rwd::server
