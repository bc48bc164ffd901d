// SPDX-License-Identifier: MIT
#include "rewind/server/tick_schedule.h"

#include <algorithm>

namespace rwd::server {

TickSchedule::TickSchedule(std::chrono::nanoseconds period) : period_(period) {}

void TickSchedule::start(net::TimePoint now) {
  due_ = now + period_;
}

std::chrono::nanoseconds TickSchedule::begin(net::TimePoint now) {
  // A timer never fires early, but a caller's clock read may land a hair
  // before the expiry it waited for: that is on time.
  const auto lateness = std::max(std::chrono::nanoseconds(0),
                                 std::chrono::duration_cast<std::chrono::nanoseconds>(now - due_));
  lateness_.observe(lateness);
  behind_ = lateness / period_;
  if (behind_ > 0) ++late_;
  return lateness;
}

int64_t TickSchedule::end(net::TimePoint now) {
  due_ += period_;
  const auto behind = std::chrono::duration_cast<std::chrono::nanoseconds>(now - due_);
  if (behind <= kMaxBehind * period_) return 0;
  // Every tick due up to now is dropped; the next is due a period on, as
  // at start().
  const int64_t dropped = behind / period_ + 1;
  missed_ += static_cast<uint64_t>(dropped);
  due_ = now + period_;
  return dropped;
}

}  // namespace rwd::server
