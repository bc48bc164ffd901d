// SPDX-License-Identifier: MIT
// Broadphase: sort-and-sweep on x over two lists. The active list (awake,
// movable bodies) is rebuilt and sorted every step from fat bounds; the
// passive list (static and sleeping bodies) is sorted only when it changes,
// so resting geometry costs one comparison per body per step. Pairs are
// active-active or active-passive; static-static and sleeping-sleeping pairs
// are never visited. A dynamic AABB tree was rejected for the first cut:
// sweep-and-prune is simpler to make exactly reproducible and is fast for
// game-sized scenes; the output (sorted pairs) does not depend on the method.
#include <algorithm>

#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

bool entry_less(const SweepEntry& l, const SweepEntry& r) {
  return l.min_x < r.min_x || (l.min_x == r.min_x && l.body < r.body);
}

bool overlap_yz(const Aabb& a, const Aabb& b) {
  return a.lower.y <= b.upper.y && b.lower.y <= a.upper.y && a.lower.z <= b.upper.z &&
         b.lower.z <= a.upper.z;
}

// Filtering: both layer masks must agree; something must be able to respond
// (a dynamic body) or to report (a sensor); two static bodies never pair.
bool should_pair(const BodyInfo& a, const BodyInfo& b) {
  if ((a.layer & b.mask) == 0 || (b.layer & a.mask) == 0) return false;
  if (a.kind == BodyKind::kStatic && b.kind == BodyKind::kStatic) return false;
  bool dynamic = a.kind == BodyKind::kDynamic || b.kind == BodyKind::kDynamic;
  bool sensor = a.sensor != 0 || b.sensor != 0;
  return dynamic || sensor;
}

void add_pair(const WorldState& state, const WorldScratch& scratch, uint32_t x, uint32_t y,
              std::vector<BodyPair>& pairs) {
  if (!overlap_yz(scratch.aabbs[x], scratch.aabbs[y])) return;
  if (!should_pair(state.infos[x], state.infos[y])) return;
  pairs.push_back(x < y ? BodyPair{x, y} : BodyPair{y, x});
}

}  // namespace

void find_pairs(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.aabbs.resize(n);
  const float tick = state.config.tick_seconds;
  const float speculative = state.config.speculative_distance_m;

  // Active bounds are fattened by the speculative distance plus how far the
  // body can move this tick, so a fast body meets what it will hit in time
  // for a speculative contact to stop it.
  scratch.active.clear();
  for (uint32_t i = 0; i < n; ++i) {
    const BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    const BodySim& sim = state.sims[i];
    Aabb box = shape_aabb(info.shape, sim.position, sim.rotation);
    float reach =
        length(sim.linear_velocity) + length(sim.angular_velocity) * state.masses[i].extent;
    float margin = speculative + tick * reach;
    Vec3 m{margin, margin, margin};
    box.lower -= m;
    box.upper += m;
    scratch.aabbs[i] = box;
    scratch.active.push_back({box.lower.x, i});
  }
  std::sort(scratch.active.begin(), scratch.active.end(), entry_less);

  if (scratch.passive_dirty) {
    scratch.passive.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const BodyInfo& info = state.infos[i];
      if (!is_simulated(info) || is_active(info)) continue;
      const BodySim& sim = state.sims[i];
      scratch.aabbs[i] = shape_aabb(info.shape, sim.position, sim.rotation);
      scratch.passive.push_back({scratch.aabbs[i].lower.x, i});
    }
    std::sort(scratch.passive.begin(), scratch.passive.end(), entry_less);
    scratch.passive_dirty = false;
  }

  std::vector<BodyPair>& pairs = scratch.pairs;
  pairs.clear();
  const auto& act = scratch.active;
  const auto& pas = scratch.passive;
  // Active vs active.
  for (size_t i = 0; i < act.size(); ++i) {
    float max_x = scratch.aabbs[act[i].body].upper.x;
    for (size_t j = i + 1; j < act.size() && act[j].min_x <= max_x; ++j) {
      add_pair(state, scratch, act[i].body, act[j].body, pairs);
    }
  }
  // Active vs passive, split so each overlapping pair is found exactly once:
  // (1) the passive body starts inside the active one's x range;
  for (const SweepEntry& a : act) {
    float max_x = scratch.aabbs[a.body].upper.x;
    auto it = std::lower_bound(pas.begin(), pas.end(), a.min_x,
                               [](const SweepEntry& e, float x) { return e.min_x < x; });
    for (; it != pas.end() && it->min_x <= max_x; ++it) {
      add_pair(state, scratch, a.body, it->body, pairs);
    }
  }
  // (2) the active body starts strictly inside the passive one's x range.
  size_t first = 0;
  for (const SweepEntry& p : pas) {
    while (first < act.size() && act[first].min_x <= p.min_x) ++first;
    float max_x = scratch.aabbs[p.body].upper.x;
    for (size_t j = first; j < act.size() && act[j].min_x <= max_x; ++j) {
      add_pair(state, scratch, act[j].body, p.body, pairs);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const BodyPair& l, const BodyPair& r) {
    return l.a < r.a || (l.a == r.a && l.b < r.b);
  });
  scratch.stats.broadphase_pairs = static_cast<uint32_t>(pairs.size());
}

}  // namespace rwd::sim::d3
