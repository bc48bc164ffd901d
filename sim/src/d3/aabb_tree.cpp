// SPDX-License-Identifier: MIT
// The broadphase's bounding volume hierarchy (aabb_tree.h). Inserts follow
// the surface-area heuristic: a leaf goes down the child whose box grows
// least, paying at each level for the growth of the boxes above it. After
// every insert or removal the path to the root is refitted and rebalanced
// by rotating a child up wherever its sibling is more than one level
// shallower.
#include "d3/aabb_tree.h"

#include <algorithm>

namespace rwd::sim::d3 {

void AabbTree::clear() {
  nodes_.clear();
  root_ = kNull;
  free_ = kNull;
  leaves_ = 0;
}

uint32_t AabbTree::allocate() {
  if (free_ == kNull) {
    nodes_.push_back({});
    free_ = static_cast<uint32_t>(nodes_.size() - 1);
    nodes_[free_].parent = kNull;
  }
  const uint32_t node = free_;
  free_ = nodes_[node].parent;
  nodes_[node] = Node{{}, kNull, kNull, kNull, 0, kNull};
  return node;
}

void AabbTree::release(uint32_t node) {
  nodes_[node].parent = free_;
  nodes_[node].height = -1;
  free_ = node;
}

uint32_t AabbTree::insert(const Aabb& box, uint32_t body) {
  const uint32_t leaf = allocate();
  nodes_[leaf].box = box;
  nodes_[leaf].body = body;
  insert_leaf(leaf);
  ++leaves_;
  return leaf;
}

void AabbTree::remove(uint32_t proxy) {
  remove_leaf(proxy);
  release(proxy);
  --leaves_;
}

void AabbTree::insert_leaf(uint32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  const Aabb box = nodes_[leaf].box;
  uint32_t index = root_;
  while (nodes_[index].child1 != kNull) {
    const Node& node = nodes_[index];
    const float node_area = half_area(node.box);
    const float combined = half_area(merge(node.box, box));
    // Making a new parent of this node and the leaf costs the combined box;
    // going further down costs every box above the growth it takes.
    const float here = combined;
    const float inherited = combined - node_area;
    float down[2];
    const uint32_t children[2] = {node.child1, node.child2};
    for (int c = 0; c < 2; ++c) {
      const Node& child = nodes_[children[c]];
      const float grown = half_area(merge(child.box, box));
      down[c] = (child.child1 == kNull ? grown : grown - half_area(child.box)) + inherited;
    }
    if (here < down[0] && here < down[1]) break;
    index = down[0] <= down[1] ? children[0] : children[1];
  }

  const uint32_t sibling = index;
  const uint32_t old_parent = nodes_[sibling].parent;
  const uint32_t parent = allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].box = merge(box, nodes_[sibling].box);
  nodes_[parent].height = nodes_[sibling].height + 1;
  nodes_[parent].child1 = sibling;
  nodes_[parent].child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  // The new parent itself may be lopsided (a deep sibling beside a leaf).
  refit_upward(parent);
}

void AabbTree::remove_leaf(uint32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const uint32_t parent = nodes_[leaf].parent;
  const uint32_t grand = nodes_[parent].parent;
  const uint32_t sibling =
      nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  release(parent);
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
    return;
  }
  if (nodes_[grand].child1 == parent) {
    nodes_[grand].child1 = sibling;
  } else {
    nodes_[grand].child2 = sibling;
  }
  nodes_[sibling].parent = grand;
  refit_upward(grand);
}

// Walks from `node` to the root, rebalancing and recomputing each box and
// height from the children.
void AabbTree::refit_upward(uint32_t node) {
  while (node != kNull) {
    node = balance(node);
    Node& n = nodes_[node];
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    n.box = merge(c1.box, c2.box);
    n.height = 1 + std::max(c1.height, c2.height);
    node = n.parent;
  }
}

