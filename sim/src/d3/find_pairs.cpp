// SPDX-License-Identifier: MIT
// The step's first stage: the awake bodies' bounds for this tick, handed to
// the broadphase (broadphase.h), which returns the candidate pairs sorted.
#include <algorithm>

#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

uint64_t pair_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t{a} << 32 | b) : (uint64_t{b} << 32 | a);
}

// The pairs intact joints keep apart, sorted, found again only after the
// joints changed.
void update_joint_pairs(const WorldState& state, WorldScratch& scratch) {
  if (scratch.joint_pairs_serial == scratch.joint_serial) return;
  scratch.joint_pairs_serial = scratch.joint_serial;
  std::vector<uint64_t>& keys = scratch.joint_pairs;
  keys.clear();
  for (const JointRecord& j : state.joints) {
    if (j.alive == 0 || j.index_a == kJointWorld) continue;
    if ((j.flags & kJointDisableCollision) == 0 || (j.flags & kJointBroken) != 0) continue;
    keys.push_back(pair_key(j.index_a, j.index_b));
  }
  std::sort(keys.begin(), keys.end());
}

// Drops the candidate pairs a joint keeps apart (both lists sorted).
void drop_joint_pairs(WorldScratch& scratch) {
  const std::vector<uint64_t>& keys = scratch.joint_pairs;
  if (keys.empty()) return;
  std::vector<BodyPair>& pairs = scratch.pairs;
  size_t kept = 0;
  size_t k = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const uint64_t key = pair_key(pairs[i].a, pairs[i].b);
    while (k < keys.size() && keys[k] < key) ++k;
    if (k < keys.size() && keys[k] == key) continue;
    pairs[kept++] = pairs[i];
  }
  pairs.resize(kept);
}

}  // namespace

void find_pairs(const WorldState& state, WorldScratch& scratch) {
  // The step's body frames start here.
  begin_body_axes(state, scratch);
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.aabbs.resize(n);
  scratch.active.clear();
  scratch.woke_bodies = false;
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
  if (state.live_joints != 0) {
    update_joint_pairs(state, scratch);
    drop_joint_pairs(scratch);
  }
  scratch.stats.broadphase_pairs = static_cast<uint32_t>(scratch.pairs.size());
}

}  // namespace rwd::sim::d3
