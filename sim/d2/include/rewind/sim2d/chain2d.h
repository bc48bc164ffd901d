// SPDX-License-Identifier: MIT
#pragma once
// Edge chains: a polyline or a closed loop of one-sided chain segments
// (ShapeType2D::kChainSegment) whose ghost vertices remove the ghost
// collisions at the joints, so a box sliding over a floor made of many
// edges never catches on the points between them. Each edge is its own
// shape; the caller puts each on a static (or kinematic) body, all with the
// same transform.
#include <span>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/shape2d.h"

namespace rwd::sim2d {

/// One chain segment per edge of the polyline `points` (loop = false: edges
/// points[i] -> points[i + 1]) or of the closed outline (loop = true: also
/// the edge from the last point back to the first). Bodies collide on the
/// right of each edge's direction (see make_chain_segment): a clockwise
/// loop keeps bodies inside, a counter-clockwise loop keeps them out, and a
/// floor open upwards runs right to left.
///
/// Ghosts: each edge's ghosts are its neighbours' far points. The two ends
/// of an open chain have no neighbour; their ghosts are placed as if a wall
/// dropped straight down behind the end (the end point moved along the
/// reverse of the edge's normal by the edge's length, halved until it fits
/// the Fx range), so an open end is a square, convex corner: a body sliding
/// off it tips over the corner like a ledge, and nothing collides with the
/// end from behind or below. For other ends, build the edges with
/// make_chain_segment and ghosts of your choice.
///
/// Refused (kInvalidArgument, naming the point index): fewer than 2 points
/// (3 for a loop), two consecutive points equal (for a loop, also the last
/// and the first), or an edge longer than the Fx range.
Result<std::vector<Shape2D>> make_chain(std::span<const Vec2> points, bool loop);

}  // namespace rwd::sim2d
