// SPDX-License-Identifier: MIT
// Broadphase. Each kind of body is held the way it moves:
//   - awake bodies are swept and pruned along the axis where their centres
//     spread most; the sorted order is kept from step to step, so a scene
//     that moved a little re-sorts in one pass, and their bounds are copied
//     into that order so the sweep reads memory in sequence;
//   - sleeping bodies live in an AABB tree (aabb_tree.h) they enter when
//     they fall asleep and leave when they wake;
//   - static bodies live in a tree built in bulk and rebuilt only when the
//     world is edited.
// Awake bodies query both trees; sleeping and static bodies never query,
// so resting geometry costs nothing per step.
//
// A pair is kept when the exact bounds overlap (awake bodies: fattened by
// the speculative distance and their reach this tick; sleeping and static
// bodies: their shape's bounds) and the pairs are sorted, so the output is
// a function of the state alone: the sweep axis and the shape of a tree,
// which depend on history and differ after a restore, never reach a result.
#include <algorithm>
#include <cstddef>
#include <limits>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/wide_float.h"

namespace rwd::sim::d3 {
namespace {

// Filtering: both layer masks must agree; something must be able to respond
// (a dynamic body) or to report (a sensor); two static bodies never pair.
bool should_pair(const BodyInfo& a, const BodyInfo& b) {
  if ((a.layer & b.mask) == 0 || (b.layer & a.mask) == 0) return false;
  if (a.kind == BodyKind::kStatic && b.kind == BodyKind::kStatic) return false;
  bool dynamic = a.kind == BodyKind::kDynamic || b.kind == BodyKind::kDynamic;
  bool sensor = a.sensor != 0 || b.sensor != 0;
  return dynamic || sensor;
}

bool is_sleeping(const BodyInfo& info) {
  return is_simulated(info) && info.kind != BodyKind::kStatic && !is_active(info);
}

float lower_on(const Aabb& box, int axis) {
  return axis == 0 ? box.lower.x : (axis == 1 ? box.lower.y : box.lower.z);
}

float upper_on(const Aabb& box, int axis) {
  return axis == 0 ? box.upper.x : (axis == 1 ? box.upper.y : box.upper.z);
}

Aabb exact_bounds(const WorldState& state, uint32_t i) {
  const BodySim& sim = state.sims[i];
  return shape_aabb(state.infos[i].shape, sim.position, sim.rotation);
}

// Rebuilds both trees in bulk (the world was edited or restored).
void rebuild_trees(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  for (int pass = 0; pass < 2; ++pass) {
    const bool statics = pass == 0;
    scratch.tree_bodies.clear();
    scratch.tree_boxes.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const BodyInfo& info = state.infos[i];
      const bool wanted =
          statics ? is_simulated(info) && info.kind == BodyKind::kStatic : is_sleeping(info);
      if (!wanted) continue;
      scratch.tree_bodies.push_back(i);
      scratch.tree_boxes.push_back(exact_bounds(state, i));
    }
    AabbTree& tree = statics ? scratch.static_tree : scratch.sleeping_tree;
    tree.build(scratch.tree_boxes, scratch.tree_bodies, scratch.tree_proxies);
  }
  scratch.sleeping_proxy.assign(n, AabbTree::kNull);
  for (size_t k = 0; k < scratch.tree_bodies.size(); ++k) {
    scratch.sleeping_proxy[scratch.tree_bodies[k]] = scratch.tree_proxies[k];
  }
  scratch.static_dirty = false;
}

// Bodies that fell asleep enter the sleeping tree; bodies that woke, were
// disabled or destroyed leave it. A sleeping body cannot move without
// waking (a teleport wakes it and marks the world edited), so its leaf
// stays exact while it sleeps. One pass of flag tests per step: nothing
// relies on every sleep and wake being reported.
void update_sleeping_tree(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t& proxy = scratch.sleeping_proxy[i];
    const bool sleeping = is_sleeping(state.infos[i]);
    if (sleeping && proxy == AabbTree::kNull) {
      proxy = scratch.sleeping_tree.insert(exact_bounds(state, i), i);
    } else if (!sleeping && proxy != AabbTree::kNull) {
      scratch.sleeping_tree.remove(proxy);
      proxy = AabbTree::kNull;
    }
  }
}

