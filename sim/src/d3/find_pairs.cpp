// SPDX-License-Identifier: MIT
// The step's first stage: the awake bodies' bounds for this tick, handed to
// the broadphase (broadphase.h), which returns the candidate pairs sorted.
#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {

void find_pairs(const WorldState& state, WorldScratch& scratch) {
  // The step's body frames start here.
  begin_body_axes(state, scratch);
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.aabbs.resize(n);
  scratch.active.clear();
  const float tick = state.config.tick_seconds;
  const float speculative = state.config.speculative_distance_m;
  for (uint32_t i = 0; i < n; ++i) {
    const BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    const BodySim& sim = state.sims[i];
    // Fattened by the speculative distance plus how far the body can move
    // this tick, so a fast body meets what it will hit in time for a
    // speculative contact to stop it.
    const float reach =
        length(sim.linear_velocity) + length(sim.angular_velocity) * state.masses[i].extent;
    const float margin = speculative + tick * reach;
    Aabb box = shape_aabb(info.shape, sim.position, set_body_axes(scratch, i, sim.rotation));
    box.lower -= Vec3{margin, margin, margin};
    box.upper += Vec3{margin, margin, margin};
    scratch.aabbs[i] = box;
    scratch.active.push_back(i);
  }
  scratch.broadphase.update(state, scratch.active, scratch.aabbs);
  scratch.broadphase.find_pairs(state, scratch.aabbs, scratch.pairs);
  scratch.stats.broadphase_pairs = static_cast<uint32_t>(scratch.pairs.size());
}

}  // namespace rwd::sim::d3
