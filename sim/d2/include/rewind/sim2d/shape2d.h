// SPDX-License-Identifier: MIT
#pragma once
// Shapes of the 2D lane. Every coordinate is Q16.16 (metres by convention)
// in the body's own frame. A shape is a small value (no pointers, trivially
// copyable), so it lives in the world state with its body and is saved,
// restored and checksummed with it.
#include <array>
#include <cstdint>
#include <span>

#include "rewind/core/status.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"

namespace rwd::sim2d {

using fixed::Fx;
using fixed::Vec2;

enum class ShapeType2D : uint8_t {
  kCircle = 0,   ///< vertices[0] is the centre; radius > 0
  kCapsule = 1,  ///< a segment vertices[0]..vertices[1] swept by radius > 0
  kPolygon = 2,  ///< convex, counter-clockwise, 3..8 vertices, optionally rounded
  kSegment = 3,  ///< a two-sided edge vertices[0]..vertices[1] (static level geometry)
  /// A one-sided edge of a chain: vertices[0]..vertices[1] with the ghost
  /// vertices[2] (the previous point) and vertices[3] (the next point);
  /// count 2. See make_chain_segment.
  kChainSegment = 4,
};
inline constexpr int kShapeTypeCount2D = 5;

/// The most vertices a convex polygon may have.
inline constexpr int kMaxPolygonVertices = 8;

/// One shape. Which fields mean something depends on `type` (see
/// ShapeType2D); the rest are zero, so equal shapes compare and hash equal.
/// Build shapes with the factories below: they validate and fill every
/// derived field (normals, centroid).
struct Shape2D {
  ShapeType2D type = ShapeType2D::kCircle;
  /// Number of meaningful vertices: 1 (circle), 2 (capsule, segment, chain
  /// segment, whose ghosts in vertices[2..3] are not counted) or 3..8
  /// (polygon).
  uint8_t count = 0;
  /// Circle and capsule radius; the rounding radius of a polygon (>= 0).
  Fx radius;
  std::array<Vec2, kMaxPolygonVertices> vertices{};
  /// Polygon only: outward unit normal of edge i (vertices[i] to
  /// vertices[i + 1]).
  std::array<Vec2, kMaxPolygonVertices> normals{};
  /// The centre of area (polygon), of the segment, or the circle's centre.
  Vec2 centroid;

  friend bool operator==(const Shape2D&, const Shape2D&) = default;
};

/// A circle of `radius` (> 0) centred at `center`.
Result<Shape2D> make_circle(Fx radius, Vec2 center = {});
/// A capsule: the segment p1..p2 (distinct points, each coordinate of
/// p2 - p1 within the Fx range) swept by `radius` (> 0).
Result<Shape2D> make_capsule(Vec2 p1, Vec2 p2, Fx radius);
/// An axis-aligned box of half extents hx, hy (each > 0) about the origin:
/// the spec's "aabb" shape and the common box. Vertices run
/// counter-clockwise from (-hx, -hy). Built through make_polygon, so a box
/// too small to carry mass is refused with the polygon's message.
Result<Shape2D> make_box(Fx half_width, Fx half_height);
/// A box of half extents hx, hy centred at `center` and turned by `angle`
/// radians (Rot2::from_angle); the centroid is `center` exactly.
Result<Shape2D> make_box(Fx half_width, Fx half_height, Vec2 center, Fx angle);
/// A convex polygon through `points` (3..8, either winding; stored
/// counter-clockwise, a clockwise outline walked backwards from point 0 so
/// point 0 stays first), rounded by `radius` (>= 0). Refused with
/// kInvalidArgument and a message naming the fault and the point index (in
/// the caller's order): too few or too many points, repeated points,
/// collinear consecutive points, a reflex corner (not convex), a
/// self-crossing outline (zero signed area, or a point outside an edge of
/// an outline that turns one way but winds more than once), an edge longer
/// than the Fx range, or an area below 2^-16 m^2 (too small to carry mass).
/// Every check is an exact integer predicate. normals[i] is
/// fixed::normalized() of the edge's clockwise perpendicular; the centroid
/// is the centre of area rounded once from exact sums.
/// The points are kept as given (no hull is taken), so what was authored is
/// what collides.
Result<Shape2D> make_polygon(std::span<const Vec2> points, Fx radius = Fx());
/// A two-sided segment p1..p2 (distinct points): level edges and walls.
/// It has no area, so only static and kinematic bodies may use it.
Result<Shape2D> make_segment(Vec2 p1, Vec2 p2);

/// One edge of a chain (see chain2d.h for whole chains): the one-sided
/// segment p1..p2 between its neighbours' far points, the ghosts ghost1
/// (the point before p1) and ghost2 (the point after p2). Stored as
/// vertices {p1, p2, ghost1, ghost2}, count 2: bounds and the broad phase
/// see p1..p2 only.
///
/// Convention (Box2D's chain convention): the normal is the right
/// perpendicular of the direction p1 -> p2, and bodies collide only from
/// that side; the left side is solid (no contact from behind). A
/// counter-clockwise loop is therefore solid inside and collides on its
/// outside like a polygon; a clockwise loop is a container that keeps
/// bodies inside. A floor whose open side is up runs right to left.
///
/// The ghosts remove ghost collisions at the joints: a contact normal that
/// would come from p1 or p2 and point into a direction the neighbouring
/// edge already covers is dropped (at a convex joint) or snapped to the
/// edge's face normal (at a flat or concave joint), so a body sliding
/// across joints of collinear edges meets one flat surface.
/// Refused (kInvalidArgument, naming the fault): p1 == p2, ghost1 == p1,
/// ghost2 == p2, or an edge (ghost edges included) longer than the Fx
/// range. Like a segment it has no area: static and kinematic bodies only.
/// It has no thickness either: a body whose centre crosses the edge within
/// one step (faster than the speculative distance per step) is behind it
/// and passes; such bodies need BodyDef2D::continuous.
Result<Shape2D> make_chain_segment(Vec2 ghost1, Vec2 p1, Vec2 p2, Vec2 ghost2);

/// Checks a shape built by hand (or read from bytes) the way the factories
/// would: kInvalidArgument naming the fault, kOk otherwise. The shape must
/// equal what its factory builds from its vertices and radius, derived
/// fields (normals, centroid) and zero padding included; a polygon must
/// already be counter-clockwise.
Status validate_shape(const Shape2D& shape);

}  // namespace rwd::sim2d
