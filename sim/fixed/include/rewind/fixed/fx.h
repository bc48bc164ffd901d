// SPDX-License-Identifier: MIT
#pragma once
#include <compare>
#include <cstdint>

#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

/// A Q16.16 fixed-point number: a signed 32-bit integer counting units of
/// 2^-16 (one "ulp", about 1.5e-5). Range [-32768, 32768 - 2^-16].
///
/// Overflow: every operation saturates: a result beyond the range becomes
/// Fx::max() or Fx::min(); nothing wraps and nothing is undefined.
/// Rounding: multiply, divide and every narrowing in this library round to
/// nearest with ties away from zero, so -(a * b) == (-a) * b bit for bit.
/// Division by zero gives max() for a positive dividend, min() for a
/// negative one and zero for 0 / 0 (use checked_div() to refuse it instead).
///
/// There is no conversion from or to floating point at all: constants are
/// written as decimal literals parsed with integers at compile time (see
/// fx_literal.h: `1.25_fx`), or built from integers and ratios.
class Fx {
 public:
  static constexpr int kFracBits = 16;
  static constexpr int32_t kOneRaw = int32_t{1} << kFracBits;

  /// Zero.
  constexpr Fx() = default;
  /// The whole number `whole`, saturated to [-32768, 32767].
  constexpr explicit Fx(int32_t whole) : raw_(saturate_i32(static_cast<I128>(whole) * kOneRaw)) {}

  /// The value with the given raw bits (raw / 65536). Every int32 is valid.
  static constexpr Fx from_raw(int32_t raw) {
    Fx f;
    f.raw_ = raw;
    return f;
  }
  /// num / den rounded to nearest (ties away from zero), saturated.
  /// den == 0 follows the division-by-zero rule above.
  static constexpr Fx ratio(int64_t num, int64_t den) {
    if (den == 0) return from_raw(num > 0 ? INT32_MAX : (num < 0 ? INT32_MIN : 0));
    return from_raw(saturate_i32(div_round(static_cast<I128>(num) * kOneRaw, den)));
  }

  static constexpr Fx zero() { return Fx(); }
  static constexpr Fx one() { return from_raw(kOneRaw); }
  static constexpr Fx half() { return from_raw(kOneRaw / 2); }
  /// The smallest positive value, 2^-16.
  static constexpr Fx epsilon() { return from_raw(1); }
  static constexpr Fx max() { return from_raw(INT32_MAX); }
  static constexpr Fx min() { return from_raw(INT32_MIN); }
  /// pi, pi/2 and 2*pi, each rounded to the nearest ulp.
  static constexpr Fx pi() { return from_raw(205887); }
  static constexpr Fx half_pi() { return from_raw(102944); }
  static constexpr Fx two_pi() { return from_raw(411775); }

  /// The raw bits: value * 65536.
  constexpr int32_t raw() const { return raw_; }
  /// The largest whole number <= value.
  constexpr int32_t floor_int() const { return raw_ >> kFracBits; }
  /// The value rounded to the nearest whole number, ties away from zero.
  constexpr int32_t round_int() const { return static_cast<int32_t>(shift_round(raw_, kFracBits)); }

  friend constexpr bool operator==(Fx a, Fx b) = default;
  friend constexpr auto operator<=>(Fx a, Fx b) = default;

  friend constexpr Fx operator+(Fx a, Fx b) {
    return from_raw(saturate_i32(static_cast<I128>(a.raw_) + b.raw_));
  }
  friend constexpr Fx operator-(Fx a, Fx b) {
    return from_raw(saturate_i32(static_cast<I128>(a.raw_) - b.raw_));
  }
  /// Saturating: -min() is max().
  friend constexpr Fx operator-(Fx a) { return from_raw(saturate_i32(-static_cast<I128>(a.raw_))); }
  friend constexpr Fx operator*(Fx a, Fx b) {
    return from_raw(saturate_i32(shift_round(static_cast<I128>(a.raw_) * b.raw_, kFracBits)));
  }
  friend constexpr Fx operator/(Fx a, Fx b) {
    if (b.raw_ == 0) return ratio(a.raw_, 0);
    return from_raw(saturate_i32(div_round(static_cast<I128>(a.raw_) * kOneRaw, b.raw_)));
  }
  /// Scaling by a whole number is exact (up to saturation).
  friend constexpr Fx operator*(Fx a, int32_t k) {
    return from_raw(saturate_i32(static_cast<I128>(a.raw_) * k));
  }
  friend constexpr Fx operator*(int32_t k, Fx a) { return a * k; }
  /// Division by a whole number, rounded; k == 0 follows the rule above.
  friend constexpr Fx operator/(Fx a, int32_t k) {
    if (k == 0) return ratio(a.raw_, 0);
    return from_raw(saturate_i32(div_round(a.raw_, k)));
  }

  constexpr Fx& operator+=(Fx b) { return *this = *this + b; }
  constexpr Fx& operator-=(Fx b) { return *this = *this - b; }
  constexpr Fx& operator*=(Fx b) { return *this = *this * b; }
  constexpr Fx& operator/=(Fx b) { return *this = *this / b; }

 private:
  int32_t raw_ = 0;
};

/// |a|, saturating: abs(Fx::min()) is Fx::max().
constexpr Fx abs(Fx a) {
  return a.raw() < 0 ? -a : a;
}
constexpr Fx min(Fx a, Fx b) {
  return b < a ? b : a;
}
constexpr Fx max(Fx a, Fx b) {
  return a < b ? b : a;
}
/// v limited to [lo, hi]; requires lo <= hi (otherwise the result is lo).
constexpr Fx clamp(Fx v, Fx lo, Fx hi) {
  return v < lo ? lo : (hi < v ? (lo < hi ? hi : lo) : v);
}
/// -1, 0 or +1 as a whole number.
constexpr int32_t sign(Fx a) {
  return a.raw() > 0 ? 1 : (a.raw() < 0 ? -1 : 0);
}

}  // namespace rwd::fixed
