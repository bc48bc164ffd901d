// SPDX-License-Identifier: MIT
// Segment pairs. A segment is level geometry: a two-vertex polygon of
// radius 0 whose two faces both collide (so a body meets it from either
// side). Against a circle it is a capsule of radius 0; against a polygon or
// a capsule it goes through the rounded-polygon routine with the segment as
// A, as Box2D v3's b2CollideSegmentAndPolygon does. Segments never collide
// with each other: level geometry is static.
#include "manifold2_internal.h"

namespace rwd::sim2d::detail {

void collide_segment_polygon(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                             W speculative, Manifold2& out) {
  collide_wpolys(to_wpoly(a), xa, to_wpoly(b), xb, speculative, out);
}

void collide_none(const Shape2D&, const Xf&, const Shape2D&, const Xf&, W, Manifold2& out) {
  out = {};
}

}  // namespace rwd::sim2d::detail
