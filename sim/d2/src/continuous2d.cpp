// SPDX-License-Identifier: MIT
// Continuous collision for bodies that ask for it: conservative advancement
// of the body's shape along the step's translation (at its end rotation)
// against the static and kinematic shapes whose bounds the sweep crosses.
// The distance comes from the manifold routines with an unbounded
// speculative distance: for polygons that is the largest separation along
// a face normal, never more than the true distance, so advancing by it
// never steps through a surface.
#include "body_math2d.h"
#include "manifold2.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

constexpr int kMaxAdvances = 24;

// Separation and normal (from the obstacle to the mover) of the two shapes.
struct Gap2D {
  W separation = 0;
  V2 normal;
  bool found = false;
};

Gap2D gap(const BodyRecord2D& mover, const Xf& mover_xf, const BodyRecord2D& obstacle,
          const Xf& obstacle_xf) {
  Manifold2 m;
  collide(obstacle.shape, obstacle_xf, mover.shape, mover_xf, w_int(1 << 20), m);
  if (m.count == 0) return {};
  W s = m.points[0].separation;
  if (m.count > 1) s = wmin(s, m.points[1].separation);
  return {s, m.normal, true};
}

// The first fraction of `translation` at which the mover comes within
// `target` of the obstacle, or kWOne when it does not.
W time_of_impact(const BodyRecord2D& mover, const Xf& start, V2 translation,
                 const BodyRecord2D& obstacle, W target) {
  const Xf obstacle_xf = origin_transform(obstacle);
  W t = 0;
  for (int i = 0; i < kMaxAdvances; ++i) {
    const Xf at{start.p + vscale(t, translation), start.q};
    const Gap2D g = gap(mover, at, obstacle, obstacle_xf);
    if (!g.found) return kWOne;
    // Closing speed along the normal, per unit of the fraction. A mover
    // leaving the surface (a bounce, a jump off the ground) never comes
    // closer, however near it starts.
    const W closing = -vdot(translation, g.normal);
    if (closing <= 0) return kWOne;
    if (g.separation <= target) return t;
    t += wdiv(g.separation - target / 2, closing);
    if (t >= kWOne) return kWOne;
  }
  return t;
}

// A chain segment collides on one side only (its normal's): a body that
// starts behind it passes through, in the sweep as in the contacts.
bool behind_chain_segment(const BodyRecord2D& obstacle, V2 point) {
  if (obstacle.shape.type != ShapeType2D::kChainSegment) return false;
  const Xf xf = origin_transform(obstacle);
  const V2 p1 = transform_point(xf, v_from(obstacle.shape.vertices[0]));
  const V2 p2 = transform_point(xf, v_from(obstacle.shape.vertices[1]));
  const V2 normal = vperp_cw(p2 - p1);
  return vdot(point - p1, normal) < 0;
}

}  // namespace

void solve_continuous(World2DState& state, const StepScratch2D& scratch) {
  const W speculative = w_from(state.config.speculative_distance);
  const W target = w_from(state.config.linear_slop);
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyContinuous) || !is_moving(body)) continue;
    const V2 translation = scratch.bodies[i].dp;
    if (vlength_sq(translation) <= wmul(speculative, speculative)) continue;
    // Swept bounds: the shape at the start and at the end of the step.
    const Xf end = origin_transform(body);
    const Xf start{end.p - translation, end.q};
    const Box2W a = shape_bounds(body.shape, start);
    const Box2W b = shape_bounds(body.shape, end);
    const Box2W swept{vmin(a.lower, b.lower), vmax(a.upper, b.upper)};
    W first = kWOne;
    for (uint32_t j = 0; j < state.bodies.size(); ++j) {
      const BodyRecord2D& other = state.bodies[j];
      if (j == i || other.kind == BodyKind2D::kDynamic || !(other.flags & kBodyLive) ||
          !(other.flags & kBodyEnabled) || (other.flags & kBodySensor)) {
        continue;
      }
      if ((body.layer & other.mask) == 0 || (other.layer & body.mask) == 0) continue;
      if (!overlaps(swept, shape_bounds(other.shape, origin_transform(other)))) continue;
      if (behind_chain_segment(other, start.p + rotate(start.q, body.local_center))) continue;
      first = wmin(first, time_of_impact(body, start, translation, other, target));
    }
    if (first < kWOne) body.center = body.center - translation + vscale(first, translation);
  }
}

}  // namespace rwd::sim2d::detail
