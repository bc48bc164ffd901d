// SPDX-License-Identifier: MIT
// Continuous collision for the bodies that opt in (BodyDef::continuous),
// after the solve: speculative contacts already stop a fast body at what its
// contacts foresaw at the start of the tick, but a body can still cross a
// shape the tick's manifolds did not hold apart (a thin wall whose contact
// normal flipped, a shape it reached only through another contact). So each
// continuous body that moved this tick is swept from where it started
// against every shape whose bounds its swept bounds meet (static, kinematic
// and dynamic ones at their poses after the solve), and if it would cross
// one it is moved back to the first time of impact, keeping its velocity:
// the next tick's contact then stops it, and the impulse passes to what it
// struck through the solver, as Box2D v3 does for its bullets.
//
// A body that barely turned is swept by its translation at its end
// rotation. A body that turned far for its thickness (a spinning plank,
// whose ends travel much further than its centre) is advanced
// conservatively instead: its pose at fraction t of the tick is the start
// pose moved by t of the translation and turned by t of the rotation, and t
// grows by the distance to the target over a bound on how fast any point of
// the body moves (translation plus the turn times its extent), so it can
// never step through; it stops once within a slop (or within half the gap
// it started with, when that is less: a plank pivoting on a pole it struck
// last tick). Its angular velocity turns back with it, the same in its own
// frame. The turn is the one the tick made after the solver's gyroscopic
// carry (contact_solver.cpp: finalize), so the sweep starts where the body
// did. Against meshes and height fields (no convex proxy) such a body is
// swept by translation, as the others.
//
// Bodies that do not opt in cost nothing beyond skipping their flag; a
// world without moving continuous bodies never asks the broadphase for queries.
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/gjk.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "d3/swept_shape.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

// Both layer masks must agree, as for pairs; sensors never stop anything.
bool can_hit(const BodyInfo& mover, const BodyInfo& other) {
  if ((mover.layer & other.mask) == 0 || (other.layer & mover.mask) == 0) return false;
  return other.sensor == 0 && is_simulated(other);
}

// The motion of a body over the tick: start pose, translation, and the
// turn (unit axis, angle) that takes the start rotation to the end one.
struct Motion {
  Vec3 start;
  Vec3 move;
  Quat start_rotation;
  Vec3 axis;
  float angle = 0.0f;
};

Motion motion_of(const BodySim& sim, const SolverBody& body) {
  Motion m;
  m.move = body.delta_position;
  m.start = sim.position - m.move;
  Quat turn = body.delta_rotation;
  if (turn.w < 0.0f) turn = {-turn.x, -turn.y, -turn.z, -turn.w};  // the short way
  m.start_rotation = normalize(conjugate(turn) * sim.rotation);
  const float sin_half = length(Vec3{turn.x, turn.y, turn.z});
  if (sin_half > 0.0f) {
    m.axis = Vec3{turn.x, turn.y, turn.z} * (1.0f / sin_half);
    m.angle = 2.0f * det_atan2(sin_half, turn.w);
  }
  return m;
}

Quat rotation_at(const Motion& m, float t) {
  const float half = 0.5f * t * m.angle;
  const float s = det_sin(half);
  return normalize(Quat{m.axis.x * s, m.axis.y * s, m.axis.z * s, det_cos(half)} *
                   m.start_rotation);
}

// Metres between the surfaces of two swept shapes (negative: they overlap).
float separation(const SweptShape& a, const SweptShape& b) {
  float nearest = 3.4e38f;
  for (uint32_t i = 0; i < a.count; ++i) {
    for (uint32_t j = 0; j < b.count; ++j) {
      const GjkOutput g = gjk_distance(a.parts[i], b.parts[j]);
      const float d = g.overlap ? -1.0f : g.distance - a.parts[i].radius - b.parts[j].radius;
      nearest = std::min(nearest, d);
    }
  }
  return nearest;
}

// The first fraction of the tick, below `first`, at which the moving body
// comes within a target distance of `target`, by conservative advancement;
// `first` when it does not, or when it starts overlapping (the contacts'
// business). The target is a slop, or half the gap for a body that starts
// within a slop: a spinning body already beside a shape (a plank that
// struck a pole last tick and is pivoting on it) is held off it too, since
// the contact, anchored where it touched at the start of the tick, does not
// follow a turn of a fifth of a radian along the face.
float advance_to_impact(const Shape& shape, const GeometryStore& store, const Motion& m,
                        float extent, const SweptShape& target, float slop, float first,
                        SweptShape& mover) {
  // No point of the body moves faster than this over the tick.
  const float bound = length(m.move) + m.angle * extent;
  float t = 0.0f;
  float goal = slop;
  for (int iteration = 0; iteration < 32; ++iteration) {
    make_swept_shape(shape, store, m.start + m.move * t, mat3_from_quat(rotation_at(m, t)), mover);
    const float d = separation(mover, target);
    if (iteration == 0) {
      if (d <= 0.0f) return first;
      goal = std::min(slop, 0.5f * d);
    }
    // Within half the goal again of it: stop (never short of the goal).
    if (d <= 1.5f * goal) return t;
    t += (d - goal) / bound;
    if (t >= first) return first;
  }
  return t;  // still closing in after every iteration: stop here, short of it
}

}  // namespace

