// SPDX-License-Identifier: MIT
// Capsule pairs. A capsule (or a segment, a capsule of radius 0) against a
// circle follows Box2D v3's b2CollideCapsuleAndCircle: the nearest point of
// the core segment becomes a circle centre. A capsule against a capsule is
// two rounded two-gons through the polygon routine, whose reference-face
// clipping gives two points when the capsules lie side by side.
#include "manifold2_internal.h"

namespace rwd::sim2d::detail {

void collide_capsule_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                            W speculative, Manifold2& out) {
  const Xf xf = inv_mul_xf(xa, xb);
  const V2 p1 = v_from(a.vertices[0]);
  const V2 p2 = v_from(a.vertices[1]);
  const V2 pb = transform_point(xf, v_from(b.vertices[0]));
  const V2 e = p2 - p1;
  // Nearest point of the core: an end, or the exact projection between.
  const W s1 = vdot(pb - p1, e);
  const W s2 = vdot(p2 - pb, e);
  V2 pa;
  if (s1 < 0) {
    pa = p1;
  } else if (s2 < 0) {
    pa = p2;
  } else {
    pa = lerp_ratio(p1, p2, s1, vdot(e, e));
  }
  // A centre on the core line itself: push out along the core's left side.
  const V2 fallback = vperp(vnormalize(e).unit);
  collide_round_pair(pa, w_from(a.radius), pb, w_from(b.radius), fallback, xa, xb, speculative,
                     out);
}

void collide_capsules(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                      Manifold2& out) {
  collide_wpolys(to_wpoly(a), xa, to_wpoly(b), xb, speculative, out);
}

}  // namespace rwd::sim2d::detail
