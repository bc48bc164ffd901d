// SPDX-License-Identifier: MIT
// Shape casts by conservative advancement. Under a pure translation the
// distance between two convex shapes is a convex function of the
// fraction t, so the tangent line at any t lies under it: stepping to where
// the tangent reaches the target (Newton's method) never passes the first
// contact, and converges from below. The slope is -(translation . normal),
// normal the unit direction from the moving shape to the body at the
// current t; when it is not negative the distance can only grow.
#include "shape_cast2d.h"

#include "body_math2d.h"
#include "query_cache2d.h"
#include "query_filter2d.h"
#include "rewind/sim2d/world2d.h"
#include "shape_bounds2d.h"

namespace rwd::sim2d::detail {

namespace {

// Enough for a head-on hit in a handful; a graze (tangent contact) halves
// its gap per iteration, and 2^-48 of a cast is below the tolerance.
constexpr int kMaxIterations = 48;

Box2W core_bounds(const WPoly& core) {
  Box2W box{core.vertices[0], core.vertices[0]};
  for (int i = 1; i < core.count; ++i) {
    box.lower = vmin(box.lower, core.vertices[i]);
    box.upper = vmax(box.upper, core.vertices[i]);
  }
  const V2 r{core.radius, core.radius};
  return {box.lower - r, box.upper + r};
}

bool cast_one(const WPoly& core, const WPoly& body, V2 translation, W min_approach, W target,
              W max_fraction, CastResult2& out) {
  Distance2 d = shape_distance(core, body);
  W t = 0;
  if (d.distance <= target + kCastTolerance) {
    if (vdot(translation, d.normal) <= min_approach) return false;
  } else {
    int i = 0;
    for (; i < kMaxIterations; ++i) {
      const W approach = vdot(translation, d.normal);
      if (approach <= 0) return false;
      // Past max_fraction even at this slope: no hit. Checked as a product
      // first, so the quotient below is at most 1 and cannot overflow.
      const W gap = d.distance - target;
      if (gap > wmul(approach, max_fraction - t)) return false;
      // Truncated toward zero: the step errs short, never past the contact.
      t += wdiv(gap, approach);
      const V2 shift{wmul(t, translation.x), wmul(t, translation.y)};
      d = shape_distance(translate_core(core, shift), body);
      if (d.distance <= target + kCastTolerance) break;
    }
    if (i == kMaxIterations) return false;
  }
  out.fraction = t;
  out.point = d.point_b;
  out.normal = -d.normal;
  return true;
}

}  // namespace

bool cast_core(const World2D& world, const QueryFilter2D& filter, const WPoly& core, V2 translation,
               W target, CastResult2& out) {
  const World2DState& state = world.state();
  const Box2W start = core_bounds(core);
  const V2 grow{target, target};
  const Box2W swept{vmin(start.lower, start.lower + translation) - grow,
                    vmax(start.upper, start.upper + translation) + grow};
  // Heading into a body already within reach must beat ~0.2 degrees, so a
  // slide along a surface (its normal a few ulps off) is not a hit.
  const W min_approach = vlength(translation) >> 8;
  bool found = false;
  W best = kWOne;
  world.query_cache().query(swept, [&](const World2D::QueryCache::Item& item, const Box2W& cull) {
    const BodyRecord2D& b = state.bodies[item.index];
    if (!passes_filter(b, item.index, filter)) return cull;
    CastResult2 hit;
    if (!cast_one(core, shape_core(b.shape, origin_transform(b)), translation, min_approach, target,
                  best, hit)) {
      return cull;
    }
    // Equal fractions go to the lower index, whatever order the tree uses.
    if (found && (hit.fraction > best || (hit.fraction == best && item.index > out.index))) {
      return cull;
    }
    found = true;
    best = hit.fraction;
    hit.index = item.index;
    out = hit;
    return cull;
  });
  return found;
}

}  // namespace rwd::sim2d::detail
