// SPDX-License-Identifier: MIT
#pragma once
// Live secure matches on loopback, all in this process: a real Server
// hosting N matches of P players on T threads (the process's own match
// loop: sockets, timers, gateway, host), and N x P scripted secure peers
// (tests/support/scripted_peer.h) on a thread of their own, which speak
// the real protocol but simulate nothing, so a hundred matches need a
// fraction of a core besides the server's. The peers share one UDP socket:
// each sends from an address of its own in 127.0.0.0/8 (IP_PKTINFO), so
// the server sees N x P clients while the peers cost one system call per
// batch. Linux only (the peers' socket); elsewhere start() says so.
//
// What it measures is the server threads' CPU time over a window (the
// process's CPU clock less the peers' thread's and the measuring
// thread's), against the ticks its matches ran, started late or dropped in
// that window.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "rewind/core/status.h"

namespace rwd::bench {

struct LiveLoadConfig {
  uint32_t matches = 1;
  uint32_t players = 8;
  uint32_t tick_rate_hz = 60;
  /// The server's threads (ServerConfig::threads), the matches spread
  /// across them; 1 to 64.
  uint32_t threads = 1;
  std::string game = "crates";
};

/// One measured window.
struct LiveLoadReport {
  double seconds = 0.0;
  uint32_t matches = 0;
  uint64_t ticks = 0;           ///< ticks the matches ran in the window
  uint64_t ticks_due = 0;       ///< matches x tick rate x seconds
  uint64_t late = 0;            ///< ticks that started a period or more late
  uint64_t missed = 0;          ///< ticks dropped
  double lateness_p99_s = 0.0;  ///< upper bound of the bucket holding the 99th percentile
  double server_cpu_s = 0.0;    ///< the server threads' CPU time, summed
  double peers_cpu_s = 0.0;     ///< the peers thread's
  uint64_t bytes_out = 0;       ///< sent by the server's matches in the window

  /// Server CPU per tick of one match, microseconds.
  double server_us_per_match_tick() const {
    return ticks == 0 ? 0.0 : server_cpu_s / static_cast<double>(ticks) * 1e6;
  }
  /// Cores' worth the server threads used (up to their count).
  double server_core_share() const { return seconds > 0 ? server_cpu_s / seconds : 0.0; }
  /// Every tick due ran, none more than 1% late or dropped.
  bool sustained() const {
    return ticks + ticks_due / 100 >= ticks_due &&
           static_cast<double>(late + missed) <= 0.01 * static_cast<double>(ticks_due);
  }
};

class LiveLoad {
 public:
  /// Binds the server's matches and the peers' socket, starts both threads
  /// and the peers' handshakes.
  static Result<std::unique_ptr<LiveLoad>> start(const LiveLoadConfig& config);
  /// Waits until every match is running (all its players joined and the
  /// countdown over); false after `timeout`.
  bool wait_running(std::chrono::seconds timeout);
  /// Measures the next `seconds`.
  LiveLoadReport measure(double seconds);
  /// Ends the matches and joins the threads.
  ~LiveLoad();

  struct Impl;
  explicit LiveLoad(std::unique_ptr<Impl> impl);

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace rwd::bench
