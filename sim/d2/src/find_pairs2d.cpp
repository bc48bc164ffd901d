// SPDX-License-Identifier: MIT
// The broadphase: a bounding-box tree over this step's bodies, built by
// median splits, walked against itself. A sweep along one axis met every
// body sharing its column or row (a pyramid's rows, a grid's columns: a
// hundred candidates a body); the tree meets only boxes that overlap.
// The pairs it finds are exactly the overlapping ones, whatever shape the
// tree takes, and they are sorted at the end, so the result depends on the
// state alone.
#include <algorithm>

#include "body_math2d.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

// Bodies per leaf: small enough that a leaf's boxes mostly overlap its
// neighbours', large enough that the tree stays shallow.
constexpr uint32_t kLeafSize = 4;

bool layers_agree(const BodyRecord2D& a, const BodyRecord2D& b) {
  return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
}

Box2W merge(const Box2W& a, const Box2W& b) {
  return {vmin(a.lower, b.lower), vmax(a.upper, b.upper)};
}

// Node `node` over items [first, first + count): a leaf, or split at the
// median box centre along the longer side of the centres' spread. Ties go
// by body index, so the split is one total order's.
void build(StepScratch2D& scratch, uint32_t node, uint32_t first, uint32_t count) {
  auto& items = scratch.broadphase_items;
  Box2W box = items[first].box;
  V2 lo = items[first].box.lower + items[first].box.upper;
  V2 hi = lo;
  bool moves = items[first].moves;
  for (uint32_t i = first + 1; i < first + count; ++i) {
    box = merge(box, items[i].box);
    const V2 c = items[i].box.lower + items[i].box.upper;
    lo = vmin(lo, c);
    hi = vmax(hi, c);
    moves = moves || items[i].moves;
  }
  scratch.tree[node].box = box;
  scratch.tree[node].moves = moves;
  if (count <= kLeafSize) {
    scratch.tree[node].first = first;
    scratch.tree[node].count = count;
    return;
  }
  const bool along_y = (hi.y - lo.y) > (hi.x - lo.x);
  const uint32_t half = count / 2;
  const auto begin = items.begin() + first;
  std::nth_element(
      begin, begin + half, begin + count,
      [along_y](const BroadphaseItem2D& a, const BroadphaseItem2D& b) {
        const W ca = along_y ? a.box.lower.y + a.box.upper.y : a.box.lower.x + a.box.upper.x;
        const W cb = along_y ? b.box.lower.y + b.box.upper.y : b.box.lower.x + b.box.upper.x;
        return ca != cb ? ca < cb : a.index < b.index;
      });
  const uint32_t left = static_cast<uint32_t>(scratch.tree.size());
  scratch.tree.resize(left + 2);
  scratch.tree[node].first = left;
  scratch.tree[node].count = 0;
  build(scratch, left, first, half);
  build(scratch, left + 1, first + half, count - half);
}

class PairCollector {
 public:
  PairCollector(const World2DState& state, StepScratch2D& scratch)
      : state_(state), items_(scratch.broadphase_items), pairs_(scratch.pairs) {}

  void test(const BroadphaseItem2D& a, const BroadphaseItem2D& b) {
    if (!a.moves && !b.moves) return;
    if (!overlaps(a.box, b.box)) return;
    if (!layers_agree(state_.bodies[a.index], state_.bodies[b.index])) return;
    const uint32_t lo = std::min(a.index, b.index);
    const uint32_t hi = std::max(a.index, b.index);
    pairs_.push_back((uint64_t{lo} << 32) | hi);
  }
  void within(const TreeNode2D& leaf) {
    for (uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
      for (uint32_t j = i + 1; j < leaf.first + leaf.count; ++j) test(items_[i], items_[j]);
    }
  }
  void across(const TreeNode2D& x, const TreeNode2D& y) {
    for (uint32_t i = x.first; i < x.first + x.count; ++i) {
      for (uint32_t j = y.first; j < y.first + y.count; ++j) test(items_[i], items_[j]);
    }
  }

 private:
  const World2DState& state_;
  const std::vector<BroadphaseItem2D>& items_;
  std::vector<uint64_t>& pairs_;
};

// Every overlapping pair of items under the root: a node against itself
// visits its children against themselves and each other; two nodes whose
// boxes overlap visit their children's pairs.
void walk(const World2DState& state, StepScratch2D& scratch) {
  const auto& tree = scratch.tree;
  auto& stack = scratch.tree_stack;
  PairCollector collect(state, scratch);
  stack.clear();
  stack.push_back({0, 0});
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    const TreeNode2D& nx = tree[x];
    const TreeNode2D& ny = tree[y];
    // Only pairs with a moving body are kept (PairCollector::test).
    if (!nx.moves && !ny.moves) continue;
    if (x == y) {
      if (nx.count > 0) {
        collect.within(nx);
      } else {
        stack.push_back({nx.first, nx.first});
        stack.push_back({nx.first + 1, nx.first + 1});
        stack.push_back({nx.first, nx.first + 1});
      }
      continue;
    }
    if (!overlaps(nx.box, ny.box)) continue;
    if (nx.count > 0 && ny.count > 0) {
      collect.across(nx, ny);
    } else if (nx.count > 0) {
      stack.push_back({x, ny.first});
      stack.push_back({x, ny.first + 1});
    } else if (ny.count > 0) {
      stack.push_back({nx.first, y});
      stack.push_back({nx.first + 1, y});
    } else {
      stack.push_back({nx.first, ny.first});
      stack.push_back({nx.first, ny.first + 1});
      stack.push_back({nx.first + 1, ny.first});
      stack.push_back({nx.first + 1, ny.first + 1});
    }
  }
}

