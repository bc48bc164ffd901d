// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

namespace detail {

// Parses a decimal literal ("12", "0.125", "1'000.5") into Q16.16 with
// integers only. Anything else (exponents, hex, too many digits, a value
// beyond the range) is thrown, which inside consteval is a compile error.
template <char... Chars>
consteval int32_t parse_fx_literal() {
  constexpr char text[] = {Chars..., '\0'};
  I128 whole = 0;
  I128 frac = 0;
  I128 frac_scale = 1;
  bool seen_point = false;
  int digits = 0;
  for (int i = 0; text[i] != '\0'; ++i) {
    const char c = text[i];
    if (c == '\'') continue;
    if (c == '.') {
      if (seen_point) throw "two decimal points in an _fx literal";
      seen_point = true;
      continue;
    }
    if (c < '0' || c > '9') throw "an _fx literal takes decimal digits and one point only";
    if (++digits > 30) throw "too many digits in an _fx literal";
    if (seen_point) {
      frac = frac * 10 + (c - '0');
      frac_scale *= 10;
    } else {
      whole = whole * 10 + (c - '0');
    }
  }
  if (digits == 0) throw "an _fx literal needs a digit";
  // value * 2^16 = whole * 2^16 + frac * 2^16 / frac_scale, rounded half up
  // (the literal is non-negative, so this is ties away from zero).
  const I128 raw = whole * Fx::kOneRaw + (2 * frac * Fx::kOneRaw + frac_scale) / (2 * frac_scale);
  if (raw > INT32_MAX) throw "an _fx literal beyond 32767.99998";
  return static_cast<int32_t>(raw);
}

}  // namespace detail

/// Compile-time fixed-point constants written in decimal: `0.1_fx` is the
/// Fx nearest to 1/10 (6554 raw), computed exactly from the digits with
/// integer arithmetic, so authoring a constant never involves floating point
/// and gives the same bits on every compiler. A negative constant is the
/// negation: `-2.5_fx`.
inline namespace literals {
template <char... Chars>
consteval Fx operator""_fx() {
  return Fx::from_raw(detail::parse_fx_literal<Chars...>());
}
}  // namespace literals

}  // namespace rwd::fixed