// The awake bodies' bounds, and the axis their centres spread most along.
int awake_bounds(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.aabbs.resize(n);
  scratch.active.clear();
  const float tick = state.config.tick_seconds;
  const float speculative = state.config.speculative_distance_m;
  double sum[3] = {0.0, 0.0, 0.0};
  double sum_sq[3] = {0.0, 0.0, 0.0};
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
    const double c[3] = {static_cast<double>(box.lower.x) + box.upper.x,
                         static_cast<double>(box.lower.y) + box.upper.y,
                         static_cast<double>(box.lower.z) + box.upper.z};
    for (int a = 0; a < 3; ++a) {
      sum[a] += c[a];
      sum_sq[a] += c[a] * c[a];
    }
  }
  const double count = static_cast<double>(std::max<size_t>(1, scratch.active.size()));
  int axis = 0;
  double best = -1.0;
  for (int a = 0; a < 3; ++a) {
    const double variance = sum_sq[a] - sum[a] * sum[a] / count;
    if (variance > best) {
      best = variance;
      axis = a;
    }
  }
  return axis;
}

// Sorts the awake bodies by (lower bound on the axis, body): from scratch
// when the set or the axis changed, else by insertion from last step's
// order, which is nearly sorted already.
void sort_sweep(const WorldState& state, WorldScratch& scratch, int axis) {
  std::vector<uint32_t>& order = scratch.sweep_order;
  std::vector<float>& lower = scratch.sweep_lower;
  bool same_set = order.size() == scratch.active.size() && axis == scratch.sweep_axis;
  for (size_t k = 0; same_set && k < order.size(); ++k) {
    same_set = order[k] < state.infos.size() && is_active(state.infos[order[k]]);
  }
  scratch.sweep_axis = axis;
  const size_t m = scratch.active.size();
  if (!same_set) {
    order = scratch.active;
    std::sort(order.begin(), order.end(), [&](uint32_t l, uint32_t r) {
      const float kl = lower_on(scratch.aabbs[l], axis);
      const float kr = lower_on(scratch.aabbs[r], axis);
      return kl < kr || (kl == kr && l < r);
    });
    lower.resize(m);
    for (size_t k = 0; k < m; ++k) lower[k] = lower_on(scratch.aabbs[order[k]], axis);
  } else {
    lower.resize(m);
    for (size_t k = 0; k < m; ++k) {
      const uint32_t body = order[k];
      const float key = lower_on(scratch.aabbs[body], axis);
      size_t slot = k;
      while (slot > 0 &&
             (lower[slot - 1] > key || (lower[slot - 1] == key && order[slot - 1] > body))) {
        lower[slot] = lower[slot - 1];
        order[slot] = order[slot - 1];
        --slot;
      }
      lower[slot] = key;
      order[slot] = body;
    }
  }
  scratch.sweep_upper.resize(m);
  // The cross-axis bounds are padded for sweep_one's last lanes: empty
  // intervals (lower > upper) overlap nothing.
  const size_t padded = m + kLanes - 1;
  for (int c = 0; c < 4; ++c) {
    const float pad =
        c % 2 == 0 ? std::numeric_limits<float>::max() : -std::numeric_limits<float>::max();
    scratch.sweep_cross[c].resize(padded);
    std::fill(scratch.sweep_cross[c].begin() + static_cast<std::ptrdiff_t>(m),
              scratch.sweep_cross[c].end(), pad);
  }
  const int axis1 = (axis + 1) % 3;
  const int axis2 = (axis + 2) % 3;
  for (size_t k = 0; k < m; ++k) {
    const Aabb& box = scratch.aabbs[order[k]];
    scratch.sweep_upper[k] = upper_on(box, axis);
    scratch.sweep_cross[0][k] = lower_on(box, axis1);
    scratch.sweep_cross[1][k] = upper_on(box, axis1);
    scratch.sweep_cross[2][k] = lower_on(box, axis2);
    scratch.sweep_cross[3][k] = upper_on(box, axis2);
  }
  scratch.sweep_hits.resize(m);
}

