// SPDX-License-Identifier: MIT
#pragma once
// Distance, penetration and sweep between two convex proxies: GJK for the
// closest points of the cores, EPA for the penetration of overlapping
// cores, and conservative advancement on GJK for a linear sweep.
//
// A proxy (after Box2D v3's b2ShapeProxy) is a small point set, its "core",
// whose convex hull is the shape, plus a radius that rounds it: a sphere is
// one point, a capsule its segment's two ends, a box its eight corners, a
// hull its vertices. GJK and EPA work on the cores only; callers add the
// radii (shape_cast does).
//
// Everything is computed in A's frame (B's points mapped by the relative
// pose), as Box2D v3 does, so that far from the world origin the precision
// is that of the relative pose, not of the world coordinates. Results are
// mapped back to the world at the end.
//
// Every routine is a pure function of its inputs' bits: only + - * / and
// sqrt, fixed iteration orders, ties to the lower index, fixed-size arrays
// (no allocation).
#include <cstdint>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// Largest core a proxy may have (a hull's vertex limit).
inline constexpr uint32_t kProxyMaxPoints = 64;

/// A convex shape for GJK: the hull of `count` core points, rounded by
/// `radius`, placed by a pose (world = position + axes * local).
struct ConvexProxy {
  const Vec3* points = nullptr;  ///< core points in the proxy's local frame
  uint32_t count = 0;            ///< 1 (sphere), 2 (capsule), 8 (box), up to 64 (hull)
  float radius = 0.0f;           ///< metres; spheres and capsules, 0 for boxes and hulls
  Vec3 position;                 ///< metres, world
  Mat3 axes;                     ///< rotation, columns are the local axes in the world
};

/// The core point of `proxy` farthest along the world direction `dir`
/// (evaluated in the local frame, axes^T * dir); ties go to the lower index.
uint32_t proxy_support(const ConvexProxy& proxy, Vec3 dir);

/// One vertex of the Minkowski difference B - A: a core point of each
/// proxy, in A's frame (see above).
struct SimplexVertex {
  Vec3 a;               ///< A's core point, A's frame
  Vec3 b;               ///< B's core point, A's frame
  Vec3 w;               ///< b - a
  float weight = 0.0f;  ///< barycentric weight in the closest point
  uint8_t index_a = 0;
  uint8_t index_b = 0;
};

/// GJK's final simplex (1 to 4 vertices, in A's frame), the start of EPA.
struct GjkSimplex {
  SimplexVertex v[4];
  uint32_t count = 0;
};

/// Optional warm start: the core indices of a previous call's simplex.
/// With a cache the result depends on its contents as well as the proxies
/// (still deterministic); pass none for a pure function of the proxies.
struct GjkCache {
  uint32_t count = 0;  ///< 0: cold start
  uint8_t index_a[4] = {0, 0, 0, 0};
  uint8_t index_b[4] = {0, 0, 0, 0};
};

/// Largest distance between cores that GJK reports as overlap, metres.
inline constexpr float kGjkOverlapDistance = 1e-6f;
/// GJK stops when the distance can shrink by no more than this fraction.
inline constexpr float kGjkRelativeTolerance = 1e-6f;
inline constexpr uint32_t kGjkMaxIterations = 32;

struct GjkOutput {
  Vec3 point_a;  ///< world, closest point of A's core
  Vec3 point_b;  ///< world, closest point of B's core
  /// Unit, from A to B (point_b - point_a over the distance); zero when the
  /// cores overlap (EPA gives a penetration normal).
  Vec3 normal;
  float distance = 0.0f;  ///< metres between the cores; 0 when they overlap
  bool overlap = false;   ///< the cores intersect (distance <= kGjkOverlapDistance)
  uint32_t iterations = 0;
  GjkSimplex simplex;  ///< final simplex, A's frame
};

/// Closest points of the two cores (GJK with Johnson's sub-algorithm in
/// the form of closest-point Voronoi region tests, barycentric weights).
/// `cache`, when given, seeds the simplex and receives the final one.
GjkOutput gjk_distance(const ConvexProxy& a, const ConvexProxy& b, GjkCache* cache = nullptr);

/// EPA limits: the polytope lives in fixed arrays.
inline constexpr uint32_t kEpaMaxVertices = 64;
inline constexpr uint32_t kEpaMaxFaces = 128;
inline constexpr uint32_t kEpaMaxIterations = 64;
/// EPA stops when the support along the nearest face gains less than this.
inline constexpr float kEpaTolerance = 1e-5f;  // metres

