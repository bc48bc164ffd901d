// SPDX-License-Identifier: MIT
// The hull builder: checks the points, finds the hull's corners, merges its
// faces and moves everything into the mass frame (hull_build_steps.h has
// the steps). Corners are decided in two stages. The triangle hull is
// exact on an integer grid, so a point exactly on a face or edge is never
// a vertex; then a vertex counts as a corner only if it stands out of the
// hull of the other vertices by more than the corner tolerance, which is
// what lets nearly coplanar triangles merge into clean convex faces.
#include "d3/hull_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "d3/hull_build_steps.h"

namespace rwd::sim::d3 {
namespace {

using hull_steps::build_tri_hull;
using hull_steps::DVec3;
using hull_steps::GridPoint;
using hull_steps::kNone;
using hull_steps::PolygonFaces;
using hull_steps::TriHull;
using hull_steps::TriHullShape;

constexpr float kMaxCoordinate = 1000.0f;    // m
constexpr double kDuplicateDistance = 1e-4;  // m
constexpr double kMinVolume = 1e-9;          // m^3
// The corner tolerance: relative to the hull's size, to the float
// precision of its coordinates, and never below a few steps of the
// canonical grid (2^-20 m) the points were snapped to.
constexpr double kCornerPerSize = 1e-5;
constexpr double kCornerPerMagnitude = 5e-7;
constexpr double kCornerFloor = 4e-6;  // m

Status invalid(std::string what) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(what));
}

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g m", v);
  return text;
}

std::string point_name(uint32_t i) {
  return "point " + std::to_string(i);
}

Status check_points(std::span<const Vec3> points, uint32_t max_points, const char* who) {
  if (points.size() < kHullMinVertices || points.size() > max_points) {
    return invalid(std::string(who) + " takes 4 to " + std::to_string(max_points) +
                   " points, got " + std::to_string(points.size()));
  }
  for (uint32_t i = 0; i < points.size(); ++i) {
    const Vec3 p = points[i];
    if (!is_finite(p)) return invalid(point_name(i) + " has a non-finite coordinate");
    if (std::fabs(p.x) > kMaxCoordinate || std::fabs(p.y) > kMaxCoordinate ||
        std::fabs(p.z) > kMaxCoordinate) {
      return invalid(point_name(i) + " has a coordinate beyond 1000 m");
    }
  }
  return Status::Ok();
}

bool too_close(Vec3 a, Vec3 b) {
  const DVec3 d = hull_steps::to_dvec(a) - hull_steps::to_dvec(b);
  return hull_steps::dot(d, d) < kDuplicateDistance * kDuplicateDistance;
}

// The points on the integer grid: centred on their bounds and scaled by a
// power of two (exact) so the largest half side just fits 2^29 units.
struct Grid {
  std::vector<GridPoint> points;
  double per_metre = 1.0;
  double corner_tolerance = 0.0;  // grid units
};

Grid make_grid(std::span<const Vec3> points) {
  DVec3 lo = hull_steps::to_dvec(points[0]);
  DVec3 hi = lo;
  double magnitude = 0.0;
  for (const Vec3& p : points) {
    lo = {std::min(lo.x, double{p.x}), std::min(lo.y, double{p.y}), std::min(lo.z, double{p.z})};
    hi = {std::max(hi.x, double{p.x}), std::max(hi.y, double{p.y}), std::max(hi.z, double{p.z})};
    magnitude = std::max(
        {magnitude, double{std::fabs(p.x)}, double{std::fabs(p.y)}, double{std::fabs(p.z)}});
  }
  const DVec3 center = (lo + hi) * 0.5;
  const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  int exponent = 0;
  std::frexp(size * 0.5, &exponent);  // half side < 2^exponent
  Grid g;
  g.per_metre = std::ldexp(1.0, 29 - exponent);
  for (const Vec3& p : points) {
    const DVec3 d = (hull_steps::to_dvec(p) - center) * g.per_metre;
    g.points.push_back({std::llround(d.x), std::llround(d.y), std::llround(d.z)});
  }
  const double tolerance =
      std::max({kCornerPerSize * size, kCornerPerMagnitude * magnitude, kCornerFloor});
  g.corner_tolerance = tolerance * g.per_metre;
  return g;
}

