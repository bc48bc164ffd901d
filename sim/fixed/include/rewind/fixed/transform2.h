// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/fixed/rot2.h"
#include "rewind/fixed/vec2.h"

namespace rwd::fixed {

/// A rigid 2D transform: rotate by q, then translate by p. Maps a body's
/// local coordinates to world coordinates.
struct Transform2 {
  Vec2 p;
  Rot2 q;

  static constexpr Transform2 identity() { return {}; }
  friend constexpr bool operator==(Transform2 a, Transform2 b) = default;
};

/// The local point v in world coordinates: q*v + p.
constexpr Vec2 apply(Transform2 t, Vec2 v) {
  return rotate(t.q, v) + t.p;
}
/// The world point v in local coordinates: q^-1 * (v - p).
constexpr Vec2 apply_inverse(Transform2 t, Vec2 v) {
  return inv_rotate(t.q, v - t.p);
}
/// The transform "b, then a": apply(mul(a, b), v) == apply(a, apply(b, v))
/// up to rounding (one rounding per component of each step).
constexpr Transform2 mul(Transform2 a, Transform2 b) {
  return {rotate(a.q, b.p) + a.p, mul(a.q, b.q)};
}
/// The inverse transform: apply(inverse(t), apply(t, v)) == v up to rounding.
constexpr Transform2 inverse(Transform2 t) {
  const Rot2 qi = inverse(t.q);
  return {rotate(qi, -t.p), qi};
}

}  // namespace rwd::fixed
