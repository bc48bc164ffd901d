// SPDX-License-Identifier: MIT
#pragma once
// Convex hull manifolds. Same conventions as manifold.h: the normal points
// from A (the hull) to B, separation is negative when the shapes overlap,
// each point lies midway between the two surfaces, and points farther
// apart than `speculative_m` are dropped. The hull is placed by its mass
// frame: a vertex x (Hull::vertices) is at hull_position + hull_axes * x in
// the world.
#include "d3/hull.h"
#include "d3/manifold.h"

namespace rwd::sim::d3 {

// ---------------------------------------------------------------------------
// Hull against rounded shapes (manifold_hull_round.cpp; feature ids are
// listed at the top of that file).

/// Hull A against sphere B (normal from the hull to the sphere). One point:
/// the hull's closest point to the centre by GJK when the centre is
/// outside, the face of least penetration when it is inside.
void collide_hull_sphere(const Hull& hull, Vec3 hull_position, const Mat3& hull_axes, Vec3 center,
                         float radius, float speculative_m, Manifold& out);

/// Hull A against capsule B (normal from the hull to the capsule): GJK
/// between the segment and the hull, or a separating axis test (faces and
/// segment x edges) when the segment touches or reaches into the hull. Two
/// points where the segment lies along a face, one otherwise.
void collide_hull_capsule(const Hull& hull, Vec3 hull_position, const Mat3& hull_axes,
                          const CapsulePose& capsule, float speculative_m, Manifold& out);

// End of hull against rounded shapes.
// ---------------------------------------------------------------------------

}  // namespace rwd::sim::d3
