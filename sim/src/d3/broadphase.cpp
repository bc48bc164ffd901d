// SPDX-License-Identifier: MIT
// The broadphase (broadphase.h): its trees, the awake bodies' sweep, the
// sorted candidate pairs and the query side.
#include "d3/broadphase.h"

#include <algorithm>
#include <cstddef>
#include <limits>

#include "d3/body_storage.h"
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

// The axis along which the boxes' centres spread most.
int spread_axis(std::span<const uint32_t> awake, std::span<const Aabb> bounds) {
  double sum[3] = {0.0, 0.0, 0.0};
  double sum_sq[3] = {0.0, 0.0, 0.0};
  for (const uint32_t i : awake) {
    const Aabb& box = bounds[i];
    const double c[3] = {static_cast<double>(box.lower.x) + box.upper.x,
                         static_cast<double>(box.lower.y) + box.upper.y,
                         static_cast<double>(box.lower.z) + box.upper.z};
    for (int a = 0; a < 3; ++a) {
      sum[a] += c[a];
      sum_sq[a] += c[a] * c[a];
    }
  }
  const double count = static_cast<double>(std::max<size_t>(1, awake.size()));
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

}  // namespace

void Broadphase::mark_edited() {
  edited_ = true;
  query_serial_ = kNoSerial;
}

// Rebuilds the static and sleeping trees in bulk (the world was edited or
// restored).
void Broadphase::rebuild_trees(const WorldState& state) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  for (int pass = 0; pass < 2; ++pass) {
    const bool statics = pass == 0;
    build_bodies_.clear();
    build_boxes_.clear();
    for (uint32_t i = 0; i < n; ++i) {
      const BodyInfo& info = state.infos[i];
      const bool wanted =
          statics ? is_simulated(info) && info.kind == BodyKind::kStatic : is_sleeping(info);
      if (!wanted) continue;
      build_bodies_.push_back(i);
      build_boxes_.push_back(exact_bounds(state, i));
    }
    if (statics) {
      static_tree_.build(build_boxes_, build_bodies_);
    } else {
      sleeping_tree_.build(build_boxes_, build_bodies_, build_proxies_);
    }
  }
  sleeping_proxy_.assign(n, AabbTree::kNull);
  for (size_t k = 0; k < build_bodies_.size(); ++k) {
    sleeping_proxy_[build_bodies_[k]] = build_proxies_[k];
  }
  edited_ = false;
}

// Bodies that fell asleep enter the sleeping tree; bodies that woke, were
// disabled or destroyed leave it. A sleeping body cannot move without
// waking (a teleport wakes it and marks the world edited), so its leaf
// stays exact while it sleeps. One pass of flag tests: nothing relies on
// every sleep and wake being reported. A body that changed trees is no
// longer where the awake query tree has it, so that tree is rebuilt.
void Broadphase::update_sleeping_tree(const WorldState& state) {
  if (edited_) {
    rebuild_trees(state);
    return;
  }
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t& proxy = sleeping_proxy_[i];
    const bool sleeping = is_sleeping(state.infos[i]);
    if (sleeping && proxy == AabbTree::kNull) {
      proxy = sleeping_tree_.insert(exact_bounds(state, i), i);
      query_serial_ = kNoSerial;
    } else if (!sleeping && proxy != AabbTree::kNull) {
      sleeping_tree_.remove(proxy);
      proxy = AabbTree::kNull;
      query_serial_ = kNoSerial;
    }
  }
}

void Broadphase::update(const WorldState& state, std::span<const uint32_t> awake,
                        std::span<const Aabb> bounds) {
  const bool same_awake =
      !edited_ && tree_awake_valid_ &&
      std::equal(awake.begin(), awake.end(), tree_awake_.begin(), tree_awake_.end());
  if (!same_awake) {
    update_sleeping_tree(state);
    tree_awake_.assign(awake.begin(), awake.end());
    tree_awake_valid_ = true;
  }
  sort_sweep(state, awake, bounds, spread_axis(awake, bounds));
}

