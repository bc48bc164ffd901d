// SPDX-License-Identifier: MIT
#pragma once
// A bounding volume hierarchy of axis-aligned boxes: leaves are bodies,
// every inner node bounds its two children. It supports both ways a
// broadphase keeps one:
//   - incremental (insert, remove): inserts descend by the surface-area
//     cost and the path back up is kept height-balanced by rotations, so
//     the tree stays shallow however leaves arrive;
//   - bulk (build): a top-down median split, for geometry that changes
//     rarely (static bodies).
// The tree is working memory only. Its shape depends on the order of past
// edits, so nothing that reaches the state may depend on it: callers use it
// to find candidates and then decide on exact boxes, and sort what they
// keep (broadphase.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

struct Aabb {
  Vec3 lower;
  Vec3 upper;
};

inline bool overlaps(const Aabb& a, const Aabb& b) {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y && a.lower.z <= b.upper.z && b.lower.z <= a.upper.z;
}

/// The smallest box holding both.
inline Aabb merge(const Aabb& a, const Aabb& b) {
  return {{std::min(a.lower.x, b.lower.x), std::min(a.lower.y, b.lower.y),
           std::min(a.lower.z, b.lower.z)},
          {std::max(a.upper.x, b.upper.x), std::max(a.upper.y, b.upper.y),
           std::max(a.upper.z, b.upper.z)}};
}

/// Half the surface area: the cost of a box in the surface area heuristic
/// (the chance that a random query ray or box meets it).
inline float half_area(const Aabb& a) {
  const float x = a.upper.x - a.lower.x;
  const float y = a.upper.y - a.lower.y;
  const float z = a.upper.z - a.lower.z;
  return x * y + y * z + z * x;
}

/// The box's centre along `axis` (0, 1, 2).
inline float centre(const Aabb& box, int axis) {
  return (component(box.lower, axis) + component(box.upper, axis)) * 0.5f;
}

inline bool contains(const Aabb& outer, const Aabb& inner) {
  return outer.lower.x <= inner.lower.x && outer.lower.y <= inner.lower.y &&
         outer.lower.z <= inner.lower.z && inner.upper.x <= outer.upper.x &&
         inner.upper.y <= outer.upper.y && inner.upper.z <= outer.upper.z;
}

struct SegmentSlabs;

class AabbTree {
 public:
  static constexpr uint32_t kNull = 0xFFFFFFFFu;

  /// Removes every leaf; capacity is kept.
  void clear();

  /// Adds a leaf for `body` bounded by `box`; returns its proxy (stable
  /// until removed).
  uint32_t insert(const Aabb& box, uint32_t body);
  void remove(uint32_t proxy);
  const Aabb& box(uint32_t proxy) const { return nodes_[proxy].box; }

  /// Replaces the tree by one built top-down over `boxes[i]` for
  /// `bodies[i]`; proxies[i] receives each leaf's proxy.
  void build(std::span<const Aabb> boxes, std::span<const uint32_t> bodies,
             std::vector<uint32_t>& proxies);

  /// Calls visit(body) for every leaf whose box overlaps `box`, in tree
  /// order (callers must not depend on that order).
  template <typename Visit>
  void query(const Aabb& box, Visit&& visit) const;

  /// Calls visit(body) for every leaf whose box the segment origin +
  /// t * dir, 0 <= t <= max_t, touches (slab test; in tree order).
  template <typename Visit>
  void ray_query(Vec3 origin, Vec3 dir, float max_t, Visit&& visit) const;
  /// For the closest hit: visits leaves near to far (each node's nearer
  /// child first) and skips every node the segment reaches only past
  /// `reach`, which visit(body) may shorten as it finds hits. A leaf is
  /// skipped only when its box starts past the reach by a margin far above
  /// the rounding of the box test, so every leaf whose exact hit lies
  /// within the reach is still visited: a caller keeping the nearest hit
  /// (ties to the lower id) gets what visiting every leaf would give.
  template <typename Visit>
  void ray_query_nearest(Vec3 origin, Vec3 dir, float& reach, Visit&& visit) const;
  /// The same for the box `start` moving along `translation` (reach a
  /// fraction of it, as sweep_query tests its boxes): for the closest hit
  /// of a shape cast.
  template <typename Visit>
  void sweep_query_nearest(const Aabb& start, Vec3 translation, float& reach, Visit&& visit) const;

