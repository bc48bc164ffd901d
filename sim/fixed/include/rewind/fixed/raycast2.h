// SPDX-License-Identifier: MIT
#pragma once
#include <optional>

#include "rewind/fixed/aabb2.h"
#include "rewind/fixed/circle.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/intersect2.h"
#include "rewind/fixed/vec2.h"

namespace rwd::fixed {

/// A ray as a finite sweep: the segment from `origin` to `origin + delta`.
/// `delta` is the full displacement, not a unit direction.
struct Ray2 {
  Vec2 origin;
  Vec2 delta;
};

/// Where a ray first meets a shape.
struct RayHit2 {
  /// The hit's position along the ray, in [0, 1] (0 = origin, 1 = the end),
  /// rounded to the nearest ulp from the exact rational value (the circle
  /// test takes a square root and may be 1 ulp further off).
  Fx fraction;
  /// origin + fraction * delta, rounded per component.
  Vec2 point;
  /// The unit surface normal at the hit, facing the ray's origin, each
  /// component within 1 ulp of the exact unit vector (2 ulps for circles,
  /// whose normal is taken from the rounded hit point).
  Vec2 normal;
};

// Shared rules for every ray test: a zero delta never hits; a ray whose
// origin is strictly inside the shape does not hit it (it reports surfaces
// it enters, not ones it leaves); an origin on the boundary moving inward
// hits at fraction 0; a ray that only grazes (touches tangentially) hits.

/// The first hit of the ray on the box (slab test with exact rational
/// compares). When the ray enters through a corner the x face wins.
std::optional<RayHit2> raycast(Ray2 ray, Aabb2 box);
/// The first hit of the ray on the disc. Exact in 128 bits while origin and
/// center are within 32768 units of each other on each axis; beyond that the
/// test halves its resolution (drops one low bit) to stay in range.
std::optional<RayHit2> raycast(Ray2 ray, Circle circle);
/// The hit of the ray on the segment. A ray parallel to the segment,
/// including one running along it, does not hit. The normal faces the ray.
std::optional<RayHit2> raycast(Ray2 ray, Segment2 segment);

}  // namespace rwd::fixed