// Sorts the walk's pairs (lo << 32 | hi, lo < hi < body_count) by key.
// Many pairs: a counting sort by hi, then a stable one by lo, each one pass
// over the pairs and one over the bodies; few: a comparison sort. Either
// gives the one sorted order.
void sort_pairs(std::vector<uint64_t>& pairs, uint32_t body_count, StepScratch2D& scratch) {
  if (pairs.size() < 256 || pairs.size() < body_count / 4) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  auto& counts = scratch.sort_counts;
  auto& other = scratch.sort_buffer;
  other.resize(pairs.size());
  const auto pass = [&](const std::vector<uint64_t>& from, std::vector<uint64_t>& to, int shift) {
    counts.assign(body_count + 1, 0);
    for (const uint64_t key : from) ++counts[((key >> shift) & 0xFFFFFFFFu) + 1];
    for (uint32_t i = 0; i < body_count; ++i) counts[i + 1] += counts[i];
    for (const uint64_t key : from) to[counts[(key >> shift) & 0xFFFFFFFFu]++] = key;
  };
  pass(pairs, other, 0);   // by hi
  pass(other, pairs, 32);  // by lo, keeping hi's order
}

// Body i's entry: its bounds grown by half the speculative distance, and
// whether it moves this step.
BroadphaseItem2D item_of(const BodyRecord2D& body, uint32_t i, W margin) {
  Box2W box = shape_bounds(body.shape, origin_transform(body));
  box.lower -= V2{margin, margin};
  box.upper += V2{margin, margin};
  return {box, i, is_moving(body)};
}

// Refits between rebuilds: boxes that moved loosen the tree a little each
// step; a rebuild every so often keeps it tight.
constexpr uint32_t kMaxRefits = 16;

// Brings the tree over this step's bounds. When the same bodies are in it
// as last step, their boxes are replaced in place and every node's box is
// refitted from its children (O(n)); otherwise, or after kMaxRefits
// refits, it is rebuilt. The tree only narrows which boxes are compared,
// so which of the two happens never changes a pair.
void update_tree(const World2DState& state, StepScratch2D& scratch) {
  const W margin = w_from(state.config.speculative_distance) / 2;
  auto& items = scratch.broadphase_items;
  auto& slot = scratch.item_of_body;
  bool same = scratch.tree_refits < kMaxRefits && !scratch.tree.empty() &&
              slot.size() == state.bodies.size();
  uint32_t live = 0;
  for (uint32_t i = 0; i < state.bodies.size() && same; ++i) {
    const BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled)) continue;
    const uint32_t k = slot[i];
    if (k >= items.size() || items[k].index != i) {
      same = false;
      break;
    }
    items[k] = item_of(body, i, margin);
    ++live;
  }
  if (same && live == items.size()) {
    auto& tree = scratch.tree;
    for (size_t n = tree.size(); n-- > 0;) {  // children come after parents
      TreeNode2D& node = tree[n];
      if (node.count > 0) {
        Box2W box = items[node.first].box;
        bool moves = items[node.first].moves;
        for (uint32_t i = node.first + 1; i < node.first + node.count; ++i) {
          box = merge(box, items[i].box);
          moves = moves || items[i].moves;
        }
        node.box = box;
        node.moves = moves;
      } else {
        node.box = merge(tree[node.first].box, tree[node.first + 1].box);
        node.moves = tree[node.first].moves || tree[node.first + 1].moves;
      }
    }
    ++scratch.tree_refits;
    return;
  }

  items.clear();
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    const BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled)) continue;
    items.push_back(item_of(body, i, margin));
  }
  scratch.tree.clear();
  scratch.tree_refits = 0;
  slot.assign(state.bodies.size(), UINT32_MAX);
  if (items.empty()) return;
  scratch.tree.resize(1);
  build(scratch, 0, 0, static_cast<uint32_t>(items.size()));
  for (uint32_t k = 0; k < items.size(); ++k) slot[items[k].index] = k;
}

}  // namespace

void find_pairs(const World2DState& state, StepScratch2D& scratch) {
  update_tree(state, scratch);

  // Joined bodies that must not collide (collide_connected off).
  // The joined pairs in joint order; sorted again only when they changed
  // since last step (a joint made, destroyed or broken), which in a world
  // of many joints is the rare step.
  auto& listed = scratch.joined_listed;
  listed.clear();
  for (const JointRecord2D& j : state.joints) {
    if (!(j.flags & kJointLive) || (j.flags & (kJointBroken | kJointCollideConnected))) continue;
    listed.push_back((uint64_t{std::min(j.a, j.b)} << 32) | std::max(j.a, j.b));
  }
  auto& joined = scratch.joined_pairs;
  if (listed != scratch.joined_listed_before) {
    joined = listed;
    std::sort(joined.begin(), joined.end());
    scratch.joined_listed_before.swap(listed);
  }

  scratch.pairs.clear();
  if (scratch.broadphase_items.size() < 2) return;
  walk(state, scratch);
  auto& pairs = scratch.pairs;
  sort_pairs(pairs, static_cast<uint32_t>(state.bodies.size()), scratch);
  // Less the joined pairs: both lists sorted, one merge.
  if (joined.empty()) return;
  size_t kept = 0;
  size_t j = 0;
  for (const uint64_t key : pairs) {
    while (j < joined.size() && joined[j] < key) ++j;
    if (j < joined.size() && joined[j] == key) continue;
    pairs[kept++] = key;
  }
  pairs.resize(kept);
}

}  // namespace rwd::sim2d::detail
