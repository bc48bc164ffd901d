// SPDX-License-Identifier: MIT
#pragma once
// The queries' acceleration: a bounding-box tree over every live, enabled
// body, built top-down by median splits. The first query after the world
// changed brings it up to date: when the same bodies are in it (a step, a
// teleport) the boxes are refitted in place (O(n)); otherwise, and every
// kMaxRefits refits so moved bodies do not leave it loose, it is rebuilt
// (O(n log n)), both into reused buffers. It only ever narrows which bodies get the exact test:
// every query compares its results by (value, body index), so they do not depend on the tree's
// shape or the order it visits bodies in.
#include <cstdint>
#include <vector>

#include "rewind/sim2d/world2d.h"
#include "shape_bounds2d.h"
#include "wmath.h"

namespace rwd::sim2d {

class World2D::QueryCache {
 public:
  struct Item {
    detail::Box2W box;
    uint32_t index = 0;
  };
  struct Node {
    detail::Box2W box;
    uint32_t first = 0;   ///< leaf: items[first, first + count)
    uint32_t count = 0;   ///< 0 for an inner node
    int32_t left = -1;    ///< the lower half of the split (by box centre)
    int32_t right = -1;   ///< the upper half
    uint8_t split_y = 0;  ///< 1: split along y, 0: along x
  };

  /// Whether the tree describes the state at (step_count, edits).
  bool fresh(uint64_t step_count, uint64_t edits) const {
    return built_ && step_count == step_count_ && edits == edits_;
  }
  void build(const World2DState& state, uint64_t edits);

  /// Calls visit(item) for every item whose box overlaps `box`. `visit`
  /// returns the box to keep culling with (so a closest-hit search can
  /// shrink it), or the same box.
  template <class Visit>
  void query(const detail::Box2W& box, Visit&& visit) const {
    if (nodes_.empty()) return;
    detail::Box2W cull = box;
    int32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<size_t>(stack[--top])];
      if (!detail::overlaps(node.box, cull)) continue;
      if (node.count > 0) {
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
          if (detail::overlaps(items_[i].box, cull)) cull = visit(items_[i], cull);
        }
        continue;
      }
      // Depth is at most log2(bodies) + 1 (median splits), far below 64.
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
  }

  /// Calls visit(item, end) for every item whose box the segment
  /// origin..end crosses (a slab-free separating-axis test: multiplies
  /// only). `visit` returns the end to keep culling with, so a closest-hit
  /// search shortens the segment as it finds hits.
  template <class Visit>
  void query_segment(detail::V2 origin, detail::V2 end, Visit&& visit) const {
    if (nodes_.empty()) return;
    int32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<size_t>(stack[--top])];
      if (!segment_crosses(node.box, origin, end)) continue;
      if (node.count > 0) {
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
          if (segment_crosses(items_[i].box, origin, end)) end = visit(items_[i], end);
        }
        continue;
      }
      // The half the segment starts toward first: a closest-hit search
      // finds its hit sooner and culls more with the shortened segment.
      // (The order changes no result: visitors break ties by body index.)
      const detail::W toward = node.split_y ? end.y - origin.y : end.x - origin.x;
      if (toward >= 0) {
        stack[top++] = node.right;
        stack[top++] = node.left;
      } else {
        stack[top++] = node.left;
        stack[top++] = node.right;
      }
    }
  }

  /// Whether the segment a..b touches the box: their bounds overlap and
  /// the box's corners are not all on one side of the segment's line.
  static bool segment_crosses(const detail::Box2W& box, detail::V2 a, detail::V2 b) {
    using namespace detail;
    const Box2W bounds{vmin(a, b), vmax(a, b)};
    if (!overlaps(box, bounds)) return false;
    const V2 d = b - a;
    // |d x (c - a)| <= |d.x| hy + |d.y| hx, with c the centre and h the
    // half extents, everything doubled to stay in whole units.
    const V2 c2 = (box.lower + box.upper) - a - a;
    const V2 h2 = box.upper - box.lower;
    const I128 cross = static_cast<I128>(d.x) * c2.y - static_cast<I128>(d.y) * c2.x;
    const I128 reach = static_cast<I128>(wabs(d.x)) * h2.y + static_cast<I128>(wabs(d.y)) * h2.x;
    return (cross < 0 ? -cross : cross) <= reach;
  }

 private:
  int32_t build_range(uint32_t first, uint32_t count);
  bool refit(const World2DState& state);

  bool built_ = false;
  uint32_t refits_ = 0;
  uint64_t step_count_ = 0;
  uint64_t edits_ = 0;
  std::vector<Item> items_;
  std::vector<Node> nodes_;
};

}  // namespace rwd::sim2d
