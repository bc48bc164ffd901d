// SPDX-License-Identifier: MIT
#include "rewind/net/time_sync.h"

#include <algorithm>
#include <cmath>

namespace rwd::net {

void TimeSync::on_lead_report(int32_t lead_ticks) {
  if (cooldown_ > 0) {
    --cooldown_;  // still describes the clock before the last jump
    return;
  }
  if (lead_ticks < config_.late_threshold_ticks) {
    jump_ += static_cast<int32_t>(std::ceil(config_.target_lead_ticks)) - lead_ticks;
    cooldown_ =
        std::max(config_.jump_cooldown_reports, static_cast<int32_t>(std::ceil(rtt_ticks_)) + 4);
    lead_ = config_.target_lead_ticks;  // the jump lands on target
    ++samples_;
    return;
  }
  // The first sample seeds the average so start-up does not drift from zero.
  lead_ = samples_ == 0 ? lead_ticks : lead_ + config_.smoothing * (lead_ticks - lead_);
  ++samples_;
}

int32_t TimeSync::take_jump() {
  const int32_t jump = jump_;
  jump_ = 0;
  return jump;
}

double TimeSync::period_scale() const {
  if (samples_ == 0) return 1.0;
  const double error = lead_ - config_.target_lead_ticks;  // > 0: too far ahead
  return 1.0 + std::clamp(error * config_.gain, -config_.max_adjust, config_.max_adjust);
}

}  // namespace rwd::net
