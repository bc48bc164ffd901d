// SPDX-License-Identifier: MIT
#pragma once
// A deterministic input generator for the fixed-point tests: splitmix64,
// integer-only, so every platform feeds the library the same values.
#include <cstdint>
#include "rewind/core/splitmix64.h"

namespace rwd::fixed {

struct SplitMix64 : rwd::SplitMix64 {
  /// Any int32 bit pattern, INT32_MIN included.
  int32_t raw_i32() { return static_cast<int32_t>(static_cast<uint32_t>(next())); }
  /// Uniform enough in [0, n) for test inputs.
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }
};

}  // namespace rwd::fixed