Status check_shape(const TriHull& tri) {
  switch (tri.shape) {
    case TriHullShape::kSolid:
      return Status::Ok();
    case TriHullShape::kCoincident:
      return invalid("all points coincide");
    case TriHullShape::kCollinear:
      return invalid("all points lie on one line (the hull has no volume)");
    case TriHullShape::kCoplanar:
      return invalid("all points lie on one plane (the hull has no volume)");
    case TriHullShape::kFailed:
      break;
  }
  return invalid("the hull of these points could not be built (nearly degenerate points)");
}

Status check_volume(std::span<const Vec3> points, const TriHull& tri) {
  const DVec3 ref = hull_steps::to_dvec(points[tri.vertices[0]]);
  double six_volume = 0.0;
  for (const hull_steps::TriFace& f : tri.faces) {
    const DVec3 a = hull_steps::to_dvec(points[f.v[0]]) - ref;
    const DVec3 b = hull_steps::to_dvec(points[f.v[1]]) - ref;
    const DVec3 c = hull_steps::to_dvec(points[f.v[2]]) - ref;
    six_volume += hull_steps::dot(a, hull_steps::cross(b, c));
  }
  const double volume = six_volume / 6.0;
  if (!(volume >= kMinVolume)) {
    char text[96];
    std::snprintf(text, sizeof text, "the hull's volume %.3g m^3 is below 1e-09 m^3", volume);
    return invalid(text);
  }
  return Status::Ok();
}

// The hull's width across each of its faces must exceed the corner
// tolerance, or no plane could tell its faces apart.
Status check_thickness(const Grid& g, const TriHull& tri) {
  double thinnest = -1.0;
  for (const hull_steps::TriFace& f : tri.faces) {
    const GridPoint a = g.points[f.v[0]];
    const hull_steps::GridNormal n = hull_steps::grid_normal(a, g.points[f.v[1]], g.points[f.v[2]]);
    DVec3 u{static_cast<double>(n.x), static_cast<double>(n.y), static_cast<double>(n.z)};
    u = u * (1.0 / std::sqrt(hull_steps::dot(u, u)));
    double width = 0.0;
    for (uint32_t v : tri.vertices) {
      width = std::max(
          width, -hull_steps::dot(u, hull_steps::to_dvec(g.points[v]) - hull_steps::to_dvec(a)));
    }
    if (thinnest < 0.0 || width < thinnest) thinnest = width;
  }
  if (thinnest <= g.corner_tolerance) {
    return invalid("the points lie within " + metres(thinnest / g.per_metre) +
                   " of a plane, within the " + metres(g.corner_tolerance / g.per_metre) +
                   " tolerance (the hull has no volume)");
  }
  return Status::Ok();
}

// How far (grid units) point v, a vertex of the hull of `subset`, stands
// out of the hull of the rest: its distance to it.
double corner_margin(const Grid& g, std::span<const uint32_t> subset, uint32_t v) {
  std::vector<uint32_t> others;
  for (uint32_t p : subset) {
    if (p != v) others.push_back(p);
  }
  const TriHull rest = build_tri_hull(g.points, others, 0.0, kNone);
  if (rest.shape == TriHullShape::kSolid) {
    return hull_steps::distance_to_faces(g.points, rest.faces, g.points[v], kNone);
  }
  if (rest.shape == TriHullShape::kCoplanar) {
    // The rest is a polygon, the base of a pyramid with v at the top: the
    // faces of the whole hull that do not touch v.
    const TriHull all = build_tri_hull(g.points, subset, 0.0, kNone);
    return hull_steps::distance_to_faces(g.points, all.faces, g.points[v], v);
  }
  return 0.0;  // the rest on a line: then `subset` had no volume
}

// Drops, one at a time, the vertex that stands out least while it is
// within the tolerance (ties to the lower index), until every vertex left
// is a corner.
Status prune_to_corners(const Grid& g, std::vector<uint32_t>& vertices) {
  while (true) {
    if (vertices.size() < kHullMinVertices) {
      return invalid("the points lie within the " + metres(g.corner_tolerance / g.per_metre) +
                     " tolerance of a plane (the hull has no volume)");
    }
    uint32_t worst = kNone;
    double worst_margin = 0.0;
    for (uint32_t v : vertices) {
      const double m = corner_margin(g, vertices, v);
      if (m <= g.corner_tolerance && (worst == kNone || m < worst_margin)) {
        worst = v;
        worst_margin = m;
      }
    }
    if (worst == kNone) return Status::Ok();
    vertices.erase(std::find(vertices.begin(), vertices.end(), worst));
  }
}

