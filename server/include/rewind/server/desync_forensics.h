// SPDX-License-Identifier: MIT
#pragma once
// What the server makes of a client's desync report: a headline (tick and
// both checksums) that never fails, the bodies and fields where the
// client's state after the tick differs from the server's, and the raw dump
// kept as evidence, stored as DIR/desync_pP_tT_rR.{txt,bin}.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "rewind/net/rollback_session.h"
#include "rewind/server/match_environment.h"

namespace rwd::server {

struct DesyncReportInfo {
  uint32_t player = 0;
  uint32_t report_id = 0;
  Tick tick = kNoTick;  ///< the final tick whose checksums differ
  uint64_t client_checksum = 0;
  /// The server's checksum of the tick as the client received it, and as
  /// the server still holds it (nullopt: no longer held).
  uint64_t server_checksum_received = 0;
  std::optional<uint64_t> server_checksum;
};

struct DesyncFindings {
  std::string headline;  ///< "player P desync at tick T: client 0x.. server 0x.."
  std::string text;      ///< the whole report
  /// Why no fields are named, when none are: empty when the diff was made.
  std::string problem;
  bool dump_unreadable = false;  ///< the client's state did not parse
  bool write_failed = false;     ///< the report could not be stored
  std::string stored_as;         ///< the .txt path written; empty when none
};

class DesyncForensics {
 public:
  /// `dir` empty: reports are examined, not stored.
  DesyncForensics(std::string dir, MatchEnvironment env)
      : dir_(std::move(dir)), env_(std::move(env)) {}

  /// Examines `dump` (the client's serialized simulation after the tick)
  /// against the state `session` holds after that tick (restored briefly, so
  /// not const), and stores the
  /// report. Never throws on bad input: an unreadable dump is reported as
  /// such, with the headline and the raw bytes still stored.
  DesyncFindings examine(const DesyncReportInfo& report, std::span<const uint8_t> dump,
                         net::RollbackSession& session) const;

 private:
  std::string dir_;
  MatchEnvironment env_;
};

}  // namespace rwd::server
