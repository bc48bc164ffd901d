// SPDX-License-Identifier: MIT
#pragma once
// Exact linear casts for the pairs that have a closed form: a sphere or a
// box swept against a sphere or a box. A sphere's centre runs along a ray
// against the target grown by its radius (a sphere, or a box with rounded
// edges and corners: its slabs, then the cylinder of the edge or the ball
// of the corner the ray enters beside); a box against a box is the
// separating-axis test along the sweep (each of the 15 axes gives the
// interval of fractions over which the projections overlap; the shapes
// first touch at the latest entry, if it comes before the earliest exit).
//
// The answer is the true first touch, not conservative advancement's
// (gjk.h): no GJK iterations, and no hit for a sweep that passes within
// the advancement's target gap without touching. Shape queries use it;
// continuous collision keeps conservative advancement, whose stop short
// of the touch it relies on.
#include "d3/gjk.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim::d3 {

/// The first touch of `swept_shape` (canonical; `swept` is its proxy,
/// posed in the world) moved by fraction * translation, fraction in [0,
/// max_fraction], against `target` with its mass frame at `position`,
/// `axes`: ShapeCastOutput's conventions (point on the target's surface,
/// normal from the target to the swept shape). Returns false, leaving
/// `out` untouched, when the pair has no exact cast or the two already
/// touch at fraction 0 (the caller sweeps by GJK then, which also finds
/// the penetration's normal); true with out.hit false for a miss.
bool cast_exact(const Shape& target, Vec3 position, const Mat3& axes, const Shape& swept_shape,
                const ConvexProxy& swept, Vec3 translation, float max_fraction,
                ShapeCastOutput& out);

}  // namespace rwd::sim::d3
