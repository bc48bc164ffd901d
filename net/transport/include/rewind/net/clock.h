// SPDX-License-Identifier: MIT
#pragma once
#include <chrono>

namespace rwd::net {

/// The clock every transport API takes its time from. Callers pass the time
/// in, so tests can drive the protocol with synthetic times.
using SteadyClock = std::chrono::steady_clock;
using TimePoint = SteadyClock::time_point;

}  // namespace rwd::net
