// SPDX-License-Identifier: MIT
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

// The classic digit-by-digit method: one result bit per iteration, using only
// shifts, compares and subtractions, so the answer is exact and the same on
// every target. Newton's method would need a division and a first guess.
uint64_t isqrt64(uint64_t n) {
  uint64_t root = 0;
  uint64_t bit = uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

U128 isqrt128(U128 n) {
  U128 root = 0;
  U128 bit = U128{1} << 126;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

U128 isqrt128_round(U128 n) {
  const U128 s = isqrt128(n);
  // round up iff n > s^2 + s, i.e. n - s^2 > s (no overflow: n >= s^2).
  return (n - s * s > s) ? s + 1 : s;
}

}  // namespace rwd::fixed
