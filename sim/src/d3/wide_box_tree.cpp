// SPDX-License-Identifier: MIT
// Building the four-wide tree (wide_box_tree.h) and checking it.
#include "d3/wide_box_tree.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace rwd::sim::d3 {

void WideBoxTree::clear() {
  nodes_.clear();
  root_ = kNull;
  leaves_ = 0;
}

void WideBoxTree::build(std::span<const Aabb> boxes, std::span<const uint32_t> bodies, Cuts cuts) {
  // The same boxes for the same bodies, bit for bit, build the same tree:
  // a restored world whose static bodies did not change keeps theirs.
  const auto same_bits = [](const auto& kept, const auto& given) {
    return kept.size() == given.size() &&
           (given.empty() || std::memcmp(kept.data(), given.data(), given.size_bytes()) == 0);
  };
  if (root_ != kNull && same_bits(build_boxes_, boxes) && same_bits(build_bodies_, bodies)) return;
  clear();
  const uint32_t count = static_cast<uint32_t>(boxes.size());
  if (count == 0) return;
  build_boxes_.assign(boxes.begin(), boxes.end());
  build_bodies_.assign(bodies.begin(), bodies.end());
  build_items_.resize(count);
  for (uint32_t i = 0; i < count; ++i) build_items_[i] = i;
  // About one node per three leaves.
  nodes_.reserve(count / 3 + 2);
  leaves_ = count;
  Aabb bounds;
  root_ = build_range(build_items_.data(), count, 0, cuts, bounds);
}

// Cuts items[0, n), n >= 2, in two and returns the size of the first part
// (1 to n - 1). The cut is the one of kBins - 1 planes across the widest
// spread of the centres (trying the other axes too doubled the build) that
// least costs a ray walking the two parts (the surface area heuristic:
// each part's area times its leaves), so parts hug the geometry and a ray
// passes few boxes. With `median`, or where every centre coincides, it is
// at the median of the centres along that spread. A function of the input
// alone (ties by body).
uint32_t WideBoxTree::split(uint32_t* items, uint32_t n, bool median) {
  constexpr int kBins = 12;
  float lo[3];
  float hi[3];
  for (int axis = 0; axis < 3; ++axis) lo[axis] = hi[axis] = centre(build_boxes_[items[0]], axis);
  for (uint32_t i = 1; i < n; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const float c = centre(build_boxes_[items[i]], axis);
      lo[axis] = std::min(lo[axis], c);
      hi[axis] = std::max(hi[axis], c);
    }
  }
  int axis = 0;
  if (hi[1] - lo[1] > hi[axis] - lo[axis]) axis = 1;
  if (hi[2] - lo[2] > hi[axis] - lo[axis]) axis = 2;
  const float extent = hi[axis] - lo[axis];
  const float scale = static_cast<float>(kBins) / extent;
  const auto bin_of = [&](uint32_t item) {
    const float c = centre(build_boxes_[item], axis);
    return std::min(kBins - 1, static_cast<int>((c - lo[axis]) * scale));
  };
  int best_plane = 0;  // none: every bin to the left of plane b is [0, b)
  if (!median && extent > 0.0f) {
    uint32_t counts[kBins] = {};
    Aabb boxes[kBins];
    for (uint32_t i = 0; i < n; ++i) {
      const int b = bin_of(items[i]);
      boxes[b] =
          counts[b]++ == 0 ? build_boxes_[items[i]] : merge(boxes[b], build_boxes_[items[i]]);
    }
    // Areas and counts left of each plane, then right of it.
    float left_cost[kBins - 1];
    Aabb left;
    uint32_t left_count = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      if (counts[b] != 0) left = left_count == 0 ? boxes[b] : merge(left, boxes[b]);
      left_count += counts[b];
      left_cost[b] = left_count == 0 ? -1.0f : half_area(left) * static_cast<float>(left_count);
    }
    Aabb right;
    uint32_t right_count = 0;
    float best_cost = std::numeric_limits<float>::infinity();
    for (int b = kBins - 1; b > 0; --b) {
      if (counts[b] != 0) right = right_count == 0 ? boxes[b] : merge(right, boxes[b]);
      right_count += counts[b];
      if (right_count == 0 || left_cost[b - 1] < 0.0f) continue;
      const float cost = left_cost[b - 1] + half_area(right) * static_cast<float>(right_count);
      if (cost < best_cost) {
        best_cost = cost;
        best_plane = b;
      }
    }
  }
  if (best_plane == 0) {
    // The median of the centres along their widest spread.
    const uint32_t half = n / 2;
    std::nth_element(items, items + half, items + n, [&](uint32_t l, uint32_t r) {
      const float cl = centre(build_boxes_[l], axis);
      const float cr = centre(build_boxes_[r], axis);
      return cl < cr || (cl == cr && build_bodies_[l] < build_bodies_[r]);
    });
    return half;
  }
  uint32_t* middle =
      std::partition(items, items + n, [&](uint32_t item) { return bin_of(item) < best_plane; });
  return static_cast<uint32_t>(middle - items);
}

