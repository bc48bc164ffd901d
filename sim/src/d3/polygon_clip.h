// SPDX-License-Identifier: MIT
#pragma once
// Cutting a convex polygon by one plane (a step of Sutherland-Hodgman): the
// one clipping rule of every face contact, box-box (manifold_box_box.cpp),
// hull-hull (manifold_hull_hull.cpp) and a shape's outline on a triangle
// (manifold_triangle_face.cpp). Each keeps its own vertex type (which
// frame, which feature labels), so the rule works on the vertices' signed
// distances and says how each vertex of the result is made; clip_polygon
// turns that into the caller's vertices.
#include <cstdint>

namespace rwd::sim::d3 {

/// How one vertex of a cut polygon comes from the polygon before the cut.
struct ClipStep {
  enum Kind : uint8_t {
    kKept,      ///< input vertex `from`, as it is
    kLeaving,   ///< where side from -> to leaves the kept half-space
    kEntering,  ///< where side from -> to enters it
  };
  Kind kind;
  uint16_t from;
  uint16_t to;  ///< a crossing's far end (from + 1, wrapping)
  float t;      ///< a crossing lies at from + t (to - from), 0 <= t <= 1
};

/// Keeps the part of a convex polygon where the signed distance is <= 0:
/// dist[i] is vertex i's (positive outside). count >= 3 is a closed polygon;
/// 2 a segment (one side, not closed) and 1 a point, as a shape's outline can
/// be. Writes at most `capacity` steps, in the polygon's order, and returns
/// how many.
int clip_by_plane(const float* dist, int count, ClipStep* steps, int capacity);

/// clip_by_plane applied to vertices: out gets the kept vertices and, for
/// each crossing, cross(from_vertex, to_vertex, t, leaving). At most
/// kCapacity vertices; returns how many.
template <int kCapacity, class Vertex, class Cross>
int clip_polygon(const Vertex* in, const float* dist, int count, Vertex* out, Cross&& cross) {
  ClipStep steps[kCapacity];
  const int n = clip_by_plane(dist, count, steps, kCapacity);
  for (int i = 0; i < n; ++i) {
    const ClipStep& s = steps[i];
    out[i] = s.kind == ClipStep::kKept
                 ? in[s.from]
                 : cross(in[s.from], in[s.to], s.t, s.kind == ClipStep::kLeaving);
  }
  return n;
}

}  // namespace rwd::sim::d3