  /// Calls visit(body) for every leaf whose box the box `start` touches
  /// somewhere on its way along `translation` (the segment of its centre
  /// against each box grown by its half size; in tree order). Far tighter
  /// than the bounds of the whole sweep when the sweep runs diagonally.
  template <typename Visit>
  void sweep_query(const Aabb& start, Vec3 translation, Visit&& visit) const;

 private:
  // The near-to-far walk of ray_query_nearest and sweep_query_nearest: the
  // segment against every box grown by `grow` (zero for a ray, which then
  // sees the boxes exactly).
  template <bool kGrow, typename Visit>
  void nearest_walk(const SegmentSlabs& slabs, Vec3 grow, float& reach, Visit&& visit) const;

 public:
  uint32_t leaf_count() const { return leaves_; }
  /// Longest root-to-leaf path (0 for one leaf, -1 when empty).
  int32_t height() const { return root_ == kNull ? -1 : nodes_[root_].height; }
  /// Checks parent links, heights, the node count and that every inner
  /// box bounds its children; for tests.
  bool valid() const;

 private:
  struct Node {
    Aabb box;
    uint32_t parent;  ///< or the next free node
    uint32_t child1;  ///< kNull for a leaf
    uint32_t child2;
    int32_t height;  ///< 0 for a leaf, -1 for a free node
    uint32_t body;
  };

  uint32_t allocate();
  void release(uint32_t node);
  void insert_leaf(uint32_t leaf);
  void remove_leaf(uint32_t leaf);
  uint32_t balance(uint32_t a);
  void refit_upward(uint32_t node);
  uint32_t build_range(uint32_t* leaves, uint32_t count, uint32_t parent);
  /// Visits the leaves under every node whose box `accept` takes.
  template <typename Accept, typename Visit>
  void walk(Accept&& accept, Visit&& visit) const;
  bool valid_subtree(uint32_t node, uint32_t parent) const;

  std::vector<Node> nodes_;
  std::vector<uint32_t> build_leaves_;
  uint32_t root_ = kNull;
  uint32_t free_ = kNull;
  uint32_t leaves_ = 0;
};

template <typename Accept, typename Visit>
void AabbTree::walk(Accept&& accept, Visit&& visit) const {
  if (root_ == kNull) return;
  // A depth-first walk holds at most one entry per level plus one. Rotations
  // keep the tree shallow (tens of levels for millions of leaves), so the
  // stack lives on the call stack unless a tree is pathologically deep.
  uint32_t local[128];
  std::vector<uint32_t> deep;
  uint32_t* stack = local;
  if (nodes_[root_].height + 2 > 128) {
    deep.resize(static_cast<size_t>(nodes_[root_].height) + 2);
    stack = deep.data();
  }
  uint32_t top = 0;
  stack[top++] = root_;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!accept(node.box)) continue;
    if (node.child1 == kNull) {
      visit(node.body);
    } else {
      stack[top++] = node.child1;
      stack[top++] = node.child2;
    }
  }
}

template <typename Visit>
void AabbTree::query(const Aabb& box, Visit&& visit) const {
  walk([&box](const Aabb& node) { return overlaps(node, box); }, visit);
}

// The segment origin + t dir against boxes, set up once per query: the
// reciprocal direction, and which axes the segment runs parallel to (their
// slab test is whether the origin lies between the planes; none, in most
// queries, which then take no branch per axis).
struct SegmentSlabs {
  Vec3 origin;
  Vec3 inv_dir;
  bool parallel[3] = {false, false, false};
  bool any_parallel = false;

  SegmentSlabs(Vec3 from, Vec3 dir)
      : origin(from), inv_dir{1.0f / dir.x, 1.0f / dir.y, 1.0f / dir.z} {
    for (int i = 0; i < 3; ++i) {
      parallel[i] = !std::isfinite(component(inv_dir, i));
      any_parallel = any_parallel || parallel[i];
    }
  }

