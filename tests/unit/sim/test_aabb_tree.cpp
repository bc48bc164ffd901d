// SPDX-License-Identifier: MIT
// The broadphase's AABB tree: after any mix of inserts and removals, and
// after a bulk build, the tree is well formed and a query reports exactly
// the leaves a brute-force scan finds.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "d3/aabb_tree.h"

namespace rwd::sim::d3 {
namespace {

struct Lcg {
  uint32_t seed = 2024;
  float next() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 16777216.0f;
  }
  Aabb box(float world, float size) {
    const Vec3 c{next() * world, next() * world, next() * world};
    const Vec3 h{0.05f + next() * size, 0.05f + next() * size, 0.05f + next() * size};
    return {c - h, c + h};
  }
};

std::vector<uint32_t> queried(const AabbTree& tree, const Aabb& box) {
  std::vector<uint32_t> out;
  tree.query(box, [&](uint32_t body) { out.push_back(body); });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<uint32_t> brute(const std::vector<Aabb>& boxes, const std::vector<bool>& live,
                            const Aabb& box) {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < boxes.size(); ++i) {
    if (live[i] && overlaps(boxes[i], box)) out.push_back(i);
  }
  return out;
}

TEST(AabbTree, InsertRemoveKeepsTreeValidAndQueriesExact) {
  Lcg rng;
  AabbTree tree;
  const uint32_t n = 600;
  std::vector<Aabb> boxes(n);
  std::vector<bool> live(n, false);
  std::vector<uint32_t> proxy(n, AabbTree::kNull);
  for (int round = 0; round < 4000; ++round) {
    const uint32_t i = static_cast<uint32_t>(rng.next() * n) % n;
    if (live[i]) {
      tree.remove(proxy[i]);
      live[i] = false;
    } else {
      boxes[i] = rng.box(20.0f, 1.0f);
      proxy[i] = tree.insert(boxes[i], i);
      live[i] = true;
    }
    if (round % 250 == 0) {
      ASSERT_TRUE(tree.valid()) << round;
    }
  }
  ASSERT_TRUE(tree.valid());
  const auto count = static_cast<uint32_t>(std::count(live.begin(), live.end(), true));
  EXPECT_EQ(tree.leaf_count(), count);
  // Balanced: far below the leaf count (a list would be count - 1 deep).
  EXPECT_LE(tree.height(), 24);
  for (int q = 0; q < 200; ++q) {
    const Aabb box = rng.box(20.0f, 3.0f);
    ASSERT_EQ(queried(tree, box), brute(boxes, live, box)) << q;
  }
}

TEST(AabbTree, BulkBuildThenEditsStaysExact) {
  Lcg rng;
  const uint32_t n = 1000;
  std::vector<Aabb> boxes(n);
  std::vector<uint32_t> bodies(n);
  for (uint32_t i = 0; i < n; ++i) {
    boxes[i] = rng.box(50.0f, 2.0f);
    bodies[i] = i;
  }
  AabbTree tree;
  std::vector<uint32_t> proxies;
  tree.build(boxes, bodies, proxies);
  ASSERT_TRUE(tree.valid());
  EXPECT_EQ(tree.height(), 10);  // median splits: ceil(log2 1000)
  std::vector<bool> live(n, true);
  for (uint32_t i = 0; i < n; i += 3) {
    tree.remove(proxies[i]);
    live[i] = false;
  }
  ASSERT_TRUE(tree.valid());
  for (int q = 0; q < 200; ++q) {
    const Aabb box = rng.box(50.0f, 5.0f);
    ASSERT_EQ(queried(tree, box), brute(boxes, live, box)) << q;
  }
  // An empty build leaves an empty tree that answers nothing.
  tree.build({}, {}, proxies);
  EXPECT_TRUE(tree.valid());
  EXPECT_EQ(tree.height(), -1);
  EXPECT_TRUE(queried(tree, boxes[0]).empty());
}

}  // namespace
}  // namespace rwd::sim::d3
