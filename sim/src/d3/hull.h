// SPDX-License-Identifier: MIT
#pragma once
// A convex hull as the engine keeps it: immutable geometry, built once when
// the game registers it (hull_builder.h) and shared by every body that uses
// it through the geometry store. Vertices, face planes and edges are in the
// hull's mass frame: the origin is the centre of mass and the axes are the
// principal axes of inertia, so a hull body's inertia is diagonal and the
// solver treats it like any other body. `frame` says where that mass frame
// sits in the frame the game authored the points in.
#include <cstdint>
#include <vector>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// Limits of a hull: 4..64 vertices. With at most 64 vertices a hull has at
/// most 124 faces and 186 edges, so every index fits in a byte.
inline constexpr uint32_t kHullMinVertices = 4;
inline constexpr uint32_t kHullMaxVertices = 64;

/// One face: a convex polygon on the plane dot(normal, x) = offset.
struct HullFace {
  Vec3 normal;          ///< unit, outward
  float offset = 0.0f;  ///< metres, plane distance from the mass-frame origin
  uint16_t first = 0;   ///< first index of the face's loop in Hull::face_vertices
  uint8_t count = 0;    ///< number of vertices in the loop (>= 3)
};

/// One edge, listed once. Seen from outside, face_left lies to the left of
/// the edge when walking from v0 to v1 (its loop runs v0 -> v1) and
/// face_right to the right (its loop runs v1 -> v0).
struct HullEdge {
  uint8_t v0 = 0;
  uint8_t v1 = 0;
  uint8_t face_left = 0;
  uint8_t face_right = 0;
};

/// Where the hull's mass frame sits in the authored frame: a point x in the
/// mass frame is at rotate(rotation, x) + center in the authored frame.
struct HullFrame {
  Vec3 center;    ///< metres, centre of mass in the authored frame
  Quat rotation;  ///< principal axes in the authored frame (unit)
};

struct Hull {
  std::vector<Vec3> vertices;  ///< metres, mass frame; 4..64, all extreme
  std::vector<HullFace> faces;
  /// Each face's vertex loop, counter-clockwise seen from outside (right
  /// hand about the outward normal); coplanar triangles are merged, so a
  /// box has six quads.
  std::vector<uint8_t> face_vertices;
  std::vector<HullEdge> edges;
  HullFrame frame;
  float volume = 0.0f;  ///< m^3
  /// Principal moments of inertia per kilogram of mass (m^2): the inertia
  /// of a body of mass m is m * unit_inertia, in the mass frame.
  Vec3 unit_inertia;
  float extent = 0.0f;  ///< metres, largest vertex distance from the origin
  Vec3 half_size;       ///< metres, half size of the mass-frame bounds about the origin
};

/// The vertex of `hull` farthest along `dir` (mass frame); ties go to the
/// lower index.
inline uint32_t hull_support_index(const Hull& hull, Vec3 dir) {
  uint32_t best = 0;
  float best_d = dot(hull.vertices[0], dir);
  for (uint32_t i = 1; i < hull.vertices.size(); ++i) {
    const float d = dot(hull.vertices[i], dir);
    if (d > best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

}  // namespace rwd::sim::d3
