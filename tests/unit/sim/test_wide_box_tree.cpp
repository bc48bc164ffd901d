// SPDX-License-Identifier: MIT
// The four-wide tree: well formed after a bulk build of any size, and every
// query visits exactly the leaves the binary tree's same query visits (its
// tests, lane by lane), including rays along an axis and rays on a box's
// face; a nearest-first walk that shortens its reach finds what testing
// every leaf finds.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "d3/aabb_tree.h"
#include "d3/wide_box_tree.h"

namespace rwd::sim::d3 {
namespace {

struct Lcg {
  uint32_t seed = 77;
  float next() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 16777216.0f;
  }
  Vec3 point(float world) { return {next() * world, next() * world, next() * world}; }
  Aabb box(float world, float size) {
    const Vec3 c = point(world);
    const Vec3 h{0.05f + next() * size, 0.05f + next() * size, 0.05f + next() * size};
    return {c - h, c + h};
  }
  // Mostly diagonal directions; one in four runs along an axis or in a
  // plane of two, where the slab test takes its parallel branch.
  Vec3 direction() {
    Vec3 d{next() - 0.5f, next() - 0.5f, next() - 0.5f};
    const uint32_t kind = static_cast<uint32_t>(next() * 8.0f);
    if (kind == 0) d = {0.0f, 0.0f, d.z < 0.0f ? -1.0f : 1.0f};
    if (kind == 1) d.x = 0.0f;
    if (kind == 2) d = {d.x, 0.0f, 0.0f};
    return d;
  }
};

struct Trees {
  std::vector<Aabb> boxes;
  std::vector<uint32_t> bodies;
  AabbTree binary;
  WideBoxTree wide;

  Trees(Lcg& rng, uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
      boxes.push_back(rng.box(20.0f, 1.5f));
      bodies.push_back(3 * i + 1);  // bodies are not the positions
    }
    std::vector<uint32_t> proxies;
    binary.build(boxes, bodies, proxies);
    wide.build(boxes, bodies);
  }
};

template <class Query>
std::vector<uint32_t> visited(Query&& query) {
  std::vector<uint32_t> out;
  query([&](uint32_t body) { out.push_back(body); });
  std::sort(out.begin(), out.end());
  return out;
}

TEST(WideBoxTree, BuildsValidTreesOfAnySize) {
  Lcg rng;
  for (const uint32_t count : {0u, 1u, 2u, 3u, 4u, 5u, 6u, 16u, 17u, 64u, 65u, 1000u, 4099u}) {
    Trees trees(rng, count);
    EXPECT_TRUE(trees.wide.valid()) << count;
    EXPECT_EQ(trees.wide.leaf_count(), count);
    // The whole world's box reaches every leaf exactly once.
    const std::vector<uint32_t> all = visited([&](auto visit) {
      trees.wide.query({{-100.0f, -100.0f, -100.0f}, {100.0f, 100.0f, 100.0f}}, visit);
    });
    std::vector<uint32_t> expected = trees.bodies;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(all, expected) << count;
  }
  WideBoxTree tree;
  EXPECT_TRUE(tree.valid());
  tree.clear();
  EXPECT_EQ(tree.leaf_count(), 0u);
}