// If one child of `a` is more than one level deeper than the other, the
// deeper child takes a's place and a takes the deeper child's shallower
// grandchild side; returns the node now at a's position.
uint32_t AabbTree::balance(uint32_t a) {
  Node& na = nodes_[a];
  if (na.child1 == kNull || na.height < 2) return a;
  const uint32_t b = na.child1;
  const uint32_t c = na.child2;
  const int32_t tilt = nodes_[c].height - nodes_[b].height;
  if (tilt >= -1 && tilt <= 1) return a;

  // `up` rises to a's place; `stay` is a's other child.
  const bool right_heavy = tilt > 1;
  const uint32_t up = right_heavy ? c : b;
  const uint32_t stay = right_heavy ? b : c;
  Node& nu = nodes_[up];
  const uint32_t f = nu.child1;
  const uint32_t g = nu.child2;

  nu.parent = na.parent;
  na.parent = up;
  if (nu.parent == kNull) {
    root_ = up;
  } else if (nodes_[nu.parent].child1 == a) {
    nodes_[nu.parent].child1 = up;
  } else {
    nodes_[nu.parent].child2 = up;
  }

  // The deeper grandchild stays under `up`; the shallower one moves to `a`
  // beside `stay`.
  const bool f_deeper = nodes_[f].height > nodes_[g].height;
  const uint32_t keep = f_deeper ? f : g;
  const uint32_t give = f_deeper ? g : f;
  nu.child1 = a;
  nu.child2 = keep;
  if (right_heavy) {
    na.child2 = give;
  } else {
    na.child1 = give;
  }
  nodes_[give].parent = a;
  na.box = merge(nodes_[stay].box, nodes_[give].box);
  na.height = 1 + std::max(nodes_[stay].height, nodes_[give].height);
  nu.box = merge(na.box, nodes_[keep].box);
  nu.height = 1 + std::max(na.height, nodes_[keep].height);
  return up;
}

void AabbTree::build(std::span<const Aabb> boxes, std::span<const uint32_t> bodies,
                     std::vector<uint32_t>& proxies) {
  clear();
  const uint32_t count = static_cast<uint32_t>(boxes.size());
  proxies.resize(count);
  if (count == 0) return;
  nodes_.reserve(2 * static_cast<size_t>(count));
  build_leaves_.resize(count);
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t leaf = allocate();
    nodes_[leaf].box = boxes[i];
    nodes_[leaf].body = bodies[i];
    proxies[i] = leaf;
    build_leaves_[i] = leaf;
  }
  leaves_ = count;
  root_ = build_range(build_leaves_.data(), count, kNull);
}

// Splits the leaves at the median of their centres along the widest axis
// of those centres (ties by body, so the split is a function of the input).
uint32_t AabbTree::build_range(uint32_t* leaves, uint32_t count, uint32_t parent) {
  if (count == 1) {
    nodes_[leaves[0]].parent = parent;
    return leaves[0];
  }
  float lo[3] = {centre(nodes_[leaves[0]].box, 0), centre(nodes_[leaves[0]].box, 1),
                 centre(nodes_[leaves[0]].box, 2)};
  float hi[3] = {lo[0], lo[1], lo[2]};
  for (uint32_t i = 1; i < count; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const float c = centre(nodes_[leaves[i]].box, axis);
      lo[axis] = std::min(lo[axis], c);
      hi[axis] = std::max(hi[axis], c);
    }
  }
  int axis = 0;
  if (hi[1] - lo[1] > hi[axis] - lo[axis]) axis = 1;
  if (hi[2] - lo[2] > hi[axis] - lo[axis]) axis = 2;
  const uint32_t half = count / 2;
  std::nth_element(leaves, leaves + half, leaves + count, [&](uint32_t l, uint32_t r) {
    const float cl = centre(nodes_[l].box, axis);
    const float cr = centre(nodes_[r].box, axis);
    return cl < cr || (cl == cr && nodes_[l].body < nodes_[r].body);
  });

  const uint32_t node = allocate();
  const uint32_t left = build_range(leaves, half, node);
  const uint32_t right = build_range(leaves + half, count - half, node);
  Node& n = nodes_[node];
  n.parent = parent;
  n.child1 = left;
  n.child2 = right;
  n.box = merge(nodes_[left].box, nodes_[right].box);
  n.height = 1 + std::max(nodes_[left].height, nodes_[right].height);
  return node;
}

bool AabbTree::valid() const {
  if (root_ == kNull) return leaves_ == 0;
  if (nodes_[root_].parent != kNull) return false;
  uint32_t free_count = 0;
  for (uint32_t f = free_; f != kNull; f = nodes_[f].parent) ++free_count;
  // A full binary tree of n leaves has 2n - 1 nodes.
  if (nodes_.size() - free_count != 2 * static_cast<size_t>(leaves_) - 1) return false;
  return valid_subtree(root_, kNull);
}

bool AabbTree::valid_subtree(uint32_t node, uint32_t parent) const {
  const Node& n = nodes_[node];
  if (n.parent != parent) return false;
  if (n.child1 == kNull) return n.child2 == kNull && n.height == 0;
  if (n.child2 == kNull) return false;
  const Node& c1 = nodes_[n.child1];
  const Node& c2 = nodes_[n.child2];
  if (n.height != 1 + std::max(c1.height, c2.height)) return false;
  if (!contains(n.box, c1.box) || !contains(n.box, c2.box)) return false;
  return valid_subtree(n.child1, node) && valid_subtree(n.child2, node);
}

}  // namespace rwd::sim::d3
