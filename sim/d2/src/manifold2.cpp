// SPDX-License-Identifier: MIT
// The collide() entry: an N x N table of pair routines indexed by the two
// shape types. Each routine exists for one order only; the reversed pair
// runs it with the roles swapped, then flips the normal and swaps the
// anchors, so collide(a, b) and collide(b, a) describe the same contact.
#include <utility>

#include "manifold2_internal.h"

namespace rwd::sim2d::detail {

namespace {

using PairFn = void (*)(const Shape2D&, const Xf&, const Shape2D&, const Xf&, W, Manifold2&);

struct PairEntry {
  PairFn fn;
  bool reversed;
};

// Rows: shape A's type; columns: shape B's type (ShapeType2D order:
// circle, capsule, polygon, segment, chain segment).
constexpr PairEntry kPairs[kShapeTypeCount2D][kShapeTypeCount2D] = {
    {{collide_circles, false},
     {collide_capsule_circle, true},
     {collide_polygon_circle, true},
     {collide_capsule_circle, true},
     {collide_chain_circle, true}},
    {{collide_capsule_circle, false},
     {collide_capsules, false},
     {collide_polygons, false},
     {collide_segment_polygon, true},
     {collide_chain_polygon, true}},
    {{collide_polygon_circle, false},
     {collide_polygons, false},
     {collide_polygons, false},
     {collide_segment_polygon, true},
     {collide_chain_polygon, true}},
    {{collide_capsule_circle, false},
     {collide_segment_polygon, false},
     {collide_segment_polygon, false},
     {collide_none, false},
     {collide_none, false}},
    {{collide_chain_circle, false},
     {collide_chain_polygon, false},
     {collide_chain_polygon, false},
     {collide_none, false},
     {collide_none, false}},
};

// An upper bound of the shape's reach from its body origin: the largest
// |x| + |y| of its vertices (>= the Euclidean distance) plus its radius.
W reach(const Shape2D& s) {
  W r = 0;
  for (int i = 0; i < s.count && i < kMaxPolygonVertices; ++i) {
    r = wmax(r, wabs(w_from(s.vertices[i].x)) + wabs(w_from(s.vertices[i].y)));
  }
  return r + w_from(s.radius);
}

// Bodies farther apart on either axis than both reaches plus the
// speculative distance cannot touch. Leaving early also keeps the pair
// routines' squared distances inside the W range for any input.
bool beyond_reach(W reach_a, const Xf& xa, W reach_b, const Xf& xb, W speculative) {
  const W limit = reach_a + reach_b + speculative;
  const V2 d = xb.p - xa.p;
  return wabs(d.x) > limit || wabs(d.y) > limit;
}

}  // namespace

bool widens(const Shape2D& s) {
  return (s.type == ShapeType2D::kPolygon || s.type == ShapeType2D::kCapsule) && s.count > 0 &&
         s.count <= kMaxPolygonVertices;
}

void widen(const Shape2D& s, WideShape2& out) {
  out.poly = to_wpoly(s);
  out.reach = reach(s);
}

void collide_wide(const WideShape2& a, const Xf& xa, const WideShape2& b, const Xf& xb,
                  W speculative, Manifold2& out) {
  out = {};
  if (beyond_reach(a.reach, xa, b.reach, xb, speculative)) return;
  collide_wpolys(a.poly, xa, b.poly, xb, speculative, out);
}

void collide(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
             Manifold2& out) {
  out = {};
  const auto ta = static_cast<unsigned>(a.type);
  const auto tb = static_cast<unsigned>(b.type);
  if (ta >= kShapeTypeCount2D || tb >= kShapeTypeCount2D) return;
  // A hand-built shape with no vertices (or too many) has no surface; the
  // routines index vertices by count, so it is refused here.
  if (a.count == 0 || b.count == 0) return;
  if (a.count > kMaxPolygonVertices || b.count > kMaxPolygonVertices) return;
  if (beyond_reach(reach(a), xa, reach(b), xb, speculative)) return;

  const PairEntry& e = kPairs[ta][tb];
  if (!e.reversed) {
    e.fn(a, xa, b, xb, speculative, out);
    return;
  }
  e.fn(b, xb, a, xa, speculative, out);
  out.normal = -out.normal;
  for (int i = 0; i < out.count; ++i) std::swap(out.points[i].anchor_a, out.points[i].anchor_b);
}

}  // namespace rwd::sim2d::detail
