// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// An axis-aligned box in world coordinates, Q32.32.
struct Box2W {
  V2 lower;
  V2 upper;
};

constexpr bool overlaps(const Box2W& a, const Box2W& b) {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y;
}

/// The tight bounds of `shape` placed at `xf` (the body origin's transform).
Box2W shape_bounds(const Shape2D& shape, const Xf& xf);

}  // namespace rwd::sim2d::detail
