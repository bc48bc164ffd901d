// SPDX-License-Identifier: MIT
// Pairs with a circle as B: circle-circle and polygon-circle (after Box2D
// v3's b2CollideCircles and b2CollidePolygonAndCircle). A circle touches at
// one point, so these manifolds hold at most one point, id 0: the single
// point keeps its warm start as a circle rolls from a face onto a corner.
#include "manifold2_internal.h"

namespace rwd::sim2d::detail {

void collide_round_pair(V2 pa, W ra, V2 pb, W rb, V2 fallback, const Xf& xa, const Xf& xb,
                        W speculative, Manifold2& out) {
  out = {};
  const UnitLength d = vnormalize(pb - pa);
  // Coincident centres have no direction: the caller's fallback keeps the
  // normal unit (and the choice the same on every peer).
  const V2 normal = d.length == 0 ? fallback : d.unit;
  const W separation = d.length - ra - rb;
  if (separation > speculative) return;
  // Midway between the two surface points.
  const V2 ca = vmul_add(pa, ra, normal);
  const V2 cb = vmul_sub(pb, rb, normal);
  set_point(out.points[0], xa, xb, vmid(ca, cb), separation, 0);
  finish(out, xa, normal, 1);
}

void collide_circles(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                     Manifold2& out) {
  const Xf xf = inv_mul_xf(xa, xb);
  const V2 pa = v_from(a.vertices[0]);
  const V2 pb = transform_point(xf, v_from(b.vertices[0]));
  collide_round_pair(pa, w_from(a.radius), pb, w_from(b.radius), V2{kWOne, 0}, xa, xb, speculative,
                     out);
}

void collide_polygon_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                            W speculative, Manifold2& out) {
  out = {};
  const WPoly poly = to_wpoly(a);
  const Xf xf = inv_mul_xf(xa, xb);
  const V2 c = transform_point(xf, v_from(b.vertices[0]));
  const W rb = w_from(b.radius);
  const W radius = poly.radius + rb;

  // The face the centre lies farthest outside of; ties keep the lowest index.
  int face = 0;
  W separation = INT64_MIN;
  for (int i = 0; i < poly.count; ++i) {
    const W s = vdot(poly.normals[i], c - poly.vertices[i]);
    if (s > separation) {
      separation = s;
      face = i;
    }
  }
  if (separation - radius > speculative) return;

  const V2 v1 = poly.vertices[face];
  const V2 v2 = poly.vertices[face + 1 < poly.count ? face + 1 : 0];
  const W u1 = vdot(c - v1, v2 - v1);
  const W u2 = vdot(c - v2, v1 - v2);
  // Outside the face's slab (and outside the polygon) the nearest feature
  // is a vertex and the normal runs from it to the centre.
  if (u1 < 0 && separation > 0) {
    collide_round_pair(v1, poly.radius, c, rb, poly.normals[face], xa, xb, speculative, out);
    return;
  }
  if (u2 < 0 && separation > 0) {
    collide_round_pair(v2, poly.radius, c, rb, poly.normals[face], xa, xb, speculative, out);
    return;
  }
  const V2 normal = poly.normals[face];
  const W s = vdot(c - v1, normal);
  // A's surface is the face moved out by its rounding radius; B's surface
  // is the centre moved back along the normal by the circle's radius.
  const V2 ca = vmul_add(c, poly.radius - s, normal);
  const V2 cb = vmul_sub(c, rb, normal);
  set_point(out.points[0], xa, xb, vmid(ca, cb), s - radius, 0);
  finish(out, xa, normal, 1);
}

}  // namespace rwd::sim2d::detail