struct EpaOutput {
  /// Unit, from A to B: moving B by depth * normal separates the cores.
  Vec3 normal;
  float depth = 0.0f;  ///< metres, >= 0
  Vec3 point_a;        ///< world, on A's core surface (deepest in B)
  Vec3 point_b;        ///< world, on B's core surface; point_a = point_b + depth * normal
  uint32_t iterations = 0;
  /// False when EPA stopped on a limit or a degenerate polytope and
  /// returned its best face so far (or, for flat cores, depth 0).
  bool converged = false;
};

/// Penetration of two overlapping cores from GJK's final simplex (a
/// simplex of fewer than four vertices is blown up to a polytope about the
/// origin first). Computes in A's frame like gjk_distance.
EpaOutput epa_penetration(const ConvexProxy& a, const ConvexProxy& b, const GjkSimplex& simplex);

/// Shape cast: surfaces within this of each other count as touching, and
/// the advancement aims for that gap (metres) so GJK's normal stays
/// defined for shapes without radius.
inline constexpr float kCastTargetGap = 1e-3f;
inline constexpr float kCastTolerance = 2.5e-4f;
inline constexpr uint32_t kShapeCastMaxIterations = 20;

struct ShapeCastOutput {
  bool hit = false;
  /// Whether the surfaces (cores plus radii) overlap at fraction 0; then
  /// hit is true, fraction 0 and the normal the separating direction (EPA
  /// when the cores overlap), whatever the translation.
  bool initially_overlapping = false;
  /// When the surfaces touch: the step toward the target gap is
  /// extrapolated to zero gap along the last normal. Exact for flat
  /// contacts and never later than the true impact (the distance is convex
  /// in the fraction), so a body moved by it does not tunnel.
  float fraction = 0.0f;
  Vec3 point;   ///< world, on A's surface at the hit
  Vec3 normal;  ///< unit, from A to B at the hit
  uint32_t iterations = 0;
};

/// Sweeps B by fraction * translation_b (A fixed), fraction in [0,
/// max_fraction], and reports the first contact of the rounded shapes.
/// Conservative advancement on gjk_distance (warm started), at most
/// kShapeCastMaxIterations steps; on that cap it reports a hit at the last
/// extrapolated fraction (conservative: early, never late).
ShapeCastOutput shape_cast(const ConvexProxy& a, const ConvexProxy& b, Vec3 translation_b,
                           float max_fraction);

/// Building blocks shared by gjk.cpp and epa.cpp; not for callers.
namespace gjk_detail {

/// B's pose in A's frame.
struct RelativePose {
  Mat3 axes;
  Vec3 position;
};
RelativePose relative_pose(const ConvexProxy& a, const ConvexProxy& b);
/// The Minkowski difference's vertex from core indices.
SimplexVertex make_vertex(const ConvexProxy& a, const ConvexProxy& b, const RelativePose& pose,
                          uint32_t index_a, uint32_t index_b);
/// The Minkowski difference's support along `dir` (A's frame): B's point
/// farthest along dir, A's farthest along -dir.
SimplexVertex support_vertex(const ConvexProxy& a, const ConvexProxy& b, const RelativePose& pose,
                             Vec3 dir);
/// The point of triangle (p0, p1, p2) nearest the origin and its
/// barycentric weights (a degenerate triangle falls back to its edges).
Vec3 closest_on_triangle(Vec3 p0, Vec3 p1, Vec3 p2, float weights[3]);
/// A triangle whose two shortest edges make an angle with sin^2 below this
/// has no reliable normal (it would be rounding noise).
inline constexpr float kDegenerateSinSq = 1e-9f;

/// The (unnormalized) normal of triangle (a, b, c), (b - a) x (c - a) up to
/// sign-preserving rounding, taken from its two shortest edges (all three
/// crosses are equal in exact arithmetic; these lose the least), or false
/// when the triangle is degenerate (kDegenerateSinSq).
inline bool triangle_normal(Vec3 a, Vec3 b, Vec3 c, Vec3& n) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 bc = c - b;
  const float ab_sq = length_squared(ab);
  const float ac_sq = length_squared(ac);
  const float bc_sq = length_squared(bc);
  float e1_sq = 0.0f;
  float e2_sq = 0.0f;
  if (bc_sq >= ab_sq && bc_sq >= ac_sq) {
    n = cross(ab, ac);
    e1_sq = ab_sq;
    e2_sq = ac_sq;
  } else if (ac_sq >= ab_sq) {
    n = cross(ab, bc);
    e1_sq = ab_sq;
    e2_sq = bc_sq;
  } else {
    n = cross(ac, bc);
    e1_sq = ac_sq;
    e2_sq = bc_sq;
  }
  return length_squared(n) > kDegenerateSinSq * e1_sq * e2_sq;
}

/// m^T v.
inline Vec3 mul_transpose(const Mat3& m, Vec3 v) {
  return {dot(m.c0, v), dot(m.c1, v), dot(m.c2, v)};
}

}  // namespace gjk_detail

}  // namespace rwd::sim::d3
