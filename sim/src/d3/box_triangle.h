// SPDX-License-Identifier: MIT
#pragma once
// A box against one triangle by separating axes: what GJK and EPA find by
// iterating (whether they overlap, how far apart or how deep, which way, and
// a witness point on each), from the thirteen axes that can separate a box
// from a triangle: the triangle's normal, the box's three face normals and
// the nine crossings of a box edge with a triangle edge. A box on a mesh
// or a height field meets a handful of triangles each step, and this costs
// a few dozen dot products where GJK and EPA cost iterations; it is exact
// for overlap (the least depth over the axes is the least depth of the
// pair, as EPA's is) and, apart, gives the largest gap along an axis,
// which is the true distance whenever the closest features are a face and
// anything, or two edges that cross (and never more than it otherwise).
//
// Face axes are preferred over edge axes, and the triangle's normal over
// the box's faces, unless the other gains more than kBoxTriangleAxisSlack:
// a box resting flat on a triangle (its face and the triangle's normal a
// hair apart) is met through the triangle's face, its lowest face clipped
// against it, the same way every step.
#include "d3/triangle.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// An oriented box: centre, unit axes (the columns of its rotation) and
/// half extents along them, all in the triangles' frame.
struct BoxFrame {
  Vec3 center;
  Vec3 axes[3];
  Vec3 half;
};

/// How far (metres) an axis must beat the preferred one to be taken.
inline constexpr float kBoxTriangleAxisSlack = 1e-4f;

struct BoxTriangleFeatures {
  bool overlap = false;     ///< the box and the triangle touch or overlap
  float separation = 0.0f;  ///< the gap along normal (> 0), or minus the depth
  Vec3 normal;              ///< unit, from the triangle toward the box
  Vec3 on_triangle;         ///< witness on the triangle (its plane, for the normal's axis)
  Vec3 on_box;              ///< witness on the box, at least the gap from on_triangle
};

/// The box against the triangle p[0..3) with unit normal tri.normal. An
/// axis with a gap beyond `reach` (metres) ends the search: the result is
/// then apart with that gap and normal, and no witness points.
BoxTriangleFeatures box_triangle_features(const BoxFrame& box, const TriangleRef& tri, float reach);

}  // namespace rwd::sim::d3
