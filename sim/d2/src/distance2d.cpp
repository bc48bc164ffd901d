// SPDX-License-Identifier: MIT
// Distance between rounded convex cores. Separated cores are nearest at a
// vertex of one and an edge (or vertex) of the other, so the minimum over
// those pairs is exact; overlapping cores are parted least along one of the
// edge normals of either (their Minkowski difference's faces), so the
// separating-axis maximum is the depth. Which case applies is decided by
// the axis test when one core has area; two point/segment cores have
// no inside, so they overlap only when their distance is zero.
#include "distance2d.h"

#include "rewind/fixed/wide_int.h"

namespace rwd::sim2d::detail {

namespace {

U128 length_sq_exact(V2 v) {
  return static_cast<U128>(static_cast<I128>(v.x) * v.x + static_cast<I128>(v.y) * v.y);
}

struct Closest {
  U128 distance_sq = ~U128{0};
  V2 a;
  V2 b;
};

int edge_count(const WPoly& p) {
  // A point is one degenerate edge, a segment one edge, a polygon closes.
  return p.count < 3 ? 1 : p.count;
}

V2 edge_end(const WPoly& p, int i) {
  if (p.count == 1) return p.vertices[0];
  return p.vertices[i + 1 < p.count ? i + 1 : 0];
}

// Vertices of `from` against edges of `to`; `swap` says which side is A.
void vertex_edge(const WPoly& from, const WPoly& to, bool swap, Closest& best) {
  const int edges = edge_count(to);
  for (int i = 0; i < from.count; ++i) {
    const V2 p = from.vertices[i];
    for (int j = 0; j < edges; ++j) {
      const V2 c = closest_on_segment(p, to.vertices[j], edge_end(to, j));
      const U128 d2 = length_sq_exact(c - p);
      // Strictly smaller keeps the first pair found, so ties go the same
      // way on every run.
      if (d2 < best.distance_sq) best = swap ? Closest{d2, c, p} : Closest{d2, p, c};
    }
  }
}

struct Axis {
  bool valid = false;
  W separation = INT64_MIN;
  V2 normal;  // A to B
  V2 point_a;
  V2 point_b;
};

// The faces of `p1` against the vertices of `p2`; flip when p1 is B.
void face_axes(const WPoly& p1, const WPoly& p2, bool flip, Axis& best) {
  if (p1.count < 2) return;
  for (int i = 0; i < p1.count; ++i) {
    W s = INT64_MAX;
    int deepest = 0;
    for (int j = 0; j < p2.count; ++j) {
      const W d = vdot(p1.normals[i], p2.vertices[j] - p1.vertices[i]);
      if (d < s) {
        s = d;
        deepest = j;
      }
    }
    if (best.valid && s <= best.separation) continue;
    const V2 deep = p2.vertices[deepest];
    const V2 on_face = vmul_sub(deep, s, p1.normals[i]);
    best.valid = true;
    best.separation = s;
    best.normal = flip ? -p1.normals[i] : p1.normals[i];
    best.point_a = flip ? deep : on_face;
    best.point_b = flip ? on_face : deep;
  }
}

}  // namespace

WPoly shape_core(const Shape2D& shape, const Xf& xf) {
  if (shape.type == ShapeType2D::kCircle) {
    WPoly p;
    p.count = 1;
    p.radius = w_from(shape.radius);
    p.vertices[0] = transform_point(xf, v_from(shape.vertices[0]));
    return p;
  }
  return transform_wpoly(xf, to_wpoly(shape));
}

WPoly point_core(V2 point) {
  WPoly p;
  p.count = 1;
  p.vertices[0] = point;
  return p;
}

WPoly translate_core(const WPoly& poly, V2 offset) {
  WPoly out = poly;
  for (int i = 0; i < out.count; ++i) out.vertices[i] += offset;
  return out;
}

V2 closest_on_segment(V2 p, V2 a, V2 b) {
  const V2 e = b - a;
  const V2 m = p - a;
  // Both dot products exact in Q64.64; the parameter num / den is taken to
  // Q32.32 only once it is known to lie in (0, 1), so the shift cannot
  // overflow (den < 2^96 for edges inside the Fx range).
  const I128 den = static_cast<I128>(e.x) * e.x + static_cast<I128>(e.y) * e.y;
  if (den == 0) return a;
  const I128 num = static_cast<I128>(m.x) * e.x + static_cast<I128>(m.y) * e.y;
  if (num <= 0) return a;
  if (num >= den) return b;
  const W t = static_cast<W>((num << kWFrac) / den);
  return {a.x + wmul(t, e.x), a.y + wmul(t, e.y)};
}

Distance2 shape_distance(const WPoly& a, const WPoly& b) {
  Closest best;
  vertex_edge(a, b, false, best);
  vertex_edge(b, a, true, best);
  Axis axis;
  face_axes(a, b, false, axis);
  face_axes(b, a, true, axis);

  const bool solid = a.count >= 3 || b.count >= 3;
  const bool overlapping = best.distance_sq == 0 || (solid && axis.valid && axis.separation <= 0);
  Distance2 out;
  V2 core_a;
  V2 core_b;
  if (!overlapping) {
    const UnitLength n = vnormalize(best.b - best.a);
    out.normal = n.unit;
    out.distance = n.length - a.radius - b.radius;
    core_a = best.a;
    core_b = best.b;
  } else if (axis.valid) {
    out.normal = axis.normal;
    out.distance = wmin(axis.separation, 0) - a.radius - b.radius;
    core_a = axis.point_a;
    core_b = axis.point_b;
  } else {
    // Two coincident points: any direction parts them; up is as good as
    // any and the same on every run.
    out.distance = -a.radius - b.radius;
    core_a = best.a;
    core_b = best.b;
  }
  out.point_a = vmul_add(core_a, a.radius, out.normal);
  out.point_b = vmul_sub(core_b, b.radius, out.normal);
  return out;
}

}  // namespace rwd::sim2d::detail
