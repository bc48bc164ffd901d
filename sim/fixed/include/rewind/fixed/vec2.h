// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_wide.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

/// A 2D vector of Q16.16 components (units are the caller's, e.g. metres or
/// pixels). Component-wise operations saturate like Fx. Products (dot,
/// cross, squared length) are summed exactly in 128 bits and rounded once.
struct Vec2 {
  Fx x;
  Fx y;

  constexpr Vec2() = default;
  constexpr Vec2(Fx x_in, Fx y_in) : x(x_in), y(y_in) {}
  static constexpr Vec2 zero() { return {}; }

  friend constexpr bool operator==(Vec2 a, Vec2 b) = default;
  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, Fx s) { return {a.x * s, a.y * s}; }
  friend constexpr Vec2 operator*(Fx s, Vec2 a) { return {a.x * s, a.y * s}; }
  constexpr Vec2& operator+=(Vec2 b) { return *this = *this + b; }
  constexpr Vec2& operator-=(Vec2 b) { return *this = *this - b; }
};

/// a.x*b.x + a.y*b.y, exact in Q32.32 (saturated only when beyond 2^31).
constexpr FxWide dot_wide(Vec2 a, Vec2 b) {
  const I128 sum =
      static_cast<I128>(a.x.raw()) * b.x.raw() + static_cast<I128>(a.y.raw()) * b.y.raw();
  return FxWide::from_raw(saturate_i64(sum));
}
/// a.x*b.y - a.y*b.x, exact in Q32.32 (saturated only when beyond 2^31).
constexpr FxWide cross_wide(Vec2 a, Vec2 b) {
  const I128 sum =
      static_cast<I128>(a.x.raw()) * b.y.raw() - static_cast<I128>(a.y.raw()) * b.x.raw();
  return FxWide::from_raw(saturate_i64(sum));
}
/// The dot product rounded once to Fx (ties away from zero), saturated.
constexpr Fx dot(Vec2 a, Vec2 b) {
  const I128 sum =
      static_cast<I128>(a.x.raw()) * b.x.raw() + static_cast<I128>(a.y.raw()) * b.y.raw();
  return Fx::from_raw(saturate_i32(shift_round(sum, 16)));
}
/// The 2D cross product (z of the 3D cross) rounded once to Fx, saturated.
constexpr Fx cross(Vec2 a, Vec2 b) {
  const I128 sum =
      static_cast<I128>(a.x.raw()) * b.y.raw() - static_cast<I128>(a.y.raw()) * b.x.raw();
  return Fx::from_raw(saturate_i32(shift_round(sum, 16)));
}
/// |v|^2 rounded to Fx; saturates at Fx::max() when |v| > 181. Prefer
/// length_squared_wide() for comparisons: it is exact up to |v| = 46340.
constexpr Fx length_squared(Vec2 v) {
  return dot(v, v);
}
constexpr FxWide length_squared_wide(Vec2 v) {
  return dot_wide(v, v);
}
/// The vector rotated a quarter turn counter-clockwise: (-y, x).
constexpr Vec2 perp(Vec2 v) {
  return {-v.y, v.x};
}

/// |v| rounded to the nearest ulp from the exact root; saturates at
/// Fx::max() (only when |v| >= 32768, e.g. a diagonal near the range edge).
Fx length(Vec2 v);
/// |a - b| computed without saturating the difference, then saturated.
Fx distance(Vec2 a, Vec2 b);
/// v / |v|, each component within 1 ulp of the exact unit vector (the
/// length is taken with 16 extra bits). Zero-length rule: the zero vector
/// maps to the zero vector, never to a made-up direction.
Vec2 normalized(Vec2 v);

}  // namespace rwd::fixed
