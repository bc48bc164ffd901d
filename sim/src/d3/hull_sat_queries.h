// SPDX-License-Identifier: MIT
#pragma once
// The separating-axis queries of a hull pair (hull_sat_queries.cpp), the
// first half of collide_hulls (manifold_hull_hull.cpp, which builds the
// contact from their answer): the best face of each hull, and the best
// edge pair, each as a separation along its axis.
#include <cstdint>
#include <limits>

#include "d3/manifold_hull_sat.h"

namespace rwd::sim::d3 {

// Euler's formula bounds a hull of V vertices to 2V - 4 faces and 3V - 6
// edges; the per-call scratch is sized by these.
inline constexpr uint32_t kMaxFaces = 2 * kHullMaxVertices - 4;
inline constexpr uint32_t kMaxEdges = 3 * kHullMaxVertices - 6;

inline constexpr float kLowestSeparation = -std::numeric_limits<float>::max();

struct FaceQuery {
  float separation = kLowestSeparation;
  uint32_t face = 0;
};

struct EdgeQuery {
  float separation = kLowestSeparation;
  uint32_t edge_a = 0;
  uint32_t edge_b = 0;
  Vec3 axis;  // unit, A's frame, from A to B
};

/// How far `other`'s vertices (other_count >= 1, in hull's frame) lie
/// outside face f of `hull`: the least height over the face's plane.
inline float face_separation(const HullView& hull, uint32_t f, const Vec3* other,
                             uint32_t other_count) {
  const Vec3 n = hull.faces[f].normal;
  float deepest = dot(n, other[0]);
  for (uint32_t v = 1; v < other_count; ++v) {
    const float d = dot(n, other[v]);
    if (d < deepest) deepest = d;
  }
  return deepest - hull.faces[f].offset;
}

/// The faces of `hull` against `other`'s vertices (other_count of them) in
/// hull's frame: the largest separation and its face (ties to the lower
/// index). Stops at a face that separates by more than speculative_m.
FaceQuery query_faces(const HullView& hull, const Vec3* other, uint32_t other_count,
                      float speculative_m);

/// The best edge pair of A and B that separates by more than `floor`
/// (hull_sat_queries.cpp): B's vertices and face normals in A's frame, B's
/// origin at b_origin. Ties to the lower (edge_a, edge_b); stops at a pair
/// that separates by more than speculative_m; separation `floor` when no
/// pair beats it.
EdgeQuery query_edges(const HullView& a, const HullView& b, const Vec3* b_vertices,
                      const Vec3* b_normals, Vec3 b_origin, float floor, float speculative_m);

}  // namespace rwd::sim::d3
