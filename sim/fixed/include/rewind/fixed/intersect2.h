// SPDX-License-Identifier: MIT
#pragma once
#include <span>

#include "rewind/core/status.h"
#include "rewind/fixed/aabb2.h"
#include "rewind/fixed/circle.h"
#include "rewind/fixed/vec2.h"

namespace rwd::fixed {

/// A line segment from a to b (closed: it contains both ends).
struct Segment2 {
  Vec2 a;
  Vec2 b;
  friend constexpr bool operator==(Segment2 l, Segment2 r) = default;
};

// Boolean overlap tests. Every one is exact: coordinates are compared through
// 128-bit products of exact differences, never rounded, so the answer is the
// true geometric one for any Fx inputs, including the range edges. Shapes
// are closed: touching counts as overlapping.

/// True when the discs share a point: |ca - cb| <= ra + rb.
bool overlaps(Circle a, Circle b);
/// True when the disc and the box share a point.
bool overlaps(Circle c, Aabb2 box);
inline bool overlaps(Aabb2 box, Circle c) {
  return overlaps(c, box);
}
/// True when p lies in the disc or on its circle.
bool contains(Circle c, Vec2 p);
/// True when the segments share a point, including touching ends and
/// collinear overlap. A zero-length segment is a point.
bool intersects(Segment2 s, Segment2 t);

/// True when p lies inside the polygon or on its boundary. The polygon is
/// the closed chain of `vertices` (the last joins the first), simple
/// (non-self-intersecting), convex or not, in either winding; the test uses
/// the even-odd crossing rule with exact orientation tests.
/// `vertices` is read only during the call. kInvalidArgument for fewer than
/// 3 vertices.
Result<bool> polygon_contains(std::span<const Vec2> vertices, Vec2 p);

}  // namespace rwd::fixed
