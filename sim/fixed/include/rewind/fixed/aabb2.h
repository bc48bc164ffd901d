// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/core/status.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"

namespace rwd::fixed {

/// An axis-aligned box, closed: it contains its edges. Invariant:
/// lower.x <= upper.x and lower.y <= upper.y (make() refuses anything else;
/// a box may be flat or a single point).
struct Aabb2 {
  Vec2 lower;
  Vec2 upper;

  /// The box [lower, upper], or kInvalidArgument when lower exceeds upper on
  /// an axis.
  static Result<Aabb2> make(Vec2 lower, Vec2 upper);
  /// The box center +- half_extents; kInvalidArgument for a negative half
  /// extent. Corners saturate at the Fx range.
  static Result<Aabb2> from_center(Vec2 center, Vec2 half_extents);

  friend constexpr bool operator==(Aabb2 a, Aabb2 b) = default;
};

/// The smallest box containing both.
constexpr Aabb2 union_of(Aabb2 a, Aabb2 b) {
  return {{min(a.lower.x, b.lower.x), min(a.lower.y, b.lower.y)},
          {max(a.upper.x, b.upper.x), max(a.upper.y, b.upper.y)}};
}
/// True when the boxes share at least one point (touching edges count).
constexpr bool overlaps(Aabb2 a, Aabb2 b) {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y;
}
/// True when p is inside or on the edge of the box.
constexpr bool contains(Aabb2 box, Vec2 p) {
  return box.lower.x <= p.x && p.x <= box.upper.x && box.lower.y <= p.y && p.y <= box.upper.y;
}
/// True when inner lies entirely inside outer (edges may touch).
constexpr bool contains(Aabb2 outer, Aabb2 inner) {
  return contains(outer, inner.lower) && contains(outer, inner.upper);
}
/// The box moved by delta; each corner saturates at the Fx range, so a box
/// pushed past the edge becomes flat there (the invariant still holds).
constexpr Aabb2 translated(Aabb2 box, Vec2 delta) {
  return {box.lower + delta, box.upper + delta};
}
/// The midpoint, each coordinate rounded toward negative infinity (exact
/// when the sum of the two raws is even); never saturates.
constexpr Vec2 center(Aabb2 box) {
  return {Fx::from_raw(static_cast<int32_t>(
              (static_cast<int64_t>(box.lower.x.raw()) + box.upper.x.raw()) >> 1)),
          Fx::from_raw(static_cast<int32_t>(
              (static_cast<int64_t>(box.lower.y.raw()) + box.upper.y.raw()) >> 1))};
}

}  // namespace rwd::fixed
