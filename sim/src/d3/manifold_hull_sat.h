// SPDX-License-Identifier: MIT
#pragma once
// Hull-hull and box-hull manifolds by the separating-axis test with face
// clipping (manifold_hull_hull.cpp). Pure functions of their inputs' bits:
// no state and no heap. The routines read hulls through HullView, a few
// pointers and counts, so an engine Hull (hull_view) and a box built on the
// stack (make_box_hull) go through the same code without copying a Hull's
// vectors or allocating one per pair.
#include <cstdint>

#include "d3/hull.h"
#include "d3/manifold.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// Read-only view of a hull's geometry, laid out as Hull lays it out (mass
/// frame, CCW face loops, edges listed once with their left and right
/// faces). The faces enclose a solid (no flat views): the edge test's
/// bounds take the origin to be inside when every face plane's offset is
/// at least zero. The arrays must outlive the view. A view beyond the hull limits
/// (more than kHullMaxVertices vertices, 124 faces or 186 edges) or without
/// vertices or faces collides with nothing.
/// Manifold::separating_axis of a hull pair: A's faces from 0, B's from
/// here (hulls have at most 124 faces).
inline constexpr uint8_t kHullFaceAxisB = 128;

struct HullView {
  const Vec3* vertices = nullptr;
  uint32_t vertex_count = 0;
  const HullFace* faces = nullptr;
  uint32_t face_count = 0;
  const uint8_t* face_vertices = nullptr;  ///< loops, indexed by HullFace::first
  const HullEdge* edges = nullptr;
  uint32_t edge_count = 0;
};

inline HullView hull_view(const Hull& hull) {
  return {hull.vertices.data(),
          static_cast<uint32_t>(hull.vertices.size()),
          hull.faces.data(),
          static_cast<uint32_t>(hull.faces.size()),
          hull.face_vertices.data(),
          hull.edges.data(),
          static_cast<uint32_t>(hull.edges.size())};
}

/// A box as a hull, held by value (no heap), so a box-hull pair runs the
/// hull routine. Vertex i is at (+-hx, +-hy, +-hz) with the sign of axis k
/// positive when bit k of i is set; face 2k is the -k face and 2k + 1 the
/// +k face (the numbering collide_boxes uses for its feature ids). The face
/// loops and the 12 edges are the same for every box and live in static
/// tables that view() points at; only vertices and face planes are stored.
struct BoxHull {
  Vec3 vertices[8];
  HullFace faces[6];
  /// The view stays valid while this BoxHull does.
  HullView view() const;
};

/// The box with these half extents, centred on its frame's origin.
BoxHull make_box_hull(Vec3 half_extents);

/// Hull A against hull B, each with a world pose (centre = the hull's
/// mass-frame origin, axes = rotation matrix of its mass frame). Normal from
/// A to B. When a face puts the hulls farther apart than speculative_m,
/// Manifold::separating_axis names it: A's face f as f, B's face f as
/// kHullFaceAxisB + f (an edge pair that separates is not named).
void collide_hulls(const HullView& a, Vec3 position_a, const Mat3& axes_a, const HullView& b,
                   Vec3 position_b, const Mat3& axes_b, float speculative_m, Manifold& out);
void collide_hulls(const Hull& a, Vec3 position_a, const Mat3& axes_a, const Hull& b,
                   Vec3 position_b, const Mat3& axes_b, float speculative_m, Manifold& out);

/// Whether `axis` (a face, as collide_hulls names it in separating_axis)
/// alone puts the hulls farther apart than speculative_m, computed bit for
/// bit as collide_hulls computes that face: when it does, collide_hulls
/// finds no points either, so a caller may skip it.
bool hull_axis_separates(const HullView& a, Vec3 position_a, const Mat3& axes_a, const HullView& b,
                         Vec3 position_b, const Mat3& axes_b, uint8_t axis, float speculative_m);

/// Box A (centre, rotation matrix, half extents) against hull B: the box is
/// made a BoxHull on the stack and the pair runs collide_hulls. Normal from
/// the box to the hull; face ids name box faces as BoxHull numbers them.
void collide_box_hull(Vec3 box_center, const Mat3& box_axes, Vec3 half_extents, const Hull& hull,
                      Vec3 hull_position, const Mat3& hull_axes, float speculative_m,
                      Manifold& out);

}  // namespace rwd::sim::d3
