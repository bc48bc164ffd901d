// SPDX-License-Identifier: MIT
#pragma once
// The steps of the hull builder (hull_builder.cpp), one per file: the exact
// triangle hull on an integer grid (hull_quickhull.cpp), the merge of its
// triangles into polygon faces (hull_faces.cpp), and the mass properties
// and principal axes (hull_mass.cpp). Internal to the builder. Geometry
// here is double precision: the builder runs once per registration, and
// doubles keep its rounding far below the float results it hands back.
#include <cstdint>
#include <span>
#include <vector>

#include "rewind/sim/math.h"

namespace rwd::sim::d3::hull_steps {

inline constexpr uint32_t kNone = UINT32_MAX;

struct DVec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

inline DVec3 operator+(DVec3 a, DVec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline DVec3 operator-(DVec3 a, DVec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline DVec3 operator*(DVec3 a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline double dot(DVec3 a, DVec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline DVec3 cross(DVec3 a, DVec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline DVec3 to_dvec(Vec3 v) {
  return {v.x, v.y, v.z};
}

/// A point on the builder's integer grid. Coordinates stay within +-2^29,
/// so differences fit 31 bits, the normal of three points fits 62 bits, and
/// the side of a fourth point is decided exactly (orientation_sign).
struct GridPoint {
  int64_t x = 0;
  int64_t y = 0;
  int64_t z = 0;
};

inline constexpr int64_t kGridLimit = int64_t{1} << 29;

inline DVec3 to_dvec(GridPoint p) {
  // Exact: |coordinates| <= 2^29 < 2^53.
  return {static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)};
}

/// The exact normal cross(b - a, c - a) of three grid points.
struct GridNormal {
  int64_t x = 0;
  int64_t y = 0;
  int64_t z = 0;
};
GridNormal grid_normal(GridPoint a, GridPoint b, GridPoint c);
/// Sign (-1, 0, 1) of dot(n, p - a), exactly: 1 when p lies on the side of
/// the plane through a that n points to.
int side_of_plane(const GridNormal& n, GridPoint a, GridPoint p);

/// One triangle of a triangle hull: counter-clockwise seen from outside;
/// adj[i] is the triangle across the edge v[i] -> v[(i + 1) % 3].
struct TriFace {
  uint32_t v[3] = {0, 0, 0};
  uint32_t adj[3] = {0, 0, 0};
};

enum class TriHullShape : uint8_t {
  kSolid,       ///< a hull with volume
  kCoincident,  ///< all points equal
  kCollinear,   ///< all points on one line
  kCoplanar,    ///< all points on one plane (plane[] spans it)
  kFailed,      ///< the horizon did not close: cannot happen with exact predicates
};

struct TriHull {
  TriHullShape shape = TriHullShape::kSolid;
  std::vector<TriFace> faces;
  std::vector<uint32_t> vertices;  ///< point indices on the hull, ascending
  uint32_t plane[3] = {kNone, kNone, kNone};
  /// Growth stopped at max_vertices with points still farther out than
  /// the slack.
  bool capped = false;
};

/// The convex hull of points[subset], as triangles, by Quickhull with
/// exact predicates, so points exactly on a face or edge never become
/// vertices and no edge is ever concave. The point farthest from the hull
/// so far goes in next (ties to the lower index). Points no more than
/// `slack` (grid units) from the hull are never added (slack 0: every
/// point outside is); growth stops once the hull has `max_vertices`
/// vertices.
TriHull build_tri_hull(std::span<const GridPoint> points, std::span<const uint32_t> subset,
                       double slack, uint32_t max_vertices);

/// Distance from p to the closest of `faces` (grid units), skipping faces
/// through point `skip` (kNone: none). For p outside a hull, its distance
/// to the hull.
double distance_to_faces(std::span<const GridPoint> points, std::span<const TriFace> faces,
                         GridPoint p, uint32_t skip);

/// Polygon faces: each loop counter-clockwise seen from outside and
/// starting at its lowest point index.
struct PolygonFaces {
  std::vector<std::vector<uint32_t>> loops;
  /// kNone on success; otherwise a vertex where the faces could not be
  /// made consistent, and why.
  uint32_t bad_vertex = kNone;
  const char* problem = "";
};

/// Merges the triangles of a kSolid hull into polygon faces. Largest
/// triangles first, each grows over its neighbours while all their corners
/// lie within `band` (grid units) of its support plane; band 0 merges
/// exactly coplanar triangles only, which always gives a valid result.
/// Checks the result: every face one convex loop, every vertex on at least
/// three faces, two faces sharing at most one edge, V - E + F = 2.
PolygonFaces merge_coplanar(std::span<const GridPoint> points, const TriHull& hull, double band);

/// Volume, centre of mass and inertia per unit mass of a uniform solid.
struct MassProperties {
  double volume = 0.0;     ///< m^3
  DVec3 center;            ///< metres, frame of the points
  double inertia[3][3]{};  ///< m^2, about the centre, per kg
};

/// Mass properties of the closed polyhedron bounded by `loops` (faces
/// counter-clockwise from outside) over `points`.
MassProperties polyhedron_mass(std::span<const DVec3> points,
                               const std::vector<std::vector<uint32_t>>& loops);

/// Principal moments and axes of a symmetric tensor.
struct PrincipalAxes {
  double moments[3] = {0.0, 0.0, 0.0};
  DVec3 axes[3];  ///< unit, right-handed; moments[i] belongs to axes[i]
};

/// Cyclic Jacobi rotations (arithmetic and sqrt only). Off-diagonal terms
/// below 1e-6 of the trace are left alone, so a tensor that is diagonal to
/// that precision keeps the identity axes, and equal moments (a cube) give
/// no arbitrary turn. The axes are ordered, signed and made right-handed to
/// lie closest to the identity.
PrincipalAxes principal_axes(const double tensor[3][3]);

/// The unit quaternion of the rotation whose columns are axes[0..2]
/// (Shepperd's method: sqrt and arithmetic only), with w >= 0.
Quat quat_from_axes(const DVec3 axes[3]);

}  // namespace rwd::sim::d3::hull_steps