// A node over items[0, count), count >= 1. Four or fewer become its leaves;
// more are cut in two (split) and each part in two again, into four
// children.
uint32_t WideBoxTree::build_range(uint32_t* items, uint32_t count, uint32_t depth, Cuts cuts,
                                  Aabb& bounds) {
  uint32_t* group[kLanes];
  uint32_t size[kLanes];
  uint32_t groups = 0;
  if (count <= kLanes) {
    for (uint32_t i = 0; i < count; ++i) {
      group[i] = items + i;
      size[i] = 1;
    }
    groups = count;
  } else {
    // Two cuts and a cut of each part: four children. A part of one leaf
    // is not cut again, and past kCostDepth levels the cuts are medians
    // (balanced), so the depth stays under kMaxDepth.
    const bool median = cuts == Cuts::kAtMedians || depth >= kCostDepth;
    group[0] = items;
    size[0] = count;
    groups = 1;
    for (uint32_t round = 0; round < 2; ++round) {
      const uint32_t parts = groups;
      for (uint32_t k = 0; k < parts; ++k) {
        if (size[k] < 2) continue;
        const uint32_t first = split(group[k], size[k], median);
        group[groups] = group[k] + first;
        size[groups] = size[k] - first;
        size[k] = first;
        ++groups;
      }
    }
  }

  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  uint32_t children[kLanes];
  Aabb boxes[kLanes];
  for (uint32_t k = 0; k < groups; ++k) {
    if (size[k] == 1) {
      children[k] = kLeaf | build_bodies_[group[k][0]];
      boxes[k] = build_boxes_[group[k][0]];
    } else {
      // nodes_ may grow here: the node is written after.
      children[k] = build_range(group[k], size[k], depth + 1, cuts, boxes[k]);
    }
  }
  Node& node = nodes_[index];
  node.count = groups;
  for (uint32_t k = 0; k < kLanes; ++k) {
    // Unused lanes repeat the first child; their bits are masked off.
    const uint32_t from = k < groups ? k : 0;
    node.child[k] = k < groups ? children[from] : kNull;
    for (int axis = 0; axis < 3; ++axis) {
      node.lower[axis][k] = component(boxes[from].lower, axis);
      node.upper[axis][k] = component(boxes[from].upper, axis);
    }
  }
  bounds = boxes[0];
  for (uint32_t k = 1; k < groups; ++k) bounds = merge(bounds, boxes[k]);
  return index;
}

bool WideBoxTree::valid() const {
  if (root_ == kNull) return leaves_ == 0 && nodes_.empty();
  std::vector<uint32_t> seen;
  const float inf = std::numeric_limits<float>::infinity();
  const Aabb everything{{-inf, -inf, -inf}, {inf, inf, inf}};
  if (!valid_node(root_, everything, 0, seen)) return false;
  if (seen.size() != leaves_) return false;
  std::sort(seen.begin(), seen.end());
  return std::adjacent_find(seen.begin(), seen.end()) == seen.end();
}

bool WideBoxTree::valid_node(uint32_t index, const Aabb& bounds, uint32_t depth,
                             std::vector<uint32_t>& seen) const {
  if (index >= nodes_.size() || depth > kMaxDepth) return false;
  const Node& node = nodes_[index];
  if (node.count == 0 || node.count > kLanes) return false;
  for (uint32_t k = 0; k < node.count; ++k) {
    const Aabb box{{node.lower[0][k], node.lower[1][k], node.lower[2][k]},
                   {node.upper[0][k], node.upper[1][k], node.upper[2][k]}};
    if (!contains(bounds, box)) return false;
    const uint32_t child = node.child[k];
    if (child & kLeaf) {
      seen.push_back(child & ~kLeaf);
    } else if (child <= index || !valid_node(child, box, depth + 1, seen)) {
      return false;
    }
  }
  return true;
}

}  // namespace rwd::sim::d3
