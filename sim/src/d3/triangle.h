// SPDX-License-Identifier: MIT
#pragma once
// One triangle of a static triangle source (a TriangleMesh or a
// HeightField) as the narrowphase sees it, and the small pieces both sources
// share: the face normal, the ray test and the edge classification behind
// "active edges".
//
// Active edges (the idea of Jolt's active edges and Bullet's internal edge
// utility): a body sliding across a flat or concave edge between two
// triangles must not catch on it, so such an edge never gives an edge
// contact; the contact is made a face contact of the triangle instead. An
// edge is active (may give edge contacts) when it bounds the surface or
// folds away from the side the body is on by more than kFlatEdgeSin.
#include <cstdint>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// Bit e of the low three bits: edge e (p[e] -> p[(e + 1) % 3]) is active
/// seen from the front (the side the normal points to): a boundary edge or
/// a convex one. Bit 3 + e: the same seen from the back (a boundary edge or
/// a concave one), for bodies behind a two-sided surface.
inline constexpr uint8_t kFrontEdgesMask = 0x07;
inline constexpr uint8_t kBackEdgesShift = 3;
inline constexpr uint8_t kBoundaryEdgeBits = 0x09;  ///< (1 | 1 << 3): active both ways

/// Two faces whose normals make an angle with a sine below this meet at a
/// flat edge (about 1e-3 rad); the edge is inactive from both sides.
inline constexpr float kFlatEdgeSin = 1e-3f;

struct TriangleRef {
  Vec3 p[3];    ///< corners in the source's local frame, counter-clockwise about normal
  Vec3 normal;  ///< unit face normal, (p1 - p0) x (p2 - p0) normalized
  uint8_t active_edges = 0;  ///< kFrontEdgesMask bits and back bits (see above)
  /// across[e]: the corner of the neighbour across edge e that lies off
  /// the edge, set for an edge active one way only (a convex or concave
  /// fold, see above); zero for flat and boundary edges. With it the
  /// narrowphase knows the neighbour's face at a fold
  /// (manifold_triangle_contact.cpp).
  Vec3 across[3];
  /// Stable id: the mesh's triangle index, or cell * 2 + half for a height
  /// field. Contact feature ids and ties are built from it, so it must be
  /// unique within one call and below 2^27 (see manifold_triangles.h).
  uint32_t id = 0;
};

/// A point's signed distance to a triangle source's surface, in the
/// source's local frame (mesh_signed_distance, height_field_signed_distance).
struct SurfaceDistance {
  float distance = 0.0f;  ///< metres; negative behind the surface
  Vec3 point;             ///< the surface's point nearest the query point
  Vec3 normal;            ///< unit; the way the distance grows (the outward normal)
};

/// (b - a) x (c - a): twice the area times the unit normal.
inline Vec3 triangle_cross(Vec3 a, Vec3 b, Vec3 c) {
  return cross(b - a, c - a);
}

/// Active-edge bits of one edge (from p to q) seen by a triangle with unit
/// normal n1 whose neighbour across the edge has unit normal n2 and the
/// vertex `opposite` (the neighbour's vertex off the edge). Returns the
/// front bit and the back bit as (front | back << 3) for edge 0; callers
/// shift by the edge index. Flat (sine of the fold below kFlatEdgeSin):
/// inactive both ways. Otherwise the neighbour folds down (convex, seen
/// from the front) when its far vertex lies below this triangle's plane.
inline uint8_t classify_shared_edge(Vec3 n1, Vec3 n2, Vec3 p, Vec3 opposite) {
  const Vec3 c = cross(n1, n2);
  const bool folded = dot(n1, n2) < 0.0f || length_squared(c) > kFlatEdgeSin * kFlatEdgeSin;
  if (!folded) return 0;
  const bool convex = dot(n1, opposite - p) < 0.0f;
  return convex ? 0x01 : 0x08;
}

/// Whether edge e of a triangle with these active-edge bits is a fold
/// (convex or concave): active from one side only. A boundary edge is
/// active from both, a flat one from neither.
inline bool edge_is_fold(uint8_t active_edges, uint32_t e) {
  return ((active_edges >> e) & 1u) != ((active_edges >> (kBackEdgesShift + e)) & 1u);
}

/// Barycentric slack of ray_triangle, so a ray through a shared edge or
/// vertex hits at least one of the triangles despite rounding.
inline constexpr float kRayBarycentricSlack = 1e-6f;

/// Ray (Moller-Trumbore) origin + t * dir, 0 <= t <= max_t, against the
/// triangle (a, b, c). `front_only` skips triangles the ray meets from
/// behind (dir along the normal (b - a) x (c - a)) and edge-on ones.
inline bool ray_triangle(Vec3 origin, Vec3 dir, Vec3 a, Vec3 b, Vec3 c, float max_t,
                         bool front_only, float& t) {
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 p = cross(dir, e2);
  const float det = dot(e1, p);  // -dot(dir, normal) * twice the area
  if (front_only ? !(det > 0.0f) : det == 0.0f) return false;
  const float inv = 1.0f / det;
  const Vec3 s = origin - a;
  const float u = dot(s, p) * inv;
  // Written so that a NaN (det too small for 1 / det) fails every test.
  if (!(u >= -kRayBarycentricSlack && u <= 1.0f + kRayBarycentricSlack)) return false;
  const Vec3 q = cross(s, e1);
  const float v = dot(dir, q) * inv;
  if (!(v >= -kRayBarycentricSlack && u + v <= 1.0f + kRayBarycentricSlack)) return false;
  const float hit = dot(e2, q) * inv;
  if (!(hit >= 0.0f && hit <= max_t)) return false;
  t = hit;
  return true;
}

}  // namespace rwd::sim::d3
