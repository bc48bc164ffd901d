// SPDX-License-Identifier: MIT
#include "rewind/net/time_sync.h"

#include <algorithm>

namespace rwd::net {

void TimeSync::on_lead_report(int32_t lead_ticks) {
  // The first sample seeds the average so start-up does not drift from zero.
  lead_ = samples_ == 0 ? lead_ticks : lead_ + config_.smoothing * (lead_ticks - lead_);
  ++samples_;
}

double TimeSync::period_scale() const {
  if (samples_ == 0) return 1.0;
  const double error = lead_ - config_.target_lead_ticks;  // > 0: too far ahead
  return 1.0 + std::clamp(error * config_.gain, -config_.max_adjust, config_.max_adjust);
}

}  // namespace rwd::net