  // The part [t_lo, t_hi] of the segment, t in [0, max_t], within the
  // closed box; false when none. Each axis narrows the range by its slab;
  // max and min are exact, so the order of the axes and of the comparisons
  // changes neither answer.
  bool interval(const Aabb& box, float max_t, float& t_lo, float& t_hi) const {
    t_lo = 0.0f;
    t_hi = max_t;
    for (int i = 0; i < 3; ++i) {
      const float o = component(origin, i);
      const float lo = component(box.lower, i);
      const float hi = component(box.upper, i);
      if (any_parallel && parallel[i]) {
        if (o < lo || o > hi) return false;
        continue;
      }
      const float inv = component(inv_dir, i);
      const float t0 = (lo - o) * inv;
      const float t1 = (hi - o) * inv;
      t_lo = std::max(t_lo, std::min(t0, t1));
      t_hi = std::min(t_hi, std::max(t0, t1));
    }
    return t_lo <= t_hi;
  }
  // Whether the segment touches the box, and from which t (entry; 0 when
  // the origin is inside).
  bool enters(const Aabb& box, float max_t, float& entry) const {
    float exit = 0.0f;
    return interval(box, max_t, entry, exit);
  }
  bool hits(const Aabb& box, float max_t) const {
    float entry = 0.0f;
    return enters(box, max_t, entry);
  }
};

// A box `start` moving along `translation`, as the sweep queries test it:
// the segment of its centre against every box grown by its half size.
struct SweptBox {
  SweptBox(const Aabb& start, Vec3 translation)
      : slabs((start.lower + start.upper) * 0.5f, translation),
        half((start.upper - start.lower) * 0.5f) {}
  SegmentSlabs slabs;
  Vec3 half;
};

template <typename Visit>
void AabbTree::ray_query(Vec3 origin, Vec3 dir, float max_t, Visit&& visit) const {
  const SegmentSlabs slabs(origin, dir);
  walk([&](const Aabb& node) { return slabs.hits(node, max_t); }, visit);
}

template <bool kGrow, typename Visit>
void AabbTree::nearest_walk(const SegmentSlabs& slabs, Vec3 grow, float& reach,
                            Visit&& visit) const {
  if (root_ == kNull) return;
  // The skip margin: a thousandth of the reach and a millimetre, where the
  // box test's rounding is a few ulps of the coordinates.
  const auto padded = [](float t) { return t + 1e-3f * t + 1e-3f; };
  const auto enters = [&](const Aabb& box, float& t) {
    if constexpr (kGrow) {
      return slabs.enters({box.lower - grow, box.upper + grow}, padded(reach), t);
    } else {
      return slabs.enters(box, padded(reach), t);
    }
  };
  struct Entry {
    uint32_t node;
    float t;  ///< where the segment enters the node's box
  };
  Entry local[128];
  std::vector<Entry> deep;
  Entry* stack = local;
  if (nodes_[root_].height + 2 > 128) {
    deep.resize(static_cast<size_t>(nodes_[root_].height) + 2);
    stack = deep.data();
  }
  uint32_t top = 0;
  float t_root = 0.0f;
  if (!enters(nodes_[root_].box, t_root)) return;
  stack[top++] = {root_, t_root};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.t > padded(reach)) continue;  // the reach shrank since it was pushed
    const Node& node = nodes_[e.node];
    if (node.child1 == kNull) {
      visit(node.body);
      continue;
    }
    float t1 = 0.0f;
    float t2 = 0.0f;
    const bool in1 = enters(nodes_[node.child1].box, t1);
    const bool in2 = enters(nodes_[node.child2].box, t2);
    // The nearer child is pushed last, so it is walked first.
    if (in1 && in2) {
      if (t1 <= t2) {
        stack[top++] = {node.child2, t2};
        stack[top++] = {node.child1, t1};
      } else {
        stack[top++] = {node.child1, t1};
        stack[top++] = {node.child2, t2};
      }
    } else if (in1) {
      stack[top++] = {node.child1, t1};
    } else if (in2) {
      stack[top++] = {node.child2, t2};
    }
  }
}

template <typename Visit>
void AabbTree::ray_query_nearest(Vec3 origin, Vec3 dir, float& reach, Visit&& visit) const {
  nearest_walk<false>(SegmentSlabs(origin, dir), {}, reach, visit);
}

template <typename Visit>
void AabbTree::sweep_query_nearest(const Aabb& start, Vec3 translation, float& reach,
                                   Visit&& visit) const {
  const SweptBox swept(start, translation);
  nearest_walk<true>(swept.slabs, swept.half, reach, visit);
}

template <typename Visit>
void AabbTree::sweep_query(const Aabb& start, Vec3 translation, Visit&& visit) const {
  const SweptBox swept(start, translation);
  walk(
      [&](const Aabb& node) {
        return swept.slabs.hits({node.lower - swept.half, node.upper + swept.half}, 1.0f);
      },
      visit);
}

}  // namespace rwd::sim::d3
