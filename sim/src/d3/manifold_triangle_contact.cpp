// SPDX-License-Identifier: MIT
// One triangle against a convex shape's core: the raw contact (a box's
// separating axes, GJK, EPA or a segment SAT) and the internal-edge fix;
// the face clipping is manifold_triangle_face.cpp's. Conventions are
// manifold_triangles.h's. Everything here works in the source's frame, on
// fixed arrays.
#include <cmath>

#include "d3/manifold_triangles.h"
#include "d3/triangle_closest.h"

namespace rwd::sim::d3 {
namespace {

// A triangle feature lies along the normal when its edges make an angle
// with the contact plane whose sine is below this (GJK's and EPA's normals
// are good to far better).
constexpr float kFeatureSin = 1e-3f;

constexpr uint32_t kEdgeCode = 24;
constexpr uint32_t kVertexCode = 27;
constexpr uint32_t kFaceCode = 30;

// A core reaching this far behind the plane of a triangle it does not
// meet is taken to have gone past the triangle's edge (see
// collide_convex_triangle), metres. Shallower overlaps, within
// WorldConfig's default slop (5 mm), keep the contacts they had: taking
// them too made the boxes resting on the bumpy field of the field_boxes
// stability scene drift 3.2 cm, past its 2 cm limit.
constexpr float kPastEdgeDepth = 0.005f;

// A contact of one point at the witness points.
bool single_point(const TriangleRef& tri, Vec3 normal, Vec3 p_tri, Vec3 p_shape, float sep,
                  uint32_t code, float speculative_m, TriangleContact& out) {
  if (!(sep <= speculative_m)) return false;
  out.normal = normal;
  out.id = tri.id;
  out.separation = sep;
  out.count = 1;
  out.points[0] = {(p_tri + p_shape) * 0.5f, sep, (tri.id << kTriangleFeatureShift) | code};
  return true;
}

// Segment (or point) core against the triangle when they intersect: the
// least overlap over the face normal and the segment crossed with each
// edge (the faces of their Minkowski difference, so the test is exact).
// Fills the normal and the witness points as GJK would.
void segment_sat(const ShapeCore& core, const TriangleRef& tri, Vec3 side, Vec3& normal,
                 Vec3& p_tri, Vec3& p_core, float& overlap) {
  const Vec3 tri_mid = (tri.p[0] + tri.p[1] + tri.p[2]) * (1.0f / 3.0f);
  const Vec3 d = core.count > 1 ? core.points[1] - core.points[0] : Vec3{};
  normal = side;
  overlap = -1.0f;
  for (int k = 0; k < 4; ++k) {
    Vec3 axis = side;
    if (k > 0) {
      axis = normalize_or_zero(cross(d, tri.p[k % 3] - tri.p[k - 1]));
      if (length_squared(axis) == 0.0f) continue;
      if (dot(axis, core.centroid - tri_mid) < 0.0f) axis = -axis;
    }
    float tri_max = dot(tri.p[0], axis);
    for (int i = 1; i < 3; ++i) tri_max = std::fmax(tri_max, dot(tri.p[i], axis));
    float seg_min = dot(core.points[0], axis);
    for (uint32_t i = 1; i < core.count; ++i)
      seg_min = std::fmin(seg_min, dot(core.points[i], axis));
    const float o = tri_max - seg_min;
    if (overlap < 0.0f || o < overlap) {
      overlap = o;
      normal = axis;
    }
  }
  // The core's point deepest along -normal (the segment's middle when both
  // ends are equally deep).
  p_core = core.points[0];
  if (core.count > 1) {
    const float a = dot(core.points[0], normal);
    const float b = dot(core.points[1], normal);
    p_core = a < b ? core.points[0] : (b < a ? core.points[1] : (core.points[0] + d * 0.5f));
  }
  p_tri = p_core + normal * overlap;
}

// Bit i set: core point i lies over the triangle (inside its prism along
// the normal).
uint64_t over_triangle(const ShapeCore& core, const TriangleRef& tri) {
  Vec3 inward[3];  // in the plane, square to edge k, toward the inside
  for (uint32_t k = 0; k < 3; ++k) inward[k] = cross(tri.normal, tri.p[(k + 1) % 3] - tri.p[k]);
  uint64_t over = 0;
  for (uint32_t i = 0; i < core.count; ++i) {
    bool inside = true;
    for (uint32_t k = 0; k < 3; ++k) {
      inside = inside && dot(core.points[i] - tri.p[k], inward[k]) >= 0.0f;
    }
    if (inside) over |= uint64_t{1} << i;
  }
  return over;
}

// The active-edge bits seen from `side` (the face normal toward the shape):
// the front bits, or the back bits for a shape behind the triangle.
uint32_t side_bits(const TriangleRef& tri, Vec3 side) {
  return dot(side, tri.normal) > 0.0f ? (tri.active_edges & kFrontEdgesMask)
                                      : ((tri.active_edges >> kBackEdgesShift) & kFrontEdgesMask);
}

// An overlapping contact on an active edge or vertex of the triangle
// (`code`), whose normal points past the face of a neighbour across a
// convex fold there: the contact is moved to that face. Under a convex
// fold the surface's solid lies below both faces, so the ways out of it
// through the fold lie between the faces' normals. EPA measures the
// triangle alone, and a shape reaching just past the edge (a corner of a
// body that lies mostly over the neighbour) leaves the triangle soonest
// sideways, along a normal beyond the neighbour's (one whose far corner
// stands out farther along it than the feature); that way runs into the
// neighbour, and its depth is a fraction of the corner's (a box corner
// 48.6 mm under its triangle, 11.5 mm past the fold, read 35.6 mm).
//
// The contact then takes the neighbour's normal, and the depth is how far
// along it the shape's deepest point must move to leave the solid under
// the fold (to rise above either face's plane), over the shape's core
// points that lie over this triangle and EPA's witness point (which lies
// where the shape meets the triangle, so a shape crossing the edge with no
// corner over the triangle keeps its depth). Points over other triangles
// are theirs: the neighbour's plane, carried past the neighbour, stands
// above a convex surface and would read them too deep. At a vertex, of the
// two edges through it, the fold giving the deeper contact. Where the
// normal meets the neighbour's, the depth is EPA's, so the contact does
// not jump as the normal crosses over.
void clamp_to_folds(const ShapeCore& core, const TriangleRef& tri, Vec3 side, uint32_t code,
                    Vec3& normal, Vec3& p_tri, Vec3& p_shape, float& sep) {
  // The edges through the feature (edge e runs from p[e] to p[e + 1]).
  uint32_t edges[2];
  uint32_t edge_count = 1;
  Vec3 corner;
  if (code < kVertexCode) {
    edges[0] = code - kEdgeCode;
    corner = tri.p[edges[0]];
  } else {
    const uint32_t k = code - kVertexCode;
    edges[0] = k;
    edges[1] = (k + 2) % 3;
    edge_count = 2;
    corner = tri.p[k];
  }
  const uint32_t bits = side_bits(tri, side);
  uint64_t over = 0;  // over_triangle's, found at the first fold that needs it
  bool over_known = false;
  bool found = false;
  float best = 0.0f;
  Vec3 best_normal;
  Vec3 best_witness;
  for (uint32_t i = 0; i < edge_count; ++i) {
    const uint32_t e = edges[i];
    // A convex fold seen from the shape's side (a boundary has no
    // neighbour, a concave fold's rises toward the shape).
    if ((bits & (1u << e)) == 0 || !edge_is_fold(tri.active_edges, e)) continue;
    const Vec3 a = tri.p[e];
    const Vec3 b = tri.p[(e + 1) % 3];
    const Vec3 far = tri.across[e];
    if (!(dot(normal, far - corner) > 0.0f)) continue;
    // The neighbour runs the edge from b to a (the sources' winding is
    // consistent across a fold), turned to the shape's side.
    Vec3 n = normalize_or_zero(cross(a - b, far - b));
    if (n == Vec3{}) continue;
    if (dot(side, tri.normal) < 0.0f) n = -n;
    // A move along n lifts a point off this triangle's plane by `lift`
    // per metre (not at all for a fold of 90 degrees or more).
    const float lift = dot(n, side);
    // The move along n that takes the surface point of a core point q
    // (radius r) out of the solid: above the neighbour's plane or this one's.
    auto push = [&](Vec3 q, float r) {
      const float under_n = r - dot(q - a, n);
      const float under_t = r - dot(q - a, side);
      if (!(under_n > 0.0f) || !(under_t > 0.0f)) return 0.0f;
      return lift > 0.0f ? std::fmin(under_n, under_t / lift) : under_n;
    };
    if (!over_known) {
      over = over_triangle(core, tri);
      over_known = true;
    }
    Vec3 witness = p_shape;
    float depth = push(p_shape, 0.0f);
    for (uint32_t k = 0; k < core.count; ++k) {
      if ((over & (uint64_t{1} << k)) == 0) continue;
      const float d = push(core.points[k], core.radius);
      if (d > depth) {
        depth = d;
        witness = core.points[k] - n * core.radius;
      }
    }
    if (!found || depth > best) {
      found = true;
      best = depth;
      best_normal = n;
      best_witness = witness;
    }
  }
  if (!found) return;
  normal = best_normal;
  p_shape = best_witness;
  p_tri = best_witness + best_normal * best;
  sep = 0.0f - best;  // +0 rather than -0 when only touching
}

}  // namespace

namespace triangle_detail {

Vec3 fix_internal_edge(const TriangleRef& tri, Vec3 side, Vec3 normal, bool& replaced,
                       uint32_t& code) {
  const uint32_t bits = side_bits(tri, side);
  // The triangle's support along the normal: the vertex farthest toward
  // the shape (ties to the lower index) and those level with it.
  uint32_t top = 0;
  float best = dot(tri.p[0], normal);
  for (uint32_t k = 1; k < 3; ++k) {
    const float dk = dot(tri.p[k], normal);
    if (dk > best) {
      best = dk;
      top = k;
    }
  }
  bool on[3];
  uint32_t count = 0;
  for (uint32_t k = 0; k < 3; ++k) {
    const Vec3 e = tri.p[top] - tri.p[k];
    on[k] = k == top || dot(e, normal) <= kFeatureSin * length(e);
    count += on[k] ? 1 : 0;
  }
  replaced = false;
  if (count == 3) {
    code = kFaceCode;
    replaced = true;
  } else if (count == 2) {
    const uint32_t e = !on[2] ? 0 : (!on[0] ? 1 : 2);  // edge e joins k = e and e + 1
    code = kEdgeCode + e;
    replaced = (bits & (1u << e)) == 0;
  } else {
    code = kVertexCode + top;
    const uint32_t before = (top + 2) % 3;
    replaced = (bits & ((1u << top) | (1u << before))) == 0;
  }
  return replaced ? side : normal;
}

}  // namespace triangle_detail

ShapeCore make_shape_core(const ConvexProxy& shape, const Vec3* box_half) {
  ShapeCore core;
  if (box_half != nullptr) {
    core.box = true;
    core.box_frame = {shape.position, {shape.axes.c0, shape.axes.c1, shape.axes.c2}, *box_half};
  }
  core.proxy = &shape;
  core.count = shape.count < kProxyMaxPoints ? shape.count : kProxyMaxPoints;
  core.radius = shape.radius;
  Vec3 sum;
  for (uint32_t i = 0; i < core.count; ++i) {
    core.points[i] = shape.position + shape.axes * shape.points[i];
    sum += core.points[i];
  }
  core.centroid = core.count > 0 ? sum * (1.0f / static_cast<float>(core.count)) : shape.position;
  return core;
}

bool collide_convex_triangle(const ShapeCore& core, const TriangleRef& tri, bool one_sided,
                             float speculative_m, TriangleContact& out) {
  if (core.count == 0) return false;
  const bool front = dot(core.centroid - tri.p[0], tri.normal) >= 0.0f;
  if (one_sided && !front) return false;
  const Vec3 side = front ? tri.normal : -tri.normal;
  // The triangle's plane first: a shape whose every core point stands
  // farther off it than its radius and the speculative distance cannot
  // reach the triangle (most of a body's neighbours on a floor), and this
  // costs a few dot products where GJK costs iterations.
  float lowest = dot(core.points[0] - tri.p[0], side);
  for (uint32_t i = 1; i < core.count; ++i) {
    const float d = dot(core.points[i] - tri.p[0], side);
    if (d < lowest) lowest = d;
  }
  if (lowest - core.radius > speculative_m) return false;

  Vec3 normal;
  Vec3 p_tri;
  Vec3 p_shape;  // on the shape's surface
  float sep = 0.0f;
  // A sphere's or a capsule's core (a point, a segment) has its closest
  // points in closed form; a hull's come from GJK.
  ConvexProxy tri_proxy;
  tri_proxy.points = tri.p;
  tri_proxy.count = 3;
  GjkOutput g;
  BoxTriangleFeatures box;
  // (A triangle without a normal, which no source builds, is left to GJK.)
  const bool by_axes = core.box && !(tri.normal == Vec3{});
  if (by_axes) {
    box = box_triangle_features(core.box_frame, tri, speculative_m);
    g.overlap = box.overlap;
    g.distance = box.separation;
    g.normal = box.normal;
    g.point_a = box.on_triangle;
    g.point_b = box.on_box;
  } else if (core.count <= 2) {
    const CoreTriangleClosest c = closest_core_triangle(core.points, core.count, tri.p, tri.normal);
    g.overlap = c.overlap;
    g.distance = c.distance;
    g.normal = c.normal;
    g.point_a = c.on_tri;
    g.point_b = c.on_core;
  } else {
    g = gjk_distance(tri_proxy, *core.proxy);
  }
  // A shape whose core reaches behind the triangle's plane (its centroid
  // in front) without meeting the triangle has gone past one of its edges:
  // a corner poking down just past an edge shared by two triangles of a
  // terrain lies under the neighbour, while the shape crosses the surface
  // only over the triangle it went in through. That triangle clips the
  // corner away (it is beside it), and GJK puts the shape in front of this
  // one, at its distance to the edge; yet the corner is behind this
  // triangle's surface, as deep as its plane says. So when the core's low
  // outline lies over this triangle, that is its contact.
  if (!g.overlap && lowest - core.radius < -kPastEdgeDepth &&
      triangle_detail::face_contact(core, tri, side, false, speculative_m, out)) {
    return true;
  }
  if (!g.overlap) {
    sep = g.distance - core.radius;
    if (!(sep <= speculative_m)) return false;
    normal = g.normal;
    p_tri = g.point_a;
    p_shape = g.point_b - normal * core.radius;
  } else if (by_axes) {
    // The least depth over the separating axes, EPA's answer for a box.
    normal = box.separation < 0.0f ? box.normal : side;  // only touching: no axis of its own
    p_tri = box.on_triangle;
    p_shape = box.on_box;
    sep = box.separation;
  } else if (core.count >= 3) {
    const EpaOutput e = epa_penetration(tri_proxy, *core.proxy, g.simplex);
    normal = e.depth > 0.0f ? e.normal : side;  // a flat difference: no EPA normal
    p_tri = e.point_a;
    p_shape = e.point_b - normal * core.radius;
    sep = -e.depth - core.radius;
  } else {
    float overlap = 0.0f;
    Vec3 p_core;
    segment_sat(core, tri, side, normal, p_tri, p_core, overlap);
    p_shape = p_core - normal * core.radius;
    sep = -overlap - core.radius;
  }

  // Near the face normal, or pushed out through the front of a one-sided
  // triangle the shape reaches through: the face's clipped outline. If the
  // outline misses the triangle, one point at the witness points (code 30;
  // the reduction prefers any other point).
  const bool forced = one_sided && !(dot(normal, side) > 0.0f);
  if (forced || dot(normal, side) >= kFaceSnapCos) {
    if (triangle_detail::face_contact(core, tri, side, false, speculative_m, out)) return true;
    if (forced) {
      return single_point(tri, side, p_tri, p_shape, dot(p_shape - p_tri, side), kFaceCode,
                          speculative_m, out);
    }
    return single_point(tri, normal, p_tri, p_shape, sep, kFaceCode, speculative_m, out);
  }
  // An edge or vertex: kept if active, else made a face contact. When the
  // shape's outline does not reach over the triangle, the inactive
  // feature's neighbour (flat or concave, so the shape lies over it) has
  // the real contact, and this triangle gives none.
  bool replaced = false;
  uint32_t code = kFaceCode;
  normal = triangle_detail::fix_internal_edge(tri, side, normal, replaced, code);
  if (replaced) return triangle_detail::face_contact(core, tri, side, true, speculative_m, out);
  if (g.overlap) clamp_to_folds(core, tri, side, code, normal, p_tri, p_shape, sep);
  return single_point(tri, normal, p_tri, p_shape, sep, code, speculative_m, out);
}

}  // namespace rwd::sim::d3
