// SPDX-License-Identifier: MIT
// Rays against circles, capsules, segments and (rounded) polygons. The ray
// is taken into the body's frame so products stay small however far from
// the world origin the body sits. Every non-circle shape is a convex core
// whose edges are pushed out by the radius, with a disc at each vertex
// when the radius is not zero: the first front-facing edge or disc the ray
// meets is the hit. A ray from inside the shape is behind every edge line
// and inside the discs, so it meets none, which is the "inside does not
// hit" rule for free. A capsule or segment is a two-edge core whose edges
// face opposite ways, which makes segments two-sided.
#include "ray_shape2d.h"

#include "manifold2_internal.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::sim2d::detail {

namespace {

// Slack (m) on an edge's ends, so a ray through a sharp corner, rounded a
// few units of 2^-32 m off the vertex, still meets one of its two edges.
constexpr W kEdgeEndSlack = W{1} << 12;

}  // namespace

bool ray_circle(V2 origin, V2 unit, W max_length, V2 center, W radius, W& s, V2& normal) {
  const V2 m = origin - center;
  const W b = vdot(m, unit);
  // |m|^2 - r^2 exact in Q64.64 (m may be metres to kilometres).
  const I128 c = static_cast<I128>(m.x) * m.x + static_cast<I128>(m.y) * m.y -
                 static_cast<I128>(radius) * radius;
  if (c < 0) return false;  // starts inside
  if (b > 0) return false;  // outside and heading away
  const I128 disc = static_cast<I128>(b) * b - c;
  if (disc < 0) return false;
  const W root = static_cast<W>(fixed::isqrt128(static_cast<U128>(disc)));
  W hit = -b - root;
  if (hit < 0) hit = 0;
  if (hit > max_length) return false;
  s = hit;
  const UnitLength n = vnormalize(vmul_add(m, hit, unit));
  normal = n.length > 0 ? n.unit : -unit;
  return true;
}

bool ray_edge(V2 origin, V2 unit, W max_length, V2 p0, V2 p1, V2 n, W& s) {
  const W den = vdot(n, unit);
  if (den >= 0) return false;  // parallel or leaving through it
  const W ahead = vdot(n, origin - p0);
  if (ahead < 0) return false;  // behind the edge line
  // Beyond max_length, tested as a product so the quotient cannot overflow.
  if (ahead > wmul(-den, max_length)) return false;
  const W hit = wdiv(ahead, -den);
  if (hit > max_length) return false;
  // Within the edge: the hit point's position along p0..p1, measured along
  // the edge's direction, which is the unit normal turned a quarter
  // counter-clockwise (every edge runs that way round its core), so no
  // square root is needed.
  const V2 h = vmul_add(origin, hit, unit);
  const V2 along_edge = vperp(n);
  const W along = vdot(h - p0, along_edge);
  const W length = vdot(p1 - p0, along_edge);
  if (along < -kEdgeEndSlack || along > length + kEdgeEndSlack) return false;
  s = hit;
  return true;
}

bool ray_shape(const Shape2D& shape, const Xf& xf, V2 origin, V2 unit, W max_length,
               RayResult2& out) {
  if (shape.count == 0 || shape.count > kMaxPolygonVertices) return false;
  const V2 o = inv_transform_point(xf, origin);
  const V2 u = inv_rotate(xf.q, unit);
  bool found = false;
  W best = max_length;
  V2 best_normal;
  if (shape.type == ShapeType2D::kCircle) {
    found =
        ray_circle(o, u, best, v_from(shape.vertices[0]), w_from(shape.radius), best, best_normal);
  } else {
    const WPoly p = to_wpoly(shape);
    for (int i = 0; i < p.count; ++i) {
      const V2 n = p.normals[i];
      const V2 a = vmul_add(p.vertices[i], p.radius, n);
      const V2 b = vmul_add(p.vertices[i + 1 < p.count ? i + 1 : 0], p.radius, n);
      W s = 0;
      // Strictly nearer only: the first of two equal hits (a corner) keeps.
      if (ray_edge(o, u, best, a, b, n, s) && (!found || s < best)) {
        found = true;
        best = s;
        best_normal = n;
      }
    }
    if (p.radius > 0) {
      for (int i = 0; i < p.count; ++i) {
        W s = 0;
        V2 n;
        if (ray_circle(o, u, best, p.vertices[i], p.radius, s, n) && (!found || s < best)) {
          found = true;
          best = s;
          best_normal = n;
        }
      }
    }
  }
  if (!found) return false;
  out.distance = best;
  out.point = vmul_add(origin, best, unit);
  out.normal = rotate(xf.q, best_normal);
  return true;
}

}  // namespace rwd::sim2d::detail
