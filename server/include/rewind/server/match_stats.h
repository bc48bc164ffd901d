// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "rewind/core/tick.h"

namespace rwd::server {

/// Counters of one match; printed as the --summary-json line.
struct MatchStats {
  int64_t ticks_final = 0;
  uint64_t rollbacks = 0;
  uint64_t resimulated_ticks = 0;
  uint64_t late_inputs = 0;         ///< arrived after their tick was simulated (in time for final)
  uint64_t substituted_inputs = 0;  ///< missing at the deadline; prediction recorded instead
  uint64_t rejected_inputs =
      0;  ///< for final ticks (once each), too far ahead, conflicting, or another slot
  uint64_t rejected_packets = 0;  ///< undecodable, unknown connection, spoofed address, ...
  uint64_t duplicate_packets = 0;
  uint64_t relayed_inputs = 0;
  uint64_t desync_reports = 0;
  uint64_t resyncs_sent = 0;
  /// Resync snapshots that did not load into a fresh simulation on the
  /// server itself, or did not reproduce their checksum: never sent.
  uint64_t resync_snapshot_failures = 0;
  /// Resync snapshots a client reported it could not load.
  uint64_t resyncs_refused = 0;
  /// Desync reports whose client state dump could not be parsed (the
  /// report keeps its tick and both checksums, and the raw dump).
  uint64_t desync_dumps_unreadable = 0;
  /// Desync reports that could not be written to the desync directory.
  uint64_t desync_report_write_failures = 0;
  /// Replay keyframes that did not load into a fresh simulation with their
  /// tick's checksum: left out of the replay (its ticks are still recorded).
  uint64_t keyframe_load_failures = 0;
  uint64_t packets_in = 0;
  uint64_t packets_out = 0;
  uint64_t bytes_in = 0;
  uint64_t bytes_out = 0;
  uint64_t final_checksum = 0;  ///< checksum of the last final tick
  Tick last_final_tick = kNoTick;
  uint32_t players_joined = 0;
  /// Secure connections (zero in tokenless mode): requests answered with
  /// a challenge, sessions opened, handshake packets refused (bad, expired
  /// or foreign tokens, responses from the wrong address or without the
  /// keys) and datagrams dropped before the match saw them (payloads that
  /// did not authenticate or replayed ones, anything not a secure packet).
  bool secure = false;
  uint64_t secure_challenges = 0;
  uint64_t secure_sessions = 0;
  uint64_t secure_refused = 0;
  uint64_t secure_dropped = 0;
  /// Tokenless mode's front door (zero when secure): hellos answered with
  /// an address cookie, and datagrams refused before the match saw them
  /// (malformed hellos, joins without a good cookie).
  uint64_t address_cookies = 0;
  uint64_t cookies_refused = 0;
  /// Bytes on each transport, as sent and received (sealed packets
  /// included, IP/UDP and WebSocket framing not): the UDP socket's, and the
  /// browsers' over WebSocket, with how many WebSocket connections the
  /// match has had.
  uint64_t udp_bytes_in = 0;
  uint64_t udp_bytes_out = 0;
  uint64_t websocket_connections = 0;
  uint64_t websocket_bytes_in = 0;
  uint64_t websocket_bytes_out = 0;
  /// The tick loop's punctuality (TickSchedule; zero where no loop ran, as
  /// in a headless match): ticks that started a period or more after they
  /// were due (run back to back to catch up), ticks dropped from the
  /// schedule after a stall (never run), and the latest start.
  uint64_t ticks_late = 0;
  uint64_t ticks_missed = 0;
  double tick_lateness_max_s = 0.0;
  double duration_s = 0.0;
  std::string end_reason;

  /// One JSON object on one line.
  std::string to_json() const;
  /// The end-of-match summary, one readable line.
  std::string to_text() const;
  /// What went wrong that an operator must look at (snapshots that did not
  /// load, unreadable desync dumps, reports not written, ticks that slipped),
  /// one line; empty when nothing did.
  std::string problems() const;
};

}  // namespace rwd::server
