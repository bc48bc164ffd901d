// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/fixed/fx.h"
#include "rewind/fixed/trig.h"
#include "rewind/fixed/vec2.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

/// A 2D rotation stored as its cosine/sine pair (each in [-1, 1]). A Rot2
/// built from an angle is unit length to within 2 ulps; rotating by it
/// rounds each output component once from the exact 128-bit sum.
struct Rot2 {
  Fx c = Fx::one();
  Fx s;

  static constexpr Rot2 identity() { return {}; }
  /// The rotation by `radians` counter-clockwise (any Fx angle).
  static Rot2 from_angle(Fx radians) {
    const SinCos sc = sin_cos(radians);
    return {sc.cos, sc.sin};
  }
  /// The angle in [-pi(), pi()].
  Fx angle() const { return atan2(s, c); }

  friend constexpr bool operator==(Rot2 a, Rot2 b) = default;
};

namespace detail {
// (a*b - c*d) rounded once to Fx, saturated.
constexpr Fx mul_sub(Fx a, Fx b, Fx c, Fx d) {
  return Fx::from_raw(saturate_i32(shift_round(
      static_cast<I128>(a.raw()) * b.raw() - static_cast<I128>(c.raw()) * d.raw(), 16)));
}
// (a*b + c*d) rounded once to Fx, saturated.
constexpr Fx mul_add(Fx a, Fx b, Fx c, Fx d) {
  return Fx::from_raw(saturate_i32(shift_round(
      static_cast<I128>(a.raw()) * b.raw() + static_cast<I128>(c.raw()) * d.raw(), 16)));
}
}  // namespace detail

/// q applied to v: (c*x - s*y, s*x + c*y).
constexpr Vec2 rotate(Rot2 q, Vec2 v) {
  return {detail::mul_sub(q.c, v.x, q.s, v.y), detail::mul_add(q.s, v.x, q.c, v.y)};
}
/// The inverse of q applied to v: (c*x + s*y, -s*x + c*y).
constexpr Vec2 inv_rotate(Rot2 q, Vec2 v) {
  return {detail::mul_add(q.c, v.x, q.s, v.y), detail::mul_sub(q.c, v.y, q.s, v.x)};
}
/// The rotation "b, then a".
constexpr Rot2 mul(Rot2 a, Rot2 b) {
  return {detail::mul_sub(a.c, b.c, a.s, b.s), detail::mul_add(a.s, b.c, a.c, b.s)};
}
/// The opposite rotation (exact).
constexpr Rot2 inverse(Rot2 q) {
  return {q.c, -q.s};
}

}  // namespace rwd::fixed
