// SPDX-License-Identifier: MIT
#pragma once
// The closest points of a point or a segment (the core of a sphere or a
// capsule) and a triangle, in closed form: what GJK finds by iterating, for
// the two cores a body on a mesh or a height field most often has. Used by
// the triangle contact (manifold_triangle_contact.cpp) in place of GJK.
//
// And the point of a triangle nearest a point, with the feature (face, edge
// or vertex) it lies on, for the signed distance to a mesh or a height
// field (mesh_distance.cpp, height_field_distance.cpp).
#include <cstdint>

#include "d3/triangle.h"
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

/// Which part of a triangle holds its point nearest a query point.
enum class TriangleFeature : uint8_t {
  kFace,    ///< the interior
  kEdge,    ///< edge `index`, from p[index] to p[(index + 1) % 3]
  kVertex,  ///< corner p[index]
};

struct PointTriangleClosest {
  Vec3 point;  ///< the triangle's point nearest the query point
  float distance_sq = 0.0f;
  TriangleFeature feature = TriangleFeature::kFace;
  uint32_t index = 0;  ///< the edge or the vertex
};

/// The point of the triangle p[0..3) (not degenerate) nearest q, and the
/// feature whose Voronoi region holds q (Ericson, Real-Time Collision
/// Detection, 5.1.5). A pure function of the inputs' bits.
PointTriangleClosest closest_point_triangle(Vec3 q, const Vec3 p[3]);

/// The SurfaceDistance of q whose nearest surface point is `at`, on a
/// triangle of unit normal `face_normal`; `behind` is the side the caller's
/// rule gives q. The normal points the way the distance grows: the face
/// normal (turned to match the side) when `at` is inside the face, else
/// along q - at.point (reversed behind), or `on_surface` when q lies on the
/// surface and that direction is undefined.
SurfaceDistance signed_surface_distance(Vec3 q, const PointTriangleClosest& at, Vec3 face_normal,
                                        bool behind, Vec3 on_surface);

}  // namespace rwd::sim::d3