// The hull in its mass frame. `kept`: ascending indices of the points that
// are its vertices; `loops`: its faces over point indices.
Hull assemble(std::span<const Vec3> points, std::span<const uint32_t> kept,
              const std::vector<std::vector<uint32_t>>& loops) {
  const uint32_t n = static_cast<uint32_t>(kept.size());
  std::vector<uint32_t> local(points.size(), kNone);
  std::vector<DVec3> authored(n);
  for (uint32_t i = 0; i < n; ++i) {
    local[kept[i]] = i;
    authored[i] = hull_steps::to_dvec(points[kept[i]]);
  }
  std::vector<std::vector<uint32_t>> faces = loops;
  for (std::vector<uint32_t>& loop : faces) {
    for (uint32_t& v : loop) v = local[v];
  }

  const hull_steps::MassProperties mass = hull_steps::polyhedron_mass(authored, faces);
  const hull_steps::PrincipalAxes principal = hull_steps::principal_axes(mass.inertia);
  Hull h;
  h.frame.center = {static_cast<float>(mass.center.x), static_cast<float>(mass.center.y),
                    static_cast<float>(mass.center.z)};
  h.frame.rotation = hull_steps::quat_from_axes(principal.axes);
  h.volume = static_cast<float>(mass.volume);
  h.unit_inertia = {static_cast<float>(principal.moments[0]),
                    static_cast<float>(principal.moments[1]),
                    static_cast<float>(principal.moments[2])};

  const Quat to_mass = conjugate(h.frame.rotation);
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3 v = rotate(to_mass, points[kept[i]] - h.frame.center);
    h.vertices.push_back(v);
    h.extent = std::max(h.extent, length(v));
    h.half_size = max(h.half_size, abs(v));
  }

  // Planes from the mass-frame vertices: the (Newell) normal of each loop,
  // and the offset that puts every vertex on or behind the plane.
  std::vector<uint8_t> face_across(kHullMaxVertices * kHullMaxVertices, 0);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const std::vector<uint32_t>& loop = faces[f];
    HullFace face;
    face.first = static_cast<uint16_t>(h.face_vertices.size());
    face.count = static_cast<uint8_t>(loop.size());
    const DVec3 base = hull_steps::to_dvec(h.vertices[loop[0]]);
    DVec3 normal;
    for (size_t k = 0; k < loop.size(); ++k) {
      const DVec3 a = hull_steps::to_dvec(h.vertices[loop[k]]) - base;
      const DVec3 b = hull_steps::to_dvec(h.vertices[loop[(k + 1) % loop.size()]]) - base;
      normal = normal + hull_steps::cross(a, b);
      h.face_vertices.push_back(static_cast<uint8_t>(loop[k]));
      face_across[loop[k] * kHullMaxVertices + loop[(k + 1) % loop.size()]] =
          static_cast<uint8_t>(f);
    }
    normal = normal * (1.0 / std::sqrt(hull_steps::dot(normal, normal)));
    face.normal = {static_cast<float>(normal.x), static_cast<float>(normal.y),
                   static_cast<float>(normal.z)};
    face.offset = dot(face.normal, h.vertices[0]);
    for (const Vec3& v : h.vertices) face.offset = std::max(face.offset, dot(face.normal, v));
    h.faces.push_back(face);
  }
  // Each edge once, from the face whose loop runs it low index to high.
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const std::vector<uint32_t>& loop = faces[f];
    for (size_t k = 0; k < loop.size(); ++k) {
      const uint32_t a = loop[k];
      const uint32_t b = loop[(k + 1) % loop.size()];
      if (a > b) continue;
      h.edges.push_back({static_cast<uint8_t>(a), static_cast<uint8_t>(b), static_cast<uint8_t>(f),
                         face_across[b * kHullMaxVertices + a]});
    }
  }
  return h;
}

