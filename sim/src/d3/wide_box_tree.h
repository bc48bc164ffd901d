// SPDX-License-Identifier: MIT
#pragma once
// A four-wide bounding volume hierarchy, built in bulk, for boxes that
// change rarely or all at once: the broadphase's static bodies and the
// awake bodies' query tree. Each node keeps its up to four children's
// boxes side by side, so four lanes (wide_float.h) test a box, a ray or a
// sweep against all of them at once, and a walk passes about half as many
// levels as in a binary tree. Queries through a level of static geometry
// spend nearly all their time walking, so this is where they get faster.
//
// It answers the bulk questions of AabbTree with the same tests, lane by
// lane and operation by operation (SegmentSlabs, overlaps), so a leaf is
// visited by exactly the rule it is there: the set of leaves a box, ray or
// sweep query visits is the same, and a nearest-first walk visits every
// leaf whose box the segment enters within the reach. Only the order of
// the visits differs, which no caller depends on. Like AabbTree, it is
// working memory: nothing that reaches the state depends on its shape.
#include <cstdint>
#include <span>
#include <vector>

#include "d3/aabb_tree.h"
#include "d3/wide_float.h"

namespace rwd::sim::d3 {

class WideBoxTree {
 public:
  /// Removes every leaf; capacity is kept.
  void clear();

  /// How a build cuts its boxes into children.
  enum class Cuts : uint8_t {
    /// By the surface area heuristic: trees that walk fastest, for boxes
    /// that are built rarely and queried often (static bodies).
    kByArea,
    /// At medians: a build about 1.5 times faster, for trees rebuilt as
    /// often as they are queried (the awake bodies, after every step).
    kAtMedians,
  };

  /// Replaces the tree by one built top-down over `boxes[i]` for
  /// `bodies[i]` (bodies below 2^31; same length). Given exactly the boxes
  /// and bodies of the tree it holds, it keeps that tree.
  void build(std::span<const Aabb> boxes, std::span<const uint32_t> bodies,
             Cuts cuts = Cuts::kByArea);

  uint32_t leaf_count() const { return leaves_; }

  /// Calls visit(body) for every leaf whose box overlaps `box` (in tree
  /// order, which callers must not depend on).
  template <typename Visit>
  void query(const Aabb& box, Visit&& visit) const;

  /// Calls visit(body) for every leaf whose box the segment origin +
  /// t * dir, 0 <= t <= max_t, touches (SegmentSlabs::hits).
  template <typename Visit>
  void ray_query(Vec3 origin, Vec3 dir, float max_t, Visit&& visit) const;

  /// Calls visit(body) for every leaf whose box the box `start` touches on
  /// its way along `translation` (as AabbTree::sweep_query).
  template <typename Visit>
  void sweep_query(const Aabb& start, Vec3 translation, Visit&& visit) const;

  /// For the closest hit, as AabbTree::ray_query_nearest: nearer children
  /// first, every node the segment enters only past the padded `reach`
  /// skipped, `reach` shortened by visit(body) as it finds hits.
  template <typename Visit>
  void ray_query_nearest(Vec3 origin, Vec3 dir, float& reach, Visit&& visit) const;
  /// The same for a box moving along `translation`, as
  /// AabbTree::sweep_query_nearest.
  template <typename Visit>
  void sweep_query_nearest(const Aabb& start, Vec3 translation, float& reach, Visit&& visit) const;

  /// Every leaf appears once, every node has one to four children, an
  /// inner child's box bounds the boxes of its own children, and no path
  /// is longer than the walks' stacks allow; for tests.
  bool valid() const;

 private:
  static constexpr uint32_t kNull = 0xFFFFFFFFu;
  /// A child that is a leaf: this bit and the body.
  static constexpr uint32_t kLeaf = 0x80000000u;
  /// Levels cut by the surface area heuristic (Cuts::kByArea), which may
  /// cut unevenly; below them cuts are at medians, which quarter a range
  /// per level, so a tree of up to 2^31 leaves is at most kMaxDepth levels
  /// deep, and a depth-first walk holds at most three siblings per level
  /// plus four.
  static constexpr uint32_t kCostDepth = 24;
  static constexpr uint32_t kMaxDepth = kCostDepth + 16;
  static constexpr uint32_t kStackSize = (kMaxDepth + 1) * 3 + 4;

