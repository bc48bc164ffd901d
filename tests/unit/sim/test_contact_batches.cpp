// SPDX-License-Identifier: MIT
// Contact batches (contact_batches.h): the constraints come out ordered by
// colour, within a colour by point count (most first) and then by index,
// with the overflow last in index order, exactly as a plain stable sort of
// the colouring puts them, for counts on both sides of the small-world
// insertion sort's bound; each colour starts where color_start says; every
// constraint sits in one lane that names it back; and no two lanes of a
// coloured batch share a body that can move.
#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "d3/contact_batches.h"
#include "d3/world_scratch.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

// Solver bodies: 0 the shared immovable body, then `movable` bodies that
// move and `fixed` that do not (static or kinematic: no inverse mass).
void add_bodies(WorldScratch& s, uint32_t movable, uint32_t fixed) {
  SolverBody immovable{};
  immovable.delta_rotation = Quat{};
  immovable.inv_inertia = mat3_zero();
  s.solver_bodies.assign(1, immovable);
  for (uint32_t i = 0; i < movable + fixed; ++i) {
    SolverBody b = immovable;
    if (i < movable) {
      b.inv_mass = 0.5f;
      b.push_inv_mass = 0.5f;
      b.inv_inertia = Mat3{};
    }
    s.solver_bodies.push_back(b);
  }
}

// A constraint between solver bodies a and b with `points` points.
ContactConstraint make_constraint(test::Rng& rng, uint32_t a, uint32_t b, uint32_t points) {
  ContactConstraint c{};
  c.body_a = a;
  c.body_b = b;
  c.point_count = points;
  c.normal = {0.0f, 1.0f, 0.0f};
  c.tangent1 = {1.0f, 0.0f, 0.0f};
  c.tangent2 = {0.0f, 0.0f, 1.0f};
  c.friction = 0.5f;
  for (uint32_t p = 0; p < points; ++p) {
    c.points[p].anchor_a = {rng.uniform(-1.0f, 1.0f), -0.5f, rng.uniform(-1.0f, 1.0f)};
    c.points[p].anchor_b = {rng.uniform(-1.0f, 1.0f), 0.5f, rng.uniform(-1.0f, 1.0f)};
  }
  return c;
}

// The order the batches must follow: each constraint coloured in index
// order as the solver colours them, then stably sorted by colour and, within
// a colour, by point count, most first (the overflow, colour kColorCount,
// keeps index order).
std::vector<uint32_t> reference_order(const WorldScratch& s, std::vector<uint32_t>& colour) {
  const size_t words = (s.solver_bodies.size() + 63) / 64;
  std::vector<uint64_t> bits(words * kColorCount, 0);
  const uint32_t count = static_cast<uint32_t>(s.constraints.size());
  colour.assign(count, 0);
  for (uint32_t k = 0; k < count; ++k) {
    const ContactConstraint& c = s.constraints[k];
    colour[k] = take_color(bits.data(), words, c.body_a, s.solver_bodies[c.body_a].inv_mass != 0.0f,
                           c.body_b, s.solver_bodies[c.body_b].inv_mass != 0.0f);
  }
  std::vector<uint32_t> order(count);
  for (uint32_t k = 0; k < count; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
    if (colour[x] != colour[y]) return colour[x] < colour[y];
    if (colour[x] == kColorCount) return false;
    return s.constraints[x].point_count > s.constraints[y].point_count;
  });
  return order;
}

void check_batches(WorldScratch& s) {
  std::vector<uint32_t> colour;
  const std::vector<uint32_t> expected = reference_order(s, colour);
  build_batches(s);
  const uint32_t count = static_cast<uint32_t>(s.constraints.size());
  ASSERT_EQ(s.colored, expected);
  ASSERT_EQ(s.color_start.size(), kColorCount + 2);
  for (uint32_t col = 0; col <= kColorCount; ++col) {
    const auto first = std::find_if(expected.begin(), expected.end(),
                                    [&](uint32_t k) { return colour[k] >= col; });
    EXPECT_EQ(s.color_start[col], static_cast<uint32_t>(first - expected.begin())) << col;
  }
  EXPECT_EQ(s.color_start[kColorCount + 1], count);
  // Every constraint in exactly one lane, which names it back.
  std::vector<int> seen(count, 0);
  for (uint32_t k = 0; k < s.batches.size(); ++k) {
    const ContactBatch& b = s.batches[k];
    std::set<uint32_t> moving;
    for (int lane = 0; lane < kBatchLanes; ++lane) {
      const uint32_t index = b.constraint[lane];
      if (index == kNoConstraint) continue;
      ASSERT_LT(index, count);
      ++seen[index];
      EXPECT_EQ(s.constraints[index].batch, k);
      EXPECT_EQ(s.constraints[index].lane, static_cast<uint32_t>(lane));
      const ContactConstraint& c = s.constraints[index];
      for (const uint32_t body : {c.body_a, c.body_b}) {
        if (s.solver_bodies[body].inv_mass == 0.0f) continue;
        EXPECT_TRUE(moving.insert(body).second) << "batch " << k << " lane " << lane;
      }
    }
  }
  for (uint32_t k = 0; k < count; ++k) EXPECT_EQ(seen[k], 1) << k;
}

TEST(ContactBatches, OrderIsAStableSortOfTheColouringAtEveryCount) {
  test::Rng rng{2024};
  // Up to 40 constraints among 12 movable and 3 fixed bodies: the small
  // worlds' insertion sort (16 or fewer) and the bucket table beyond it.
  for (uint32_t count = 0; count <= 40; ++count) {
    for (int trial = 0; trial < 20; ++trial) {
      WorldScratch s;
      add_bodies(s, 12, 3);
      const uint32_t bodies = static_cast<uint32_t>(s.solver_bodies.size());
      for (uint32_t k = 0; k < count; ++k) {
        uint32_t a = static_cast<uint32_t>(rng.next() % bodies);
        uint32_t b = static_cast<uint32_t>(rng.next() % bodies);
        if (a == b) b = (a + 1) % bodies;
        if (s.solver_bodies[a].inv_mass == 0.0f && s.solver_bodies[b].inv_mass == 0.0f) {
          b = 1 + static_cast<uint32_t>(rng.next() % 12);  // a movable one
        }
        const uint32_t points = 1 + static_cast<uint32_t>(rng.next() % kMaxManifoldPoints);
        s.constraints.push_back(make_constraint(rng, std::min(a, b), std::max(a, b), points));
      }
      SCOPED_TRACE(testing::Message() << "count " << count << " trial " << trial);
      check_batches(s);
      if (HasFatalFailure()) return;
    }
  }
}

TEST(ContactBatches, ABodyInMoreContactsThanColoursOverflowsInIndexOrder) {
  test::Rng rng{7};
  WorldScratch s;
  add_bodies(s, 40, 0);
  // Body 1 touches 35 others: 24 colours, then the overflow.
  for (uint32_t k = 0; k < 35; ++k) {
    s.constraints.push_back(
        make_constraint(rng, 1, 2 + k, 1 + static_cast<uint32_t>(k % kMaxManifoldPoints)));
  }
  check_batches(s);
  EXPECT_EQ(s.color_start[kColorCount + 1] - s.color_start[kColorCount], 11u);
}

}  // namespace
}  // namespace rwd::sim::d3
