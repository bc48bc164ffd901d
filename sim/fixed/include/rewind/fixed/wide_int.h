// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd::fixed {

/// 128-bit integers for exact intermediates (products of 64-bit values).
/// GCC and clang provide them on every target Rewind builds for (x86-64,
/// aarch64, wasm32); `__extension__` keeps -Wpedantic quiet about the type.
__extension__ typedef __int128 I128;
__extension__ typedef unsigned __int128 U128;

/// |v| as an unsigned value; exact for every input, including INT64_MIN.
constexpr uint64_t magnitude(int64_t v) {
  return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
}

/// |v| as an unsigned value; exact for every input, including the minimum.
constexpr U128 magnitude(I128 v) {
  return v < 0 ? U128{0} - static_cast<U128>(v) : static_cast<U128>(v);
}

/// num / den rounded to nearest, ties away from zero (the rounding every
/// operation of this library uses). den must not be 0. |num| and |den| must
/// stay below 2^126 so the doubled values fit.
constexpr I128 div_round(I128 num, I128 den) {
  const bool negative = (num < 0) != (den < 0);
  const U128 n = magnitude(num);
  const U128 d = magnitude(den);
  const U128 q = (2 * n + d) / (2 * d);
  return negative ? -static_cast<I128>(q) : static_cast<I128>(q);
}

/// v / 2^shift rounded to nearest, ties away from zero. shift in [1, 126].
constexpr I128 shift_round(I128 v, int shift) {
  const U128 m = magnitude(v);
  const U128 q = (m + (U128{1} << (shift - 1))) >> shift;
  return v < 0 ? -static_cast<I128>(q) : static_cast<I128>(q);
}

/// v clamped to the int32 range.
constexpr int32_t saturate_i32(I128 v) {
  if (v > INT32_MAX) return INT32_MAX;
  if (v < INT32_MIN) return INT32_MIN;
  return static_cast<int32_t>(v);
}

/// v clamped to the int64 range.
constexpr int64_t saturate_i64(I128 v) {
  if (v > INT64_MAX) return INT64_MAX;
  if (v < INT64_MIN) return INT64_MIN;
  return static_cast<int64_t>(v);
}

/// floor(sqrt(n)), exact for every 64-bit n (bit-by-bit, no division).
uint64_t isqrt64(uint64_t n);

/// floor(sqrt(n)), exact for every 128-bit n (bit-by-bit, no division).
U128 isqrt128(U128 n);

/// sqrt(n) rounded to the nearest integer, exact for every 128-bit n. A tie
/// cannot occur: (s + 1/2)^2 is never an integer.
U128 isqrt128_round(U128 n);

}  // namespace rwd::fixed