void continuous_collision(WorldState& state, WorldScratch& scratch) {
  const WorldConfig& config = state.config;
  const float slop = config.linear_slop_m;
  for (size_t s = 1; s < scratch.solver_bodies.size(); ++s) {
    const uint32_t i = scratch.solver_body_ids[s];
    const BodyInfo& info = state.infos[i];
    // Dynamic bodies are never meshes or height fields, so every one that
    // opts in can be swept (a compound by each of its children).
    if (info.continuous == 0 || info.kind != BodyKind::kDynamic || info.enabled == 0 ||
        info.sensor != 0 || !can_sweep(info.shape)) {
      continue;
    }
    BodySim& sim = state.sims[i];
    const Motion motion = motion_of(sim, scratch.solver_bodies[s]);
    const Vec3 move = motion.move;
    const float distance_sq = length_squared(move);
    const float extent = state.masses[i].extent;
    // Turned further than half its thinnest half-width at its extent: the
    // end rotation does not stand for the tick.
    const Aabb local = shape_aabb(info.shape, Vec3{}, Mat3{});
    const float thinnest =
        0.5f * std::min({local.upper.x - local.lower.x, local.upper.y - local.lower.y,
                         local.upper.z - local.lower.z});
    const bool spinning = motion.angle * extent > std::max(slop, 0.5f * thinnest);
    // The contacts hold what moves this little.
    if (distance_sq <= slop * slop && !spinning) continue;
    const Vec3 start = motion.start;
    const Mat3 axes = mat3_from_quat(sim.rotation);
    Aabb from = shape_aabb(info.shape, start, axes);
    if (spinning) {
      // Every pose of the tick lies within the extent of the centre's path.
      from = {start - Vec3{extent, extent, extent}, start + Vec3{extent, extent, extent}};
    }

    prepare_queries(state, scratch);
    std::vector<uint32_t>& candidates = scratch.query_hits;
    candidates.clear();
    const auto collect = [&](uint32_t j) {
      if (j != i && can_hit(info, state.infos[j])) candidates.push_back(j);
    };
    scratch.broadphase.sweep_query(from, move, collect);
    std::sort(candidates.begin(), candidates.end());

    SweptShape& mover = scratch.swept;
    make_swept_shape(info.shape, *scratch.store, start, axes, mover);
    float first = 1.0f;
    bool turned_back = false;
    for (const uint32_t j : candidates) {
      const BodyInfo& other_info = state.infos[j];
      const BodySim& other_sim = state.sims[j];
      if (spinning && can_sweep(other_info.shape)) {
        make_swept_shape(other_info.shape, *scratch.store, other_sim.position,
                         mat3_from_quat(other_sim.rotation), scratch.swept_target);
        const float t = advance_to_impact(info.shape, *scratch.store, motion, extent,
                                          scratch.swept_target, slop, first, scratch.swept);
        if (t < first) {
          first = t;
          turned_back = true;
        }
        continue;
      }
      // (Advancement reposes the mover: pose it back at the end rotation.)
      if (spinning) make_swept_shape(info.shape, *scratch.store, start, axes, mover);
      const ShapeCastOutput hit =
          sweep_against(other_info.shape, *scratch.store, other_sim.position,
                        mat3_from_quat(other_sim.rotation), mover, move, first);
      // Shapes touching at the start are a contact's business, and so is
      // motion along or away from the surface: only a crossing counts.
      if (!hit.hit || hit.initially_overlapping || hit.fraction >= first) continue;
      const float closing = -dot(move, hit.normal) * (1.0f - hit.fraction);
      if (closing <= slop) continue;
      first = hit.fraction;
      turned_back = false;
    }
    if (first >= 1.0f) continue;
    if (turned_back) {
      // Advancement stopped short of the impact: the pose there, with the
      // angular velocity turned back with the body (the same in the body's
      // frame), so a body whose inertia differs by axis keeps its energy.
      const Quat back = normalize(rotation_at(motion, first) * conjugate(sim.rotation));
      sim.position = start + move * first;
      sim.rotation = rotation_at(motion, first);
      sim.angular_velocity = rotate(back, sim.angular_velocity);
    } else {
      // Back to the impact, and half a slop short of it along the path, so
      // the next tick starts with a speculative contact, not an overlap.
      const float length_m = std::sqrt(distance_sq);
      const float back = std::max(0.0f, first - 0.5f * slop / length_m);
      sim.position = start + move * back;
    }
    sim.sleep_time = 0.0f;
    // Query trees built before the move no longer hold this body.
    scratch.broadphase.forget_poses();
  }
}

}  // namespace rwd::sim::d3