TEST(WideBoxTree, ABuildOfTheSameBoxesKeepsTheTreeAndAnyChangeRebuildsIt) {
  Lcg rng;
  std::vector<Aabb> boxes;
  std::vector<uint32_t> bodies;
  for (uint32_t i = 0; i < 500; ++i) {
    boxes.push_back(rng.box(20.0f, 1.0f));
    bodies.push_back(i);
  }
  for (const auto cuts : {WideBoxTree::Cuts::kByArea, WideBoxTree::Cuts::kAtMedians}) {
    WideBoxTree tree;
    tree.build(boxes, bodies, cuts);
    const Aabb probe = boxes[77];
    const auto before = visited([&](auto v) { tree.query(probe, v); });
    tree.build(boxes, bodies, cuts);  // the same input: kept
    EXPECT_TRUE(tree.valid());
    EXPECT_EQ(visited([&](auto v) { tree.query(probe, v); }), before);
    // Box 77 moved 100 m along x: found there, no longer where it was.
    std::vector<Aabb> moved = boxes;
    moved[77].lower = moved[77].lower + Vec3{100.0f, 0.0f, 0.0f};
    moved[77].upper = moved[77].upper + Vec3{100.0f, 0.0f, 0.0f};
    tree.build(moved, bodies, cuts);
    const auto there = visited([&](auto v) { tree.query(moved[77], v); });
    EXPECT_TRUE(std::binary_search(there.begin(), there.end(), 77u));
    const auto gone = visited([&](auto v) { tree.query(probe, v); });
    EXPECT_FALSE(std::binary_search(gone.begin(), gone.end(), 77u));
    // Then its upper x one ulp lower: a probe touching only that face (at
    // the old coordinate) no longer finds it, so a change of one ulp rebuilds.
    const Aabb face{{moved[77].upper.x, moved[77].lower.y, moved[77].lower.z}, moved[77].upper};
    const auto touching = visited([&](auto v) { tree.query(face, v); });
    EXPECT_TRUE(std::binary_search(touching.begin(), touching.end(), 77u));
    moved[77].upper.x = std::nextafter(moved[77].upper.x, 0.0f);
    tree.build(moved, bodies, cuts);
    EXPECT_TRUE(tree.valid());
    const auto apart = visited([&](auto v) { tree.query(face, v); });
    EXPECT_FALSE(std::binary_search(apart.begin(), apart.end(), 77u));
    // Fewer bodies: rebuilt, the missing one gone.
    tree.build(std::span(boxes).first(400), std::span(bodies).first(400), cuts);
    EXPECT_EQ(tree.leaf_count(), 400u);
    EXPECT_TRUE(tree.valid());
  }
}

TEST(WideBoxTree, LopsidedAndCoincidentBoxesStayWithinTheWalksDepth) {
  // Boxes ever farther apart along a line (each cut by area leaves one box
  // on its own) and boxes all in one place (no plane separates them).
  std::vector<Aabb> line;
  std::vector<Aabb> heap;
  std::vector<uint32_t> bodies;
  float x = 0.0f;
  for (uint32_t i = 0; i < 3000; ++i) {
    line.push_back({{x, 0.0f, 0.0f}, {x + 0.5f, 0.5f, 0.5f}});
    heap.push_back({{1.0f, 1.0f, 1.0f}, {2.0f, 2.0f, 2.0f}});
    bodies.push_back(i);
    x = x * 1.01f + 1.0f;
  }
  for (const auto* boxes : {&line, &heap}) {
    WideBoxTree tree;
    tree.build(*boxes, bodies);
    EXPECT_TRUE(tree.valid());
    const Aabb probe = (*boxes)[1234];
    const auto found = visited([&](auto v) { tree.query(probe, v); });
    EXPECT_TRUE(std::binary_search(found.begin(), found.end(), 1234u));
  }
}

TEST(WideBoxTree, BoxRayAndSweepQueriesVisitWhatTheBinaryTreeVisits) {
  Lcg rng;
  Trees trees(rng, 3000);
  int nonempty = 0;
  for (int q = 0; q < 3000; ++q) {
    const Aabb box = rng.box(20.0f, 2.0f);
    const auto wide_box = visited([&](auto v) { trees.wide.query(box, v); });
    const auto binary_box = visited([&](auto v) { trees.binary.query(box, v); });
    ASSERT_EQ(wide_box, binary_box) << q;

    const Vec3 origin = rng.point(20.0f);
    const Vec3 dir = rng.direction();
    const float max_t = 0.5f + rng.next() * 30.0f;
    const auto wide_ray = visited([&](auto v) { trees.wide.ray_query(origin, dir, max_t, v); });
    const auto binary_ray = visited([&](auto v) { trees.binary.ray_query(origin, dir, max_t, v); });
    ASSERT_EQ(wide_ray, binary_ray) << q;

    const Aabb start = rng.box(20.0f, 0.5f);
    const Vec3 move = rng.direction() * (rng.next() * 15.0f);
    const auto wide_sweep = visited([&](auto v) { trees.wide.sweep_query(start, move, v); });
    const auto binary_sweep = visited([&](auto v) { trees.binary.sweep_query(start, move, v); });
    ASSERT_EQ(wide_sweep, binary_sweep) << q;
    nonempty += !wide_box.empty() + !wide_ray.empty() + !wide_sweep.empty();
  }
  EXPECT_GT(nonempty, 3000);  // the queries meet boxes, not only empty space
}

