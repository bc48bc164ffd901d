// SPDX-License-Identifier: MIT
#pragma once
// SplitMix64 (Steele, Lea and Flood, 2014): a Weyl sequence passed through
// a 64-bit mix. Integer operations only, so every compiler and platform
// produce the same numbers; the one copy that seeds generators, mixes ids
// and scripts inputs and test scenes wherever Rewind needs reproducible
// bits. Not for secrets (connect tokens and keys come from libsodium).
#include <cstdint>

namespace rwd {

/// The Weyl increment: 2^64 divided by the golden ratio, odd.
inline constexpr uint64_t kSplitMix64Gamma = 0x9E37'79B9'7F4A'7C15ull;

/// SplitMix64's output mix: a bijection on 64 bits with full avalanche.
constexpr uint64_t splitmix64_mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58'476D'1CE4'E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D0'49BB'1331'11EBull;
  return z ^ (z >> 31);
}

struct SplitMix64 {
  uint64_t state = 0;

  /// The next 64 bits: the state advances by the increment, then is mixed.
  constexpr uint64_t next() {
    state += kSplitMix64Gamma;
    return splitmix64_mix(state);
  }
  /// In [0, n) by modulo (a bias below n / 2^64: fine for scripts and
  /// tests, not for statistics); 0 for n = 0.
  constexpr uint64_t below(uint64_t n) { return n == 0 ? 0 : next() % n; }
  /// In [0, 1), from the top 24 bits: every value a float holds exactly.
  constexpr float unit() {
    return static_cast<float>(next() >> 40) / static_cast<float>(1ull << 24);
  }
};

/// The first output of a generator seeded with `seed`: one call's worth of
/// well-mixed bits from any 64-bit value (seeds derived from ids, ticks).
constexpr uint64_t splitmix64_once(uint64_t seed) {
  return splitmix64_mix(seed + kSplitMix64Gamma);
}

}  // namespace rwd
