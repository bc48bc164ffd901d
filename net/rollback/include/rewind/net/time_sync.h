// SPDX-License-Identifier: MIT
#pragma once
// Keeps a client's inputs arriving just ahead of the server's need. The
// server reports, with every batch of final ticks, how many ticks early the
// client's newest input arrived ("lead"). The client runs its tick clock a
// little faster when the lead is below target and a little slower above it,
// so it converges without ever jumping (which would waste or skip inputs).
#include <cstdint>

namespace rwd::net {

struct TimeSyncConfig {
  double target_lead_ticks = 2.0;      ///< desired arrival margin; covers jitter
  double max_adjust = 0.08;            ///< tick period scale stays in [1 - max, 1 + max]
  double gain = 0.02;                  ///< scale change per tick of lead error
  double smoothing = 0.1;              ///< weight of a new lead sample in the average
  int32_t late_threshold_ticks = 0;    ///< a report below this lead triggers a jump
  int32_t jump_cooldown_reports = 12;  ///< reports ignored after a jump (~ a round trip)
};

class TimeSync {
 public:
  explicit TimeSync(const TimeSyncConfig& config = {}) : config_(config) {}

  /// A lead report from the server (negative: the input arrived late).
  void on_lead_report(int32_t lead_ticks);
  /// Reports keep describing the clock from before a jump for a round trip:
  /// the cooldown after a jump covers at least that many reports.
  void set_round_trip_ticks(double rtt_ticks) { rtt_ticks_ = rtt_ticks; }
  /// Whole ticks the clock should jump forward now (0 = none); resets.
  int32_t take_jump();
  /// Forgets pending jumps and the cooldown (the clock was re-anchored).
  void clear_jump() {
    jump_ = 0;
    cooldown_ = 0;
  }
  /// Multiplier for the local tick period: > 1 slows the client down.
  double period_scale() const;
  double smoothed_lead() const { return lead_; }
  bool has_samples() const { return samples_ > 0; }

 private:
  TimeSyncConfig config_;
  double lead_ = 0.0;
  uint64_t samples_ = 0;
  int32_t jump_ = 0;
  int32_t cooldown_ = 0;
  double rtt_ticks_ = 0.0;
};

}  // namespace rwd::net
