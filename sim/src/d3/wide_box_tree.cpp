// SPDX-License-Identifier: MIT
// Building the four-wide tree (wide_box_tree.h) and checking it.
#include "d3/wide_box_tree.h"

#include <algorithm>
#include <limits>

namespace rwd::sim::d3 {
namespace {

float centre(const Aabb& box, int axis) {
  return (component(box.lower, axis) + component(box.upper, axis)) * 0.5f;
}

Aabb merge(const Aabb& a, const Aabb& b) {
  return {{std::min(a.lower.x, b.lower.x), std::min(a.lower.y, b.lower.y),
           std::min(a.lower.z, b.lower.z)},
          {std::max(a.upper.x, b.upper.x), std::max(a.upper.y, b.upper.y),
           std::max(a.upper.z, b.upper.z)}};
}

}  // namespace

void WideBoxTree::clear() {
  nodes_.clear();
  root_ = kNull;
  leaves_ = 0;
}

void WideBoxTree::build(std::span<const Aabb> boxes, std::span<const uint32_t> bodies) {
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
  root_ = build_range(build_items_.data(), count, bounds);
}

// A node over items[0, count), count >= 1. Four or fewer become its leaves;
// more are cut at the median of their centres along the widest axis of
// those centres (ties by body, so the cut is a function of the input), and
// each half again along its own widest axis, into four children.
uint32_t WideBoxTree::build_range(uint32_t* items, uint32_t count, Aabb& bounds) {
  const auto split = [this](uint32_t* first, uint32_t n) {
    float lo[3];
    float hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = hi[axis] = centre(build_boxes_[first[0]], axis);
    }
    for (uint32_t i = 1; i < n; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        const float c = centre(build_boxes_[first[i]], axis);
        lo[axis] = std::min(lo[axis], c);
        hi[axis] = std::max(hi[axis], c);
      }
    }
    int axis = 0;
    if (hi[1] - lo[1] > hi[axis] - lo[axis]) axis = 1;
    if (hi[2] - lo[2] > hi[axis] - lo[axis]) axis = 2;
    const uint32_t half = n / 2;
    std::nth_element(first, first + half, first + n, [&](uint32_t l, uint32_t r) {
      const float cl = centre(build_boxes_[l], axis);
      const float cr = centre(build_boxes_[r], axis);
      return cl < cr || (cl == cr && build_bodies_[l] < build_bodies_[r]);
    });
    return half;
  };

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
    const uint32_t half = split(items, count);
    const uint32_t first_quarter = split(items, half);
    const uint32_t third_quarter = split(items + half, count - half);
    group[0] = items;
    size[0] = first_quarter;
    group[1] = items + first_quarter;
    size[1] = half - first_quarter;
    group[2] = items + half;
    size[2] = third_quarter;
    group[3] = items + half + third_quarter;
    size[3] = count - half - third_quarter;
    groups = kLanes;
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
      children[k] = build_range(group[k], size[k], boxes[k]);
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
  if (!valid_node(root_, everything, seen)) return false;
  if (seen.size() != leaves_) return false;
  std::sort(seen.begin(), seen.end());
  return std::adjacent_find(seen.begin(), seen.end()) == seen.end();
}

bool WideBoxTree::valid_node(uint32_t index, const Aabb& bounds,
                             std::vector<uint32_t>& seen) const {
  if (index >= nodes_.size()) return false;
  const Node& node = nodes_[index];
  if (node.count == 0 || node.count > kLanes) return false;
  for (uint32_t k = 0; k < node.count; ++k) {
    const Aabb box{{node.lower[0][k], node.lower[1][k], node.lower[2][k]},
                   {node.upper[0][k], node.upper[1][k], node.upper[2][k]}};
    if (!contains(bounds, box)) return false;
    const uint32_t child = node.child[k];
    if (child & kLeaf) {
      seen.push_back(child & ~kLeaf);
    } else if (child <= index || !valid_node(child, box, seen)) {
      return false;
    }
  }
  return true;
}

}  // namespace rwd::sim::d3
