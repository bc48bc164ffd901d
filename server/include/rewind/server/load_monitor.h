// SPDX-License-Identifier: MIT
#pragma once
// How loaded the process's tick loop is, from what its matches report
// after every tick: the share of the match threads' time spent ticking,
// and how many ticks started late or were dropped (TickSchedule). The
// server refuses new matches while the load is over its budget or ticks
// slip, and the process counts as unhealthy (Agones health pings stop)
// while ticks slip persistently or the loop has stopped ticking at all.
//
// Ticks are summed into one-second buckets of the steady clock; a window
// is the last few whole seconds before `now`, so a figure does not swing
// with the part of a second that has passed. Thread-safe: every match
// strand records into it, the control API and the health pinger read it.
// No clock: the callers pass the time in.
#include <array>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "rewind/net/clock.h"

namespace rwd::server {

class LoadMonitor {
 public:
  /// Whole seconds the load and the slipping are judged over.
  static constexpr int64_t kWindowS = 5;
  /// A second slips when more than this share of its scheduled ticks
  /// started late or were dropped.
  static constexpr double kSlipShare = 0.1;
  /// Unhealthy after this many slipping seconds in a row.
  static constexpr int64_t kUnhealthyAfterS = 10;
  /// Unhealthy when matches are live and none has ticked for this long
  /// (a tick loop that stopped, a thread starved outright).
  static constexpr std::chrono::seconds kStalledAfter{2};

  /// `tick_budget`: the share of the match threads' time spent ticking
  /// beyond which new matches are refused, in (0, 1]. `now` starts the
  /// record (no window reaches before it).
  LoadMonitor(double tick_budget, net::TimePoint now);
  LoadMonitor(const LoadMonitor&) = delete;
  LoadMonitor& operator=(const LoadMonitor&) = delete;

  /// Threads running the matches (the load is a share of their time); 1
  /// until set.
  void set_threads(uint32_t threads);
  double tick_budget() const { return tick_budget_; }

  /// A match began ticking / ended, at `now`.
  void match_started(net::TimePoint now);
  void match_ended();

  /// One tick of one match: it started at `start` and its work (reading
  /// datagrams, the tick, sending) took `work`; `late` when it started a
  /// period or more after it was due; `missed`: ticks its schedule dropped
  /// when it ended.
  void record_tick(net::TimePoint start, std::chrono::nanoseconds work, bool late, uint64_t missed);

  /// The window before `now`.
  struct Load {
    double window_s = 0.0;  ///< seconds covered (less than kWindowS just after start)
    double busy = 0.0;      ///< tick work / (threads * window), may pass 1 when starved
    uint64_t ticks = 0;     ///< ticks run
    uint64_t late = 0;      ///< of those, started a period or more late
    uint64_t missed = 0;    ///< ticks dropped
    uint32_t threads = 1;
    uint32_t live = 0;       ///< matches ticking now
    bool slipping = false;   ///< late + missed over kSlipShare of the scheduled ticks
    bool stalled = false;    ///< live matches, no tick for kStalledAfter
    int64_t slipping_s = 0;  ///< whole seconds in a row that slipped, newest back
  };
  Load load(net::TimePoint now) const;

  /// Why a new match must be refused now ("overloaded: ..."), or empty:
  /// the load is over the budget, ticks slip, or the loop stalled.
  std::string overload_reason(net::TimePoint now) const;
  /// False while ticks have slipped for kUnhealthyAfterS seconds in a row
  /// or the loop stalled: the process cannot keep its matches' tick rate.
  bool healthy(net::TimePoint now) const;
  /// Why healthy() is false, or empty.
  std::string unhealthy_reason(net::TimePoint now) const;

 private:
  struct Second {
    int64_t second = INT64_MIN;  ///< which second of the steady clock it sums
    uint64_t busy_ns = 0;
    uint64_t ticks = 0;
    uint64_t late = 0;
    uint64_t missed = 0;
  };
  static constexpr size_t kSeconds = 32;  // > kUnhealthyAfterS + 1, a ring
  static int64_t second_of(net::TimePoint t);
  const Second* find(int64_t second) const;
  static bool slipped(const Second& s);

  const double tick_budget_;
  const int64_t first_second_;

  mutable std::mutex mutex_;
  uint32_t threads_ = 1;
  uint32_t live_ = 0;
  net::TimePoint last_tick_{};             ///< the newest tick's start, or a match's start
  int64_t live_since_second_ = INT64_MAX;  ///< when the live count last rose from 0
  std::array<Second, kSeconds> seconds_{};
};

}  // namespace rwd::server
