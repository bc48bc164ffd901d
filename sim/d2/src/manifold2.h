// SPDX-License-Identifier: MIT
#pragma once
// Contact manifolds of the 2D lane: one routine per shape pair in an N x N
// table (reversed pairs swap their roles), every value Q32.32. A manifold
// holds up to two points; points farther apart than the speculative
// distance are left out, closer ones (even separated) are kept so the
// solver can stop bodies before they touch.
#include <cstdint>

#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

struct ManifoldPoint2 {
  /// The contact point relative to body A's origin and to body B's origin,
  /// in world axes (m). The point lies midway between the two surfaces.
  V2 anchor_a;
  V2 anchor_b;
  /// Signed distance between the surfaces along the normal (m); negative
  /// when they overlap.
  W separation = 0;
  /// Names the pair of features (vertex/edge indices) that made the point,
  /// so a point keeps its warm-start impulse while the same features touch:
  /// (A's vertex index << 8) | B's vertex index for polygon, capsule and
  /// segment pairs (the same whichever face is the reference); 0 for the
  /// single point of a pair with a circle.
  uint16_t id = 0;
};

struct Manifold2 {
  /// Unit normal in world axes, pointing from A to B.
  V2 normal;
  ManifoldPoint2 points[2];
  int count = 0;
};

/// A convex polygon in W, possibly rounded: a polygon shape, or a capsule or
/// segment as a two-vertex polygon whose two normals face opposite ways.
struct WPoly {
  V2 vertices[kMaxPolygonVertices];
  V2 normals[kMaxPolygonVertices];
  W radius = 0;
  int count = 0;
};

/// A shape widened once for every pair it meets in a step: its polygon in W
/// and its reach (an upper bound of its distance from the body origin).
/// Only polygons and capsules are widened: every pair of the two is
/// collided as two polygons.
struct WideShape2 {
  WPoly poly;
  W reach = 0;
};
/// Whether `s` is a shape collide_wide() takes (a polygon or a capsule).
bool widens(const Shape2D& s);
/// `s` (widens(s)) as collide_wide() reads it.
void widen(const Shape2D& s, WideShape2& out);
/// collide() for two widened shapes: the same manifold, without widening
/// either shape again.
void collide_wide(const WideShape2& a, const Xf& xa, const WideShape2& b, const Xf& xb,
                  W speculative, Manifold2& out);

/// The manifold of shape `a` on a body at `xa` (the body origin's
/// transform) against shape `b` at `xb`, keeping points whose separation is
/// below `speculative` (m, > 0). `out` is overwritten; count 0 means apart.
/// Any pair of ShapeType2D values is accepted; segments and chain segments
/// against each other give no contact (level geometry does not collide
/// with itself).
void collide(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
             Manifold2& out);

}  // namespace rwd::sim2d::detail
