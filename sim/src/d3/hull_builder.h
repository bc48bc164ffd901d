// SPDX-License-Identifier: MIT
#pragma once
// Building a Hull (hull.h) from the points a game gives at registration.
// Pure functions of the input bits: the same points give the same hull,
// bit for bit, on every compiler and architecture.
//
// Corners are decided with exact integer predicates on a fine grid, then
// with a tolerance: a point is a corner only if it lies farther than
// max(1e-5 * size, 5e-7 * largest coordinate, 4e-6 m) from the hull of the
// other points (size: the largest side of the points' bounding box), and
// neighbouring triangles whose corners lie within half that of one plane
// merge into one polygon face. A hull thinner than the tolerance across
// any face has no volume. Where faces that close to coplanar meet at a
// very shallow angle (a cone a thousand times wider than high), merging
// them could leave a corner on only two faces; such a hull merges exactly
// coplanar triangles only.
#include <span>

#include "d3/hull.h"
#include "rewind/core/status.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// Most points hull_from_points() takes.
inline constexpr uint32_t kHullMaxCloudPoints = 4096;

/// Strict: every given point must be a vertex of the convex hull (4..64
/// points); hull vertex i is points[i] in the mass frame. Refused with
/// kInvalidArgument and a message naming the point where there is one:
/// fewer than 4 or more than 64 points; a non-finite coordinate; a
/// coordinate of magnitude > 1000 m; two points closer than 1e-4 m; all
/// points on a line or a plane (or within the tolerance of one), or a hull
/// of less than 1e-9 m^3; a point that is not a corner (inside the hull,
/// or on or within the tolerance of one of its faces or edges).
Result<Hull> make_hull(std::span<const Vec3> points);

/// The convex hull of any point cloud (4..4096 points): points inside it,
/// on its faces or edges, or within the tolerance of them are dropped, and
/// so is every point closer than 1e-4 m to an earlier one. A hull of more
/// than 64 corners is reduced to 64 of the cloud's points, added farthest
/// first, so some points of such a cloud end up outside it. Vertices keep
/// the order of the points they come from. Refused with kInvalidArgument
/// for a bad count, a non-finite or out-of-range coordinate, or a cloud
/// without volume (as make_hull()).
Result<Hull> hull_from_points(std::span<const Vec3> points);

}  // namespace rwd::sim::d3
