// SPDX-License-Identifier: MIT
#include "rewind/fixed/wide_int.h"

#include <bit>

namespace rwd::fixed {

// The classic digit-by-digit method: one result bit per iteration, using only
// shifts, compares and subtractions, so the answer is exact and the same on
// every target. Newton's method would need a division and a first guess.
// The first trial bit is the largest power of four not above n (from the
// count of leading zeros, not a scan down from the top), and each step
// chooses by a mask rather than a branch: which way a step goes is as good
// as random, and a mispredicted branch per result bit cost more than the
// arithmetic.
namespace {

template <class U>
U isqrt_digits(U n, int top_bit) {
  U root = 0;
  U bit = U{1} << (top_bit & ~1);
  while (bit != 0) {
    const U trial = root + bit;
    const U take = U{0} - static_cast<U>(n >= trial);  // all ones or zero
    n -= trial & take;
    root = (root >> 1) + (bit & take);
    bit >>= 2;
  }
  return root;
}

}  // namespace

uint64_t isqrt64(uint64_t n) {
  if (n == 0) return 0;
  return isqrt_digits<uint64_t>(n, 63 - std::countl_zero(n));
}

// Past 64 bits: the root of the top 62 or 63 bits, scaled back up, is
// within a part in 2^30 of the root and above it; one Newton step (one
// division) brings that within one unit, and the last unit is settled by
// squaring. The floor of the square root is one number, so this gives the
// digit method's answer exactly, in a third of its time.
U128 isqrt128(U128 n) {
  const auto high = static_cast<uint64_t>(n >> 64);
  if (high == 0) return isqrt64(static_cast<uint64_t>(n));
  const int bits = 128 - std::countl_zero(high);       // 65..128
  const int shift = (bits - 62) & ~1;                  // even, so the root scales by 2^(shift/2)
  const auto top = static_cast<uint64_t>(n >> shift);  // in [2^61, 2^63)
  const U128 above = static_cast<U128>(isqrt64(top) + 1) << (shift / 2);
  U128 root = (above + n / above) >> 1;
  constexpr U128 kMaxRoot = (U128{1} << 64) - 1;  // the root of 2^128 - 1
  if (root > kMaxRoot) root = kMaxRoot;
  while (root * root > n) --root;
  while (root < kMaxRoot && (root + 1) * (root + 1) <= n) ++root;
  return root;
}

U128 isqrt128_round(U128 n) {
  const U128 s = isqrt128(n);
  // round up iff n > s^2 + s, i.e. n - s^2 > s (no overflow: n >= s^2).
  return (n - s * s > s) ? s + 1 : s;
}

}  // namespace rwd::fixed
