// SPDX-License-Identifier: MIT
#pragma once
// Shared pieces of the manifold routines. Every routine works in body A's
// frame: B's features are brought there with inv_mul_xf, so products stay
// small however far from the world origin the pair sits, and only the final
// normal and anchors are turned back into world axes.
#include <cstdint>

#include "manifold2.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// The linear slop of the 2D lane (m): contact tolerances are fractions of it.
inline constexpr W kLinearSlop = w_ratio(5, 1000);
/// How much deeper B's best face must be before it becomes the reference
/// face instead of A's: the hysteresis keeps the reference (and so the point
/// ids) from flickering between two nearly equal faces.
inline constexpr W kReferenceTolerance = kLinearSlop / 10;
/// Below this core separation the polygons are treated as touching and
/// clipped; above it a vertex-vertex normal is long enough to normalize.
inline constexpr W kVertexGap = kLinearSlop / 10;

/// Feature ids: A's vertex index in the high byte, B's in the low byte.
/// A clipped point is named by the reference face's side-plane vertex and
/// the incident vertex, always written as (A's index, B's index) whichever
/// polygon holds the reference face, so the id of a touching corner pair
/// survives the reference face switching between A and B (as in Box2D).
constexpr uint16_t make_id(int vertex_a, int vertex_b) {
  return static_cast<uint16_t>(((vertex_a & 0xFF) << 8) | (vertex_b & 0xFF));
}

/// A stored unit normal (within an Fx ulp of unit length) brought to unit
/// length in W with one Newton step, as renormalize() does for rotations.
V2 unit_normal_from(Vec2 n);
/// The shape in its own body frame (polygon, capsule or segment).
WPoly to_wpoly(const Shape2D& shape);
/// The same polygon moved by xf (vertices and normals).
WPoly transform_wpoly(const Xf& xf, const WPoly& poly);

/// a + (b - a) * num / den, rounded once from the exact 128-bit product;
/// den > 0.
V2 lerp_ratio(V2 a, V2 b, W num, W den);

/// floor((a + b) / 2) per component, without overflowing the sum.
constexpr V2 vmid(V2 a, V2 b) {
  return {(a.x >> 1) + (b.x >> 1) + (a.x & b.x & 1), (a.y >> 1) + (b.y >> 1) + (a.y & b.y & 1)};
}

/// Writes `local_point` (in A's frame) as a manifold point in world axes.
void set_point(ManifoldPoint2& mp, const Xf& xa, const Xf& xb, V2 local_point, W separation,
               uint16_t id);

/// Sets out.normal from a normal in A's frame and the point count.
void finish(Manifold2& out, const Xf& xa, V2 local_normal, int count);

/// The one-point manifold of two rounded points (centres pa, pb in A's
/// frame, radii ra, rb); `fallback` is the normal used when pa == pb.
void collide_round_pair(V2 pa, W ra, V2 pb, W rb, V2 fallback, const Xf& xa, const Xf& xb,
                        W speculative, Manifold2& out);

/// Clips the incident face `inc_edge` of `inc` to the side planes of the
/// reference face `ref_edge` of `ref` and writes the points that lie within
/// `speculative` (points in A's frame; `flip`: B holds the reference).
void clip(const WPoly& ref, const WPoly& inc, int ref_edge, int inc_edge, bool flip, const Xf& xa,
          const Xf& xb, W speculative, Manifold2& out);

// The pair routines. Each overwrites `out`; A is the first shape.
void collide_circles(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                     Manifold2& out);
/// Capsule or segment A against circle B.
void collide_capsule_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                            W speculative, Manifold2& out);
void collide_polygon_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                            W speculative, Manifold2& out);
/// Any two of polygon, capsule, segment (each as a rounded polygon).
void collide_wpolys(const WPoly& a, const Xf& xa, const WPoly& b, const Xf& xb, W speculative,
                    Manifold2& out);
void collide_capsules(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                      Manifold2& out);
void collide_polygons(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                      Manifold2& out);
/// Segment A against a polygon or capsule B.
void collide_segment_polygon(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                             W speculative, Manifold2& out);
/// Chain segment A against circle B (one-sided, ghost vertices honoured).
void collide_chain_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                          W speculative, Manifold2& out);
/// Chain segment A against a polygon or capsule B (one-sided, ghost
/// vertices honoured).
void collide_chain_polygon(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                           W speculative, Manifold2& out);
/// No contact (segment or chain segment against segment or chain segment).
void collide_none(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                  Manifold2& out);

}  // namespace rwd::sim2d::detail