// Faces merged within half the corner tolerance. Where nearly coplanar
// faces meet at a shallow angle (a cone a thousand times wider than high,
// say) that can leave a corner on only two faces; such a hull keeps
// exactly coplanar triangles merged only, which is always consistent.
Result<Hull> finish(std::span<const Vec3> points, const Grid& g, const TriHull& tri,
                    std::span<const uint32_t> kept) {
  PolygonFaces faces = hull_steps::merge_coplanar(g.points, tri, 0.5 * g.corner_tolerance);
  if (faces.bad_vertex != kNone) faces = hull_steps::merge_coplanar(g.points, tri, 0.0);
  if (faces.bad_vertex != kNone) {
    return invalid(point_name(faces.bad_vertex) +
                   " cannot be resolved into a clean hull: " + faces.problem);
  }
  return assemble(points, kept, faces.loops);
}

std::string not_a_corner(uint32_t i, double margin, const Grid& g) {
  return point_name(i) + " is not a corner of the hull: it stands " + metres(margin / g.per_metre) +
         " out of the hull of the other points, within the " +
         metres(g.corner_tolerance / g.per_metre) +
         " tolerance (on or next to a face or edge of it)";
}

}  // namespace

Result<Hull> make_hull(std::span<const Vec3> points) {
  if (Status s = check_points(points, kHullMaxVertices, "make_hull"); !s.ok()) return s;
  const uint32_t n = static_cast<uint32_t>(points.size());
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = i + 1; j < n; ++j) {
      if (too_close(points[i], points[j])) {
        return invalid(point_name(j) + " duplicates point " + std::to_string(i) +
                       " (closer than 1e-4 m)");
      }
    }
  }
  const Grid g = make_grid(points);
  std::vector<uint32_t> all(n);
  for (uint32_t i = 0; i < n; ++i) all[i] = i;
  const TriHull tri = build_tri_hull(g.points, all, 0.0, kNone);
  if (Status s = check_shape(tri); !s.ok()) return s;
  if (Status s = check_volume(points, tri); !s.ok()) return s;
  if (Status s = check_thickness(g, tri); !s.ok()) return s;
  for (uint32_t i = 0; i < n; ++i) {
    if (!std::binary_search(tri.vertices.begin(), tri.vertices.end(), i)) {
      return invalid(point_name(i) +
                     " is not a corner of the hull: it is inside it or on one of its faces or "
                     "edges");
    }
  }
  for (uint32_t i = 0; i < n; ++i) {
    const double margin = corner_margin(g, all, i);
    if (margin <= g.corner_tolerance) return invalid(not_a_corner(i, margin, g));
  }
  return finish(points, g, tri, all);
}

Result<Hull> hull_from_points(std::span<const Vec3> points) {
  if (Status s = check_points(points, kHullMaxCloudPoints, "hull_from_points"); !s.ok()) {
    return s;
  }
  // Points closer than the duplicate distance to an earlier kept point are
  // the same point.
  std::vector<uint32_t> kept;
  for (uint32_t i = 0; i < points.size(); ++i) {
    bool duplicate = false;
    for (uint32_t k : kept) {
      if (too_close(points[i], points[k])) {
        duplicate = true;
        break;
      }
    }
    if (!duplicate) kept.push_back(i);
  }
  if (kept.size() < kHullMinVertices) {
    return invalid("fewer than 4 distinct points (closer than 1e-4 m count as one)");
  }
  const Grid g = make_grid(points);
  // Farthest point first up to 64 vertices, ignoring points within the
  // corner tolerance of the hull so far.
  TriHull tri = build_tri_hull(g.points, kept, g.corner_tolerance, kHullMaxVertices);
  if (Status s = check_shape(tri); !s.ok()) return s;
  if (Status s = check_volume(points, tri); !s.ok()) return s;
  if (Status s = check_thickness(g, tri); !s.ok()) return s;
  std::vector<uint32_t> corners = tri.vertices;
  if (Status s = prune_to_corners(g, corners); !s.ok()) return s;
  tri = build_tri_hull(g.points, corners, 0.0, kNone);
  if (Status s = check_shape(tri); !s.ok()) return s;
  if (Status s = check_volume(points, tri); !s.ok()) return s;
  if (Status s = check_thickness(g, tri); !s.ok()) return s;
  return finish(points, g, tri, corners);
}

}  // namespace rwd::sim::d3