// Positions after k in the sweep order whose bounds overlap k's, into
// `hits`, ascending; returns how many. The candidates are the positions
// whose lower bound on the sweep axis is at most k's upper one (a binary
// search: the lower bounds are sorted); they are tested kLanes at a time
// on the other two axes, branch-free, since in a dense scene they are many
// more than the overlaps. The arrays are padded with kLanes - 1 entries
// that overlap nothing.
size_t sweep_one(const WorldScratch& scratch, size_t k, uint32_t* hits) {
  const size_t m = scratch.sweep_order.size();
  const float* lower = scratch.sweep_lower.data();
  const float* lo1 = scratch.sweep_cross[0].data();
  const float* hi1 = scratch.sweep_cross[1].data();
  const float* lo2 = scratch.sweep_cross[2].data();
  const float* hi2 = scratch.sweep_cross[3].data();
  const float upper = scratch.sweep_upper[k];
  const size_t end = static_cast<size_t>(std::upper_bound(lower + k + 1, lower + m, upper) - lower);
  const FloatW k_lo1 = splat(lo1[k]);
  const FloatW k_hi1 = splat(hi1[k]);
  const FloatW k_lo2 = splat(lo2[k]);
  const FloatW k_hi2 = splat(hi2[k]);
  size_t count = 0;
  for (size_t l = k + 1; l < end; l += kLanes) {
    const MaskW miss = (load(lo1 + l) > k_hi1) | (k_lo1 > load(hi1 + l)) | (load(lo2 + l) > k_hi2) |
                       (k_lo2 > load(hi2 + l));
    uint32_t bits = ~lane_bits(miss) & ((1u << kLanes) - 1u);
    if (end - l < static_cast<size_t>(kLanes)) bits &= (1u << (end - l)) - 1u;
    while (bits != 0) {
      hits[count++] = static_cast<uint32_t>(l + static_cast<size_t>(__builtin_ctz(bits)));
      bits &= bits - 1u;
    }
  }
  return count;
}

// Sorts scratch.pairs by (a, b): a counting sort by a (one pass to count,
// one to place), then each a's pairs by b, by insertion while they are few
// (a body has a handful of neighbours) and std::sort past that (the ground
// under a pile). Pairs are unique, so the order is the one sort order.
void sort_pairs(WorldScratch& scratch, uint32_t body_count) {
  std::vector<BodyPair>& pairs = scratch.pairs;
  std::vector<BodyPair>& sorted = scratch.pair_spare;
  std::vector<uint32_t>& start = scratch.pair_start;
  start.assign(static_cast<size_t>(body_count) + 1, 0);
  for (const BodyPair& p : pairs) ++start[p.a + 1];
  for (uint32_t i = 0; i < body_count; ++i) start[i + 1] += start[i];
  sorted.resize(pairs.size());
  for (const BodyPair& p : pairs) sorted[start[p.a]++] = p;
  // start[a] is now the end of a's run, and the start of a + 1's.
  uint32_t begin = 0;
  for (uint32_t a = 0; a < body_count; ++a) {
    const uint32_t end = start[a];
    if (end - begin > 16) {
      std::sort(sorted.begin() + begin, sorted.begin() + end,
                [](const BodyPair& l, const BodyPair& r) { return l.b < r.b; });
    } else {
      for (uint32_t k = begin + 1; k < end; ++k) {
        const BodyPair p = sorted[k];
        uint32_t slot = k;
        while (slot > begin && sorted[slot - 1].b > p.b) {
          sorted[slot] = sorted[slot - 1];
          --slot;
        }
        sorted[slot] = p;
      }
    }
    begin = end;
  }
  pairs.swap(sorted);
}

}  // namespace

void find_pairs(const WorldState& state, WorldScratch& scratch) {
  // The first stage of a step: the step's body frames start here.
  begin_body_axes(state, scratch);
  if (scratch.static_dirty) {
    rebuild_trees(state, scratch);
  } else {
    update_sleeping_tree(state, scratch);
  }
  sort_sweep(state, scratch, awake_bounds(state, scratch));

  std::vector<BodyPair>& pairs = scratch.pairs;
  pairs.clear();
  const std::vector<uint32_t>& order = scratch.sweep_order;
  const size_t m = order.size();
  for (size_t k = 0; k < m; ++k) {
    const uint32_t i = order[k];
    const Aabb& box = scratch.aabbs[i];
    const BodyInfo& info = state.infos[i];
    const size_t hit_count = sweep_one(scratch, k, scratch.sweep_hits.data());
    for (size_t h = 0; h < hit_count; ++h) {
      const uint32_t j = order[scratch.sweep_hits[h]];
      if (!should_pair(info, state.infos[j])) continue;
      pairs.push_back(i < j ? BodyPair{i, j} : BodyPair{j, i});
    }
    // Tree leaves hold exact bounds, so a leaf reached is a pair.
    const auto against = [&](uint32_t j) {
      if (!should_pair(info, state.infos[j])) return;
      pairs.push_back(i < j ? BodyPair{i, j} : BodyPair{j, i});
    };
    scratch.sleeping_tree.query(box, against);
    scratch.static_tree.query(box, against);
  }
  sort_pairs(scratch, static_cast<uint32_t>(state.infos.size()));
  scratch.stats.broadphase_pairs = static_cast<uint32_t>(pairs.size());
}

}  // namespace rwd::sim::d3