TEST(WideBoxTree, RaysAlongABoxFaceVisitWhatTheBinaryTreeVisits) {
  // Boxes on a unit grid, rays along the axes exactly on their faces and
  // edges: the parallel-axis branch decides on equal coordinates.
  std::vector<Aabb> boxes;
  std::vector<uint32_t> bodies;
  for (int x = 0; x < 8; ++x) {
    for (int y = 0; y < 8; ++y) {
      const Vec3 lo{static_cast<float>(x), static_cast<float>(y), 0.0f};
      boxes.push_back({lo, lo + Vec3{1.0f, 1.0f, 1.0f}});
      bodies.push_back(static_cast<uint32_t>(boxes.size()));
    }
  }
  AabbTree binary;
  std::vector<uint32_t> proxies;
  binary.build(boxes, bodies, proxies);
  WideBoxTree wide;
  wide.build(boxes, bodies);
  for (int k = 0; k <= 16; ++k) {
    const float c = 0.5f * static_cast<float>(k);
    for (const Vec3 dir : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, -1}}) {
      const Vec3 origin = dir.x != 0.0f   ? Vec3{-1.0f, c, 1.0f}
                          : dir.y != 0.0f ? Vec3{c, -1.0f, 0.0f}
                                          : Vec3{c, c, 3.0f};
      const auto w = visited([&](auto v) { wide.ray_query(origin, dir, 20.0f, v); });
      const auto b = visited([&](auto v) { binary.ray_query(origin, dir, 20.0f, v); });
      EXPECT_EQ(w, b) << k;
      EXPECT_FALSE(w.empty()) << k;
    }
  }
}

TEST(WideBoxTree, NearestWalksFindWhatTestingEveryLeafFinds) {
  Lcg rng;
  Trees trees(rng, 2000);
  // Stand-in shapes: a leaf's "hit" lies somewhere inside its box along the
  // segment, from where the segment enters it.
  const auto hit_in_box = [](const SegmentSlabs& slabs, const Aabb& box, float max_t, uint32_t body,
                             float& t) {
    if (!slabs.enters(box, max_t, t)) return false;
    t += 0.01f * static_cast<float>(body % 5);
    return t <= max_t;
  };
  // Leaves the nearest-first walks visited, and leaves their segments touch.
  int nearest_visits = 0;
  int touched = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec3 origin = rng.point(20.0f);
    const Vec3 dir = rng.direction();
    const float max_t = 1.0f + rng.next() * 25.0f;
    const SegmentSlabs slabs(origin, dir);
    uint32_t best = 0xFFFFFFFFu;
    float best_t = max_t;
    for (size_t i = 0; i < trees.boxes.size(); ++i) {
      float t = 0.0f;
      const uint32_t body = trees.bodies[i];
      if (!hit_in_box(slabs, trees.boxes[i], max_t, body, t)) continue;
      if (t < best_t || (t == best_t && body < best)) {
        best = body;
        best_t = t;
      }
    }
    uint32_t found = 0xFFFFFFFFu;
    float reach = max_t;
    trees.wide.ray_query_nearest(origin, dir, reach, [&](uint32_t body) {
      ++nearest_visits;
      const size_t i = (body - 1) / 3;
      float t = 0.0f;
      if (!hit_in_box(slabs, trees.boxes[i], max_t, body, t)) return;
      if (t > reach || (t == reach && found != 0xFFFFFFFFu && body > found)) return;
      found = body;
      reach = t;
    });
    ASSERT_EQ(found, best) << q;
    if (best != 0xFFFFFFFFu) {
      EXPECT_EQ(reach, best_t) << q;
    }
    trees.wide.ray_query(origin, dir, max_t, [&](uint32_t) { ++touched; });
  }
  // The reach cut short at each hit skips leaves: the walks visit fewer
  // than the segments touch.
  EXPECT_LT(nearest_visits, touched);
}

}  // namespace
}  // namespace rwd::sim::d3
