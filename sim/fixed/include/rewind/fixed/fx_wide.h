// SPDX-License-Identifier: MIT
#pragma once
#include <compare>
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

/// A Q32.32 fixed-point number in an int64: the exact home of products of
/// two Fx values and of sums that must not be rounded before the end (dot
/// products, squared lengths, slow velocities accumulated over many steps).
/// Range [-2^31, 2^31 - 2^-32]; resolution 2^-32. Operations saturate like
/// Fx; narrowing back to Fx rounds to nearest, ties away from zero.
class FxWide {
 public:
  static constexpr int kFracBits = 32;

  constexpr FxWide() = default;
  /// The exact value of an Fx.
  constexpr explicit FxWide(Fx f) : raw_(static_cast<int64_t>(f.raw()) * (int64_t{1} << 16)) {}

  static constexpr FxWide from_raw(int64_t raw) {
    FxWide w;
    w.raw_ = raw;
    return w;
  }
  /// a * b, exact: the product of two Q16.16 raws is a Q32.32 raw.
  static constexpr FxWide product(Fx a, Fx b) {
    return from_raw(static_cast<int64_t>(a.raw()) * b.raw());
  }

  constexpr int64_t raw() const { return raw_; }
  /// Rounded to the nearest Fx (ties away from zero), saturated.
  constexpr Fx to_fx() const { return Fx::from_raw(saturate_i32(shift_round(raw_, 16))); }

  friend constexpr bool operator==(FxWide a, FxWide b) = default;
  friend constexpr auto operator<=>(FxWide a, FxWide b) = default;

  friend constexpr FxWide operator+(FxWide a, FxWide b) {
    return from_raw(saturate_i64(static_cast<I128>(a.raw_) + b.raw_));
  }
  friend constexpr FxWide operator-(FxWide a, FxWide b) {
    return from_raw(saturate_i64(static_cast<I128>(a.raw_) - b.raw_));
  }
  friend constexpr FxWide operator-(FxWide a) {
    return from_raw(saturate_i64(-static_cast<I128>(a.raw_)));
  }
  /// Rounded to nearest, ties away from zero; saturated.
  friend constexpr FxWide operator*(FxWide a, FxWide b) {
    return from_raw(saturate_i64(shift_round(static_cast<I128>(a.raw_) * b.raw_, kFracBits)));
  }
  constexpr FxWide& operator+=(FxWide b) { return *this = *this + b; }
  constexpr FxWide& operator-=(FxWide b) { return *this = *this - b; }

 private:
  int64_t raw_ = 0;
};

}  // namespace rwd::fixed