  struct alignas(64) Node {
    float lower[3][kLanes];  ///< [axis][child]
    float upper[3][kLanes];
    uint32_t child[kLanes];  ///< a node's index, or kLeaf | body
    uint32_t count = 0;      ///< children used, from the first
  };

  uint32_t split(uint32_t* items, uint32_t n, bool median);
  uint32_t build_range(uint32_t* items, uint32_t count, uint32_t depth, Cuts cuts, Aabb& bounds);
  bool valid_node(uint32_t node, const Aabb& bounds, uint32_t depth,
                  std::vector<uint32_t>& seen) const;

  // Bit k set for each child k of `node` whose box overlaps `box`.
  static uint32_t overlap_bits(const Node& node, const Aabb& box);
  // Bit k set for each child k of `node` whose box, grown by `grow` when
  // kGrow, the segment enters within max_t; entry[k] is where.
  template <bool kGrow>
  static uint32_t enter_bits(const Node& node, const SegmentSlabs& slabs, Vec3 grow, float max_t,
                             float (&entry)[kLanes]);

  template <typename Accept, typename Visit>
  void walk(Accept&& accept, Visit&& visit) const;
  template <bool kGrow, typename Visit>
  void nearest_walk(const SegmentSlabs& slabs, Vec3 grow, float& reach, Visit&& visit) const;

