// SPDX-License-Identifier: MIT
// Helpers shared by the manifold routines: shapes widened to W, the
// exact lerp used by clipping, and the conversion of a point found in A's
// frame into the world-axis anchors the solver reads.
#include "manifold2_internal.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::sim2d::detail {

V2 unit_normal_from(Vec2 n) {
  const V2 v = v_from(n);
  // |v| is within an Fx ulp of 1, so one Newton step of 1/sqrt about 1
  // leaves it unit to ~2^-30; the direction keeps its authored bits.
  const W scale = (3 * kWOne - vlength_sq(v)) / 2;
  return vscale(scale, v);
}

WPoly to_wpoly(const Shape2D& shape) {
  WPoly p;
  p.radius = w_from(shape.radius);
  if (shape.type == ShapeType2D::kPolygon) {
    p.count = shape.count;
    for (int i = 0; i < p.count; ++i) {
      p.vertices[i] = v_from(shape.vertices[i]);
      p.normals[i] = unit_normal_from(shape.normals[i]);
    }
    return p;
  }
  // Capsule or segment: a two-gon. Edge 0 runs v0 -> v1 with the outward
  // (clockwise) normal, edge 1 runs back with the opposite one.
  p.count = 2;
  p.vertices[0] = v_from(shape.vertices[0]);
  p.vertices[1] = v_from(shape.vertices[1]);
  const V2 u = vnormalize(p.vertices[1] - p.vertices[0]).unit;
  p.normals[0] = vperp_cw(u);
  p.normals[1] = -p.normals[0];
  return p;
}

WPoly transform_wpoly(const Xf& xf, const WPoly& poly) {
  WPoly out;
  out.radius = poly.radius;
  out.count = poly.count;
  for (int i = 0; i < poly.count; ++i) {
    out.vertices[i] = transform_point(xf, poly.vertices[i]);
    out.normals[i] = rotate(xf.q, poly.normals[i]);
  }
  return out;
}

V2 lerp_ratio(V2 a, V2 b, W num, W den) {
  const auto along = [&](W from, W to) {
    const I128 d = static_cast<I128>(to) - from;
    return from + static_cast<W>(fixed::div_round(d * num, den));
  };
  return {along(a.x, b.x), along(a.y, b.y)};
}

void set_point(ManifoldPoint2& mp, const Xf& xa, const Xf& xb, V2 local_point, W separation,
               uint16_t id) {
  mp.anchor_a = rotate(xa.q, local_point);
  // Both anchors name the same world point: xa.p + anchor_a == xb.p + anchor_b.
  mp.anchor_b = mp.anchor_a + (xa.p - xb.p);
  mp.separation = separation;
  mp.id = id;
}

void finish(Manifold2& out, const Xf& xa, V2 local_normal, int count) {
  out.normal = rotate(xa.q, local_normal);
  out.count = count;
}

}  // namespace rwd::sim2d::detail
