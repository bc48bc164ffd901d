// SPDX-License-Identifier: MIT
#pragma once
// A deterministic input generator for the fixed-point tests: splitmix64,
// integer-only, so every platform feeds the library the same values.
#include <cstdint>

namespace rwd::fixed {

struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Any int32 bit pattern, INT32_MIN included.
  int32_t raw_i32() { return static_cast<int32_t>(static_cast<uint32_t>(next())); }
  /// Uniform enough in [0, n) for test inputs.
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }
};

}  // namespace rwd::fixed