  std::vector<Node> nodes_;
  std::vector<uint32_t> build_items_;
  std::vector<Aabb> build_boxes_;
  std::vector<uint32_t> build_bodies_;
  uint32_t root_ = kNull;
  uint32_t leaves_ = 0;
};

inline uint32_t WideBoxTree::overlap_bits(const Node& node, const Aabb& box) {
  // overlaps(child, box), lane by lane.
  const MaskW hit =
      (splat(box.upper.x) >= load(node.lower[0])) & (load(node.upper[0]) >= splat(box.lower.x)) &
      (splat(box.upper.y) >= load(node.lower[1])) & (load(node.upper[1]) >= splat(box.lower.y)) &
      (splat(box.upper.z) >= load(node.lower[2])) & (load(node.upper[2]) >= splat(box.lower.z));
  return lane_bits(hit) & ((1u << node.count) - 1u);
}

template <bool kGrow>
inline uint32_t WideBoxTree::enter_bits(const Node& node, const SegmentSlabs& slabs, Vec3 grow,
                                        float max_t, float (&entry)[kLanes]) {
  // SegmentSlabs::enters, lane by lane. No value here is NaN: an axis the
  // segment is not parallel to has a finite reciprocal, and box and origin
  // are finite, so each t is finite or infinite; the min and max
  // instructions then give std::min's and std::max's floats on every
  // target, but for the sign of a zero, which no comparison sees. An axis
  // the segment runs parallel to fails a lane whose box it passes outside
  // by dropping t_hi below t_lo (which never falls below 0).
  FloatW t_lo = splat(0.0f);
  FloatW t_hi = splat(max_t);
  for (int i = 0; i < 3; ++i) {
    FloatW lo = load(node.lower[i]);
    FloatW hi = load(node.upper[i]);
    if constexpr (kGrow) {
      lo = lo - splat(component(grow, i));
      hi = hi + splat(component(grow, i));
    }
    const FloatW o = splat(component(slabs.origin, i));
    if (slabs.any_parallel && slabs.parallel[i]) {
      t_hi = select((o < lo) | (o > hi), splat(-1.0f), t_hi);
      continue;
    }
    const FloatW inv = splat(component(slabs.inv_dir, i));
    const FloatW t0 = (lo - o) * inv;
    const FloatW t1 = (hi - o) * inv;
    t_lo = max_no_nan(t_lo, min_no_nan(t0, t1));
    t_hi = min_no_nan(t_hi, max_no_nan(t0, t1));
  }
  store(entry, t_lo);
  return lane_bits(t_hi >= t_lo) & ((1u << node.count) - 1u);
}

template <typename Accept, typename Visit>
void WideBoxTree::walk(Accept&& accept, Visit&& visit) const {
  if (root_ == kNull) return;
  uint32_t stack[kStackSize];
  uint32_t top = 0;
  stack[top++] = root_;
  while (top > 0) {
    uint32_t index = stack[--top];
    // The last inner child found is walked next without a trip through the
    // stack: the order is the stack's, one store and load fewer a node.
    while (index != kNull) {
      const Node& node = nodes_[index];
      uint32_t bits = accept(node);
      index = kNull;
      while (bits != 0) {
        const uint32_t child = node.child[__builtin_ctz(bits)];
        bits &= bits - 1u;
        if (child & kLeaf) {
          visit(child & ~kLeaf);
          continue;
        }
        if (index != kNull) stack[top++] = index;
        index = child;
      }
    }
  }
}

template <typename Visit>
void WideBoxTree::query(const Aabb& box, Visit&& visit) const {
  walk([&box](const Node& node) { return overlap_bits(node, box); }, visit);
}

template <typename Visit>
void WideBoxTree::ray_query(Vec3 origin, Vec3 dir, float max_t, Visit&& visit) const {
  const SegmentSlabs slabs(origin, dir);
  float entry[kLanes];
  walk([&](const Node& node) { return enter_bits<false>(node, slabs, {}, max_t, entry); }, visit);
}

template <typename Visit>
void WideBoxTree::sweep_query(const Aabb& start, Vec3 translation, Visit&& visit) const {
  const SweptBox swept(start, translation);
  float entry[kLanes];
  walk(
      [&](const Node& node) {
        return enter_bits<true>(node, swept.slabs, swept.half, 1.0f, entry);
      },
      visit);
}

template <bool kGrow, typename Visit>
void WideBoxTree::nearest_walk(const SegmentSlabs& slabs, Vec3 grow, float& reach,
                               Visit&& visit) const {
  if (root_ == kNull) return;
  // The skip margin of AabbTree::nearest_walk.
  const auto padded = [](float t) { return t + 1e-3f * t + 1e-3f; };
  // Each entry is a child (as Node::child) and where the segment enters
  // its box, kept in two arrays so that each field is written and read
  // alone: a pair written as two 4-byte stores and read back as one 8-byte
  // load cannot be forwarded from the store buffer and stalls every pop.
  uint32_t stack_child[kStackSize];
  float stack_t[kStackSize];
  uint32_t top = 0;
  stack_child[top] = root_;
  stack_t[top++] = 0.0f;
  while (top > 0) {
    --top;
    uint32_t child = stack_child[top];
    if (stack_t[top] > padded(reach)) continue;  // the reach shrank since it was pushed
    // Down the nearest child without a trip through the stack (the reach
    // cannot have shrunk between its test and now); the others wait there.
    for (;;) {
      if (child & kLeaf) {
        visit(child & ~kLeaf);
        break;
      }
      const Node& node = nodes_[child];
      float entry[kLanes];
      uint32_t bits = enter_bits<kGrow>(node, slabs, grow, padded(reach), entry);
      // The children entered, farthest first.
      uint32_t found_child[kLanes];
      float found_t[kLanes];
      uint32_t count = 0;
      while (bits != 0) {
        const uint32_t k = static_cast<uint32_t>(__builtin_ctz(bits));
        bits &= bits - 1u;
        const float t = entry[k];
        uint32_t slot = count++;
        while (slot > 0 && found_t[slot - 1] < t) {
          found_child[slot] = found_child[slot - 1];
          found_t[slot] = found_t[slot - 1];
          --slot;
        }
        found_child[slot] = node.child[k];
        found_t[slot] = t;
      }
      if (count == 0) break;
      for (uint32_t k = 0; k + 1 < count; ++k) {
        stack_child[top] = found_child[k];
        stack_t[top++] = found_t[k];
      }
      child = found_child[count - 1];
    }
  }
}

template <typename Visit>
void WideBoxTree::ray_query_nearest(Vec3 origin, Vec3 dir, float& reach, Visit&& visit) const {
  nearest_walk<false>(SegmentSlabs(origin, dir), {}, reach, visit);
}

template <typename Visit>
void WideBoxTree::sweep_query_nearest(const Aabb& start, Vec3 translation, float& reach,
                                      Visit&& visit) const {
  const SweptBox swept(start, translation);
  nearest_walk<true>(swept.slabs, swept.half, reach, visit);
}

}  // namespace rwd::sim::d3
