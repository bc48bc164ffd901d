// SPDX-License-Identifier: MIT
#pragma once
// Exact distance between two rounded convex shapes, the core of the 2D
// lane's overlap, shape-cast, nearest-body and signed-distance queries.
// Shapes are taken as cores (a point, a segment or a convex polygon, in
// one shared frame) swept by a radius, so circles, capsules, segments and
// rounded polygons are one case.
#include "manifold2_internal.h"
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// The core of `shape` placed by `xf`: a circle is a one-vertex core, a
/// capsule or segment a two-vertex one (normals facing both ways), a
/// polygon its vertices and edge normals. Radius as the shape's.
WPoly shape_core(const Shape2D& shape, const Xf& xf);

/// A bare point as a core.
WPoly point_core(V2 point);

/// `poly` moved by `offset` (normals unchanged).
WPoly translate_core(const WPoly& poly, V2 offset);

struct Distance2 {
  /// Signed distance between the rounded surfaces (m), negative when they
  /// overlap (then minus the depth along `normal`).
  W distance = 0;
  /// Unit, pointing from A toward B (the direction that separates them).
  V2 normal{0, kWOne};
  /// The nearest points of A's and B's surfaces. When the shapes overlap
  /// they are the deepest point of one core and its projection onto the
  /// other's separating face, each moved out by its radius.
  V2 point_a;
  V2 point_b;
};

/// The distance from A to B. Separated cores: the exact minimum over
/// vertex-edge pairs (each 128-bit exact up to one rounding of the
/// projection), so it is the true distance to within a few 2^-32 m.
/// Overlapping cores: the separating-axis depth over both cores' edge
/// normals (the least translation that parts them). Cost: O(na x nb).
Distance2 shape_distance(const WPoly& a, const WPoly& b);

/// The point of segment a..b nearest p (a when a == b).
V2 closest_on_segment(V2 p, V2 a, V2 b);

}  // namespace rwd::sim2d::detail
