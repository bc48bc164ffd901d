// SPDX-License-Identifier: MIT
// Continuous collision for the bodies that opt in (BodyDef::continuous),
// after the solve: speculative contacts already stop a fast body at what its
// contacts foresaw at the start of the tick, but a body can still cross a
// shape the tick's manifolds did not hold apart (a thin wall whose contact
// normal flipped, a shape it reached only through another contact). So each
// continuous body that moved this tick is swept, by its translation, from
// where it started against every shape whose bounds its swept bounds meet (static,
// kinematic and dynamic ones at their poses after the solve), and if it
// would cross one it is moved back to the first time of impact, keeping its
// velocity: the next tick's contact then stops it, and the impulse passes
// to what it struck through the solver, as Box2D v3 does for its bullets.
//
// Bodies that do not opt in cost nothing beyond skipping their flag; a
// world without moving continuous bodies never asks the broadphase for queries.
// Rotation during the tick is not swept (the sweep uses the end rotation).
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/gjk.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "d3/swept_shape.h"

namespace rwd::sim::d3 {
namespace {

// Both layer masks must agree, as for pairs; sensors never stop anything.
bool can_hit(const BodyInfo& mover, const BodyInfo& other) {
  if ((mover.layer & other.mask) == 0 || (other.layer & mover.mask) == 0) return false;
  return other.sensor == 0 && is_simulated(other);
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
    const Vec3 move = scratch.solver_bodies[s].delta_position;
    const float distance_sq = length_squared(move);
    if (distance_sq <= slop * slop) continue;  // the contacts hold what moves this little
    const Vec3 start = sim.position - move;
    const Mat3 axes = mat3_from_quat(sim.rotation);
    const Aabb from = shape_aabb(info.shape, start, axes);

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
    for (const uint32_t j : candidates) {
      const BodyInfo& other_info = state.infos[j];
      const BodySim& other_sim = state.sims[j];
      const ShapeCastOutput hit =
          sweep_against(other_info.shape, *scratch.store, other_sim.position,
                        mat3_from_quat(other_sim.rotation), mover, move, first);
      // Shapes touching at the start are a contact's business, and so is
      // motion along or away from the surface: only a crossing counts.
      if (!hit.hit || hit.initially_overlapping || hit.fraction >= first) continue;
      const float closing = -dot(move, hit.normal) * (1.0f - hit.fraction);
      if (closing <= slop) continue;
      first = hit.fraction;
    }
    if (first >= 1.0f) continue;
    // Back to the impact, and half a slop short of it along the path, so the
    // next tick starts with a speculative contact rather than an overlap.
    const float length_m = std::sqrt(distance_sq);
    const float back = std::max(0.0f, first - 0.5f * slop / length_m);
    sim.position = start + move * back;
    sim.sleep_time = 0.0f;
    // Query trees built before the move no longer hold this body.
    scratch.broadphase.forget_poses();
  }
}

}  // namespace rwd::sim::d3