// Sorts the awake bodies by (lower bound on the axis, body): from scratch
// when the set or the axis changed, else by insertion from last step's
// order, which is nearly sorted already.
void Broadphase::sort_sweep(const WorldState& state, std::span<const uint32_t> awake,
                            std::span<const Aabb> bounds, int axis) {
  std::vector<uint32_t>& order = sweep_order_;
  std::vector<float>& lower = sweep_lower_;
  bool same_set = order.size() == awake.size() && axis == sweep_axis_;
  for (size_t k = 0; same_set && k < order.size(); ++k) {
    same_set = order[k] < state.infos.size() && is_active(state.infos[order[k]]);
  }
  sweep_axis_ = axis;
  const size_t m = awake.size();
  if (!same_set) {
    order.assign(awake.begin(), awake.end());
    std::sort(order.begin(), order.end(), [&](uint32_t l, uint32_t r) {
      const float kl = lower_on(bounds[l], axis);
      const float kr = lower_on(bounds[r], axis);
      return kl < kr || (kl == kr && l < r);
    });
    lower.resize(m);
    for (size_t k = 0; k < m; ++k) lower[k] = lower_on(bounds[order[k]], axis);
  } else {
    lower.resize(m);
    for (size_t k = 0; k < m; ++k) {
      const uint32_t body = order[k];
      const float key = lower_on(bounds[body], axis);
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
  sweep_upper_.resize(m);
  // The cross-axis bounds are padded for sweep_one's last lanes: empty
  // intervals (lower > upper) overlap nothing.
  const size_t padded = m + kLanes - 1;
  for (int c = 0; c < 4; ++c) {
    const float pad =
        c % 2 == 0 ? std::numeric_limits<float>::max() : -std::numeric_limits<float>::max();
    sweep_cross_[c].resize(padded);
    std::fill(sweep_cross_[c].begin() + static_cast<std::ptrdiff_t>(m), sweep_cross_[c].end(), pad);
  }
  const int axis1 = (axis + 1) % 3;
  const int axis2 = (axis + 2) % 3;
  for (size_t k = 0; k < m; ++k) {
    const Aabb& box = bounds[order[k]];
    sweep_upper_[k] = upper_on(box, axis);
    sweep_cross_[0][k] = lower_on(box, axis1);
    sweep_cross_[1][k] = upper_on(box, axis1);
    sweep_cross_[2][k] = lower_on(box, axis2);
    sweep_cross_[3][k] = upper_on(box, axis2);
  }
  sweep_hits_.resize(m);
}

// Positions after k in the sweep order whose bounds overlap k's, into
// `hits`, ascending; returns how many. The candidates are the positions
// whose lower bound on the sweep axis is at most k's upper one (a binary
// search: the lower bounds are sorted); they are tested kLanes at a time
// on the other two axes, branch-free, since in a dense scene they are many
// more than the overlaps. The arrays are padded with kLanes - 1 entries
// that overlap nothing.
size_t Broadphase::sweep_one(size_t k, uint32_t* hits) const {
  const size_t m = sweep_order_.size();
  const float* lower = sweep_lower_.data();
  const float* lo1 = sweep_cross_[0].data();
  const float* hi1 = sweep_cross_[1].data();
  const float* lo2 = sweep_cross_[2].data();
  const float* hi2 = sweep_cross_[3].data();
  const float upper = sweep_upper_[k];
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

void Broadphase::find_pairs(const WorldState& state, std::span<const Aabb> bounds,
                            std::vector<BodyPair>& pairs) {
  pairs.clear();
  const size_t m = sweep_order_.size();
  for (size_t k = 0; k < m; ++k) {
    const uint32_t i = sweep_order_[k];
    const BodyInfo& info = state.infos[i];
    const size_t hit_count = sweep_one(k, sweep_hits_.data());
    for (size_t h = 0; h < hit_count; ++h) {
      const uint32_t j = sweep_order_[sweep_hits_[h]];
      if (!should_pair(info, state.infos[j])) continue;
      pairs.push_back(i < j ? BodyPair{i, j} : BodyPair{j, i});
    }
    // Tree leaves hold exact bounds, so a leaf reached is a pair.
    const auto against = [&](uint32_t j) {
      if (!should_pair(info, state.infos[j])) return;
      pairs.push_back(i < j ? BodyPair{i, j} : BodyPair{j, i});
    };
    sleeping_tree_.query(bounds[i], against);
    static_tree_.query(bounds[i], against);
  }
  sort_pairs(pairs, static_cast<uint32_t>(state.infos.size()));
}

// Sorts the pairs by (a, b): a counting sort by a (one pass to count, one
// to place), then each a's pairs by b, by insertion while they are few (a
// body has a handful of neighbours) and std::sort past that (the ground
// under a pile). Pairs are unique, so the order is the one sort order.
void Broadphase::sort_pairs(std::vector<BodyPair>& pairs, uint32_t body_count) {
  // A few pairs among many bodies (a few awake in a sleeping level): a
  // comparison sort, not a pass over every body. Either gives the one
  // (a, b) order (no pair appears twice).
  if (pairs.size() * 8 < body_count) {
    std::sort(pairs.begin(), pairs.end(), [](const BodyPair& l, const BodyPair& r) {
      return l.a != r.a ? l.a < r.a : l.b < r.b;
    });
    return;
  }
  std::vector<BodyPair>& sorted = pair_spare_;
  std::vector<uint32_t>& start = pair_start_;
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

// The query side: the static and sleeping trees are the step's own, and the
// bodies in neither get a tree over their exact bounds at these poses, so
// every simulated body is in exactly one of the three and a query never
// meets a body twice. All three are made current once per pose serial: a
// body cannot move between steps without an edit (which rebuilds them), so
// one woken by a velocity between steps is still exactly where its
// sleeping leaf says, and a world queried many times per step scans its
// bodies once.
void Broadphase::prepare_queries(const WorldState& state, uint64_t pose_serial) {
  if (query_serial_ == pose_serial && !edited_) return;
  update_sleeping_tree(state);
  // Brought up to date with bodies woken or put to sleep since the last
  // step: update() cannot tell from the awake list alone any more.
  tree_awake_valid_ = false;
  build_bodies_.clear();
  build_boxes_.clear();
  for (uint32_t i = 0; i < state.infos.size(); ++i) {
    const BodyInfo& info = state.infos[i];
    if (!is_simulated(info) || info.kind == BodyKind::kStatic ||
        sleeping_proxy_[i] != AabbTree::kNull) {
      continue;
    }
    build_bodies_.push_back(i);
    build_boxes_.push_back(exact_bounds(state, i));
  }
  awake_tree_.build(build_boxes_, build_bodies_, WideBoxTree::Cuts::kAtMedians);
  query_serial_ = pose_serial;
}

}  // namespace rwd::sim::d3
