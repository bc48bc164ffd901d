// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd {

/// A simulation tick number. Tick 0 is the first tick a match steps; ticks
/// only ever grow by one. Signed so that "before the first tick" is -1.
using Tick = int32_t;

inline constexpr Tick kNoTick = -1;

}  // namespace rwd
