// SPDX-License-Identifier: MIT
#pragma once
// When a match's ticks are due, and how far the loop falls behind. Tick n
// is due at start + n periods, on an absolute grid, so the schedule never
// drifts. A tick's lateness is the time it actually started (the loop's
// clock read as its handler begins) minus the time it was due; a timer
// that wakes on time leaves only the wake-up latency. A loop that runs late
// catches up by running the due ticks back to back, each counted late when
// it started a whole period or more after its time (the next one was
// already due). A loop more than kMaxBehind ticks behind (a stopped
// process, a starved thread) drops the ticks it missed, counted, and the
// grid restarts from now instead of bursting through them. No clock: the
// runner passes the time in, so the rules are testable with any times.
#include <chrono>
#include <cstdint>

#include "rewind/net/clock.h"
#include "rewind/server/tick_histogram.h"

namespace rwd::server {

class TickSchedule {
 public:
  /// Behind by more than this many periods, the missed ticks are dropped.
  static constexpr int64_t kMaxBehind = 10;

  /// `period` > 0.
  explicit TickSchedule(std::chrono::nanoseconds period);

  /// Starts the grid: the first tick is due one period after `now`.
  void start(net::TimePoint now);
  /// When the next tick is due.
  net::TimePoint due() const { return due_; }

  /// The next tick starts at `now` (at or after due()): records its
  /// lateness and returns it.
  std::chrono::nanoseconds begin(net::TimePoint now);
  /// The tick begun last ended at `now`: the next one is due a period after
  /// it was, or, when that leaves the loop more than kMaxBehind periods
  /// behind, a period after `now` with the ticks in between dropped.
  /// Returns how many were dropped.
  int64_t end(net::TimePoint now);

  std::chrono::nanoseconds period() const { return period_; }
  /// Lateness of every tick begun.
  const TickHistogram& lateness() const { return lateness_; }
  /// Ticks that started a period or more after they were due.
  uint64_t late() const { return late_; }
  /// Ticks dropped from the schedule, never run.
  uint64_t missed() const { return missed_; }
  /// Whole periods the last tick started after it was due: 0 on time,
  /// 1 or more while the loop catches up.
  int64_t behind() const { return behind_; }

 private:
  std::chrono::nanoseconds period_;
  net::TimePoint due_{};
  TickHistogram lateness_{TickHistogram::kLatenessBoundsNs};
  uint64_t late_ = 0;
  uint64_t missed_ = 0;
  int64_t behind_ = 0;
};

}  // namespace rwd::server
