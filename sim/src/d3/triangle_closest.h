// SPDX-License-Identifier: MIT
#pragma once
// The closest points of a point or a segment (the core of a sphere or a
// capsule) and a triangle, in closed form: what GJK finds by iterating, for
// the two cores a body on a mesh or a height field most often has. Used by
// the triangle contact (manifold_triangle_contact.cpp) in place of GJK.
#include <cstdint>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

struct CoreTriangleClosest {
  bool overlap = false;  ///< the core touches or crosses the triangle (GJK's overlap)
  float distance = 0.0f;
  Vec3 normal;   ///< unit, from the triangle to the core (not set on overlap)
  Vec3 on_tri;   ///< the triangle's closest point
  Vec3 on_core;  ///< the core's
};

/// Closest points of the core `points[0..count)` (count 1 or 2) and the
/// triangle p[0..3) with unit normal `n` (zero for a degenerate triangle).
CoreTriangleClosest closest_core_triangle(const Vec3* points, uint32_t count, const Vec3 p[3],
                                          Vec3 n);

}  // namespace rwd::sim::d3
