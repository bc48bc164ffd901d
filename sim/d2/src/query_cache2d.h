// SPDX-License-Identifier: MIT
#pragma once
// The queries' acceleration: a bounding-box tree over every live, enabled
// body, built top-down by median splits. It is rebuilt whole (O(n log n),
// into reused buffers) by the first query after the world changed, and
// only ever narrows which bodies get the exact test: every query compares
// its results by (value, body index), so they do not depend on the tree's
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
    uint32_t first = 0;  ///< leaf: items[first, first + count)
    uint32_t count = 0;  ///< 0 for an inner node
    int32_t left = -1;
    int32_t right = -1;
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

 private:
  int32_t build_range(uint32_t first, uint32_t count);

  bool built_ = false;
  uint64_t step_count_ = 0;
  uint64_t edits_ = 0;
  std::vector<Item> items_;
  std::vector<Node> nodes_;
};

}  // namespace rwd::sim2d
