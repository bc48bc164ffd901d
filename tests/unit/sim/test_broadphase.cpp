// SPDX-License-Identifier: MIT
// Broadphase: the candidate pairs match a brute-force reference, sorted by
// (lower, higher) index, with static-static pairs skipped; the trees and
// sweep order kept from step to step (through sleep, wake and restore)
// give exactly what a fresh broadphase gives.
#include <algorithm>

#include <gtest/gtest.h>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// Every pair of live bodies whose bounds overlap: awake bodies' bounds
// grown by the speculative distance and their reach this tick, the
// others' exact.
std::vector<BodyPair> reference_pairs(const WorldState& state) {
  std::vector<BodyPair> expected;
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  std::vector<Aabb> boxes(n);
  for (uint32_t i = 0; i < n; ++i) {
    const BodySim& sim = state.sims[i];
    boxes[i] = shape_aabb(state.infos[i].shape, sim.position, sim.rotation);
    if (is_active(state.infos[i])) {
      const float reach =
          length(sim.linear_velocity) + length(sim.angular_velocity) * state.masses[i].extent;
      const float m = state.config.speculative_distance_m + state.config.tick_seconds * reach;
      boxes[i].lower -= Vec3{m, m, m};
      boxes[i].upper += Vec3{m, m, m};
    }
  }
  for (uint32_t a = 0; a < n; ++a) {
    for (uint32_t b = a + 1; b < n; ++b) {
      const BodyInfo& ia = state.infos[a];
      const BodyInfo& ib = state.infos[b];
      if (!is_simulated(ia) || !is_simulated(ib)) continue;
      if (!is_active(ia) && !is_active(ib)) continue;
      if (ia.kind == BodyKind::kStatic && ib.kind == BodyKind::kStatic) continue;
      if (overlaps(boxes[a], boxes[b])) expected.push_back({a, b});
    }
  }
  return expected;
}

// A ground and `count` bodies in a loose lattice above it that falls into a
// heap; every `sphere_every`-th body a sphere (0: boxes only).
std::vector<BodyId> add_heap(World3D& world, int count, int sphere_every) {
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box({20.0f, 0.5f, 20.0f});
  ground.position = {0.0f, -0.5f, 0.0f};
  EXPECT_TRUE(world.create_body(ground).ok());
  std::vector<BodyId> bodies;
  for (int i = 0; i < count; ++i) {
    BodyDef def;
    def.shape = sphere_every > 0 && i % sphere_every == 0 ? Shape::make_sphere(0.25f)
                                                          : Shape::make_box({0.25f, 0.25f, 0.25f});
    def.position = {static_cast<float>(i % 5) * 0.6f - 1.2f,
                    0.5f + static_cast<float>(i / 25) * 0.6f,
                    static_cast<float>((i / 5) % 5) * 0.6f - 1.2f};
    bodies.push_back(world.create_body(def).value());
  }
  return bodies;
}

void expect_pairs(const std::vector<BodyPair>& got, const std::vector<BodyPair>& expected,
                  int tick) {
  ASSERT_EQ(got.size(), expected.size()) << "tick " << tick;
  for (size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(got[i].a, expected[i].a) << "tick " << tick << " pair " << i;
    ASSERT_EQ(got[i].b, expected[i].b) << "tick " << tick << " pair " << i;
  }
}

TEST(Broadphase, MatchesBruteForceAndIsSorted) {
  World3D world;
  // A deterministic scatter of static and dynamic shapes, some overlapping.
  uint32_t seed = 12345;
  auto next = [&]() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 16777216.0f;
  };
  for (int i = 0; i < 80; ++i) {
    BodyDef def;
    def.kind = i % 4 == 0 ? BodyKind::kStatic : BodyKind::kDynamic;
    def.position = {next() * 10.0f, next() * 10.0f, next() * 10.0f};
    def.shape = i % 2 == 0 ? Shape::make_sphere(0.3f + next())
                           : Shape::make_box({0.2f + next(), 0.2f + next(), 0.2f + next()});
    def.rotation = normalize(Quat{next(), next(), next(), 1.0f});
    ASSERT_TRUE(world.create_body(def).ok());
  }
  const WorldState& state = world.state();
  WorldScratch scratch;
  find_pairs(state, scratch);

  const std::vector<BodyPair> expected = reference_pairs(state);
  ASSERT_GT(expected.size(), 10u);
  expect_pairs(scratch.pairs, expected, 0);
}

// Boxes fall into a heap and fall asleep; some are kicked awake again and a
// restore rewinds the world. A broadphase that keeps its trees and sweep
// order across all of it reports exactly the reference pairs every tick.
TEST(Broadphase, KeptStructuresMatchFreshOnesThroughSleepWakeAndRestore) {
  World3D world;
  const std::vector<BodyId> boxes = add_heap(world, 60, 0);
  WorldScratch kept;
  WorldState saved;
  uint32_t asleep_seen = 0;
  for (int tick = 0; tick < 420; ++tick) {
    if (tick == 300) world.save(saved);
    if (tick == 320 || tick == 360) {
      // Kick a few boxes (waking them and what they touch).
      for (int k = 0; k < 60; k += 7) {
        ASSERT_TRUE(world.set_linear_velocity(boxes[k], {0.0f, 3.0f, 0.5f}).ok());
      }
    }
    if (tick == 380) {
      world.restore(saved);
      mark_world_edited(kept);
    }
    world.step();
    const WorldState& state = world.state();
    for (uint32_t i = 0; i < state.infos.size(); ++i) {
      if (is_simulated(state.infos[i]) && state.infos[i].kind == BodyKind::kDynamic &&
          !is_active(state.infos[i])) {
        ++asleep_seen;
      }
    }
    const std::vector<BodyPair> expected = reference_pairs(state);
    find_pairs(state, kept);
    expect_pairs(kept.pairs, expected, tick);
    WorldScratch fresh;
    find_pairs(state, fresh);
    expect_pairs(fresh.pairs, expected, tick);
  }
  EXPECT_GT(asleep_seen, 0u) << "the heap should have slept at some point";
}

}  // namespace
}  // namespace rwd::sim::d3

namespace rwd::sim::d3 {
namespace {

// The query side of the broadphase holds every simulated body exactly once
// (static, sleeping or awake tree) at its current pose: through a heap
// falling asleep, bodies woken by a velocity (no edit), a teleport and a
// restore, an overlap covering the world reports every body, once.
TEST(Broadphase, QueriesMatchExactBoundsThroughSleepWakeAndRestore) {
  World3D world;
  const std::vector<BodyId> boxes = add_heap(world, 40, 3);
  WorldState saved;
  uint32_t sleeping_seen = 0;
  const Shape everything = Shape::make_box({50.0f, 50.0f, 50.0f});
  std::vector<BodyId> got;
  const auto check = [&](int tick) {
    const WorldState& state = world.state();
    std::vector<BodyId> expected;
    for (uint32_t i = 0; i < state.infos.size(); ++i) {
      if (!is_simulated(state.infos[i])) continue;
      expected.push_back({i, state.infos[i].generation});
      if (state.infos[i].kind == BodyKind::kDynamic && !is_active(state.infos[i])) {
        ++sleeping_seen;
      }
    }
    ASSERT_TRUE(world.overlap(everything, {}, Quat{}, {}, got).ok());
    ASSERT_EQ(got.size(), expected.size()) << "tick " << tick;
    for (size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].index, expected[k].index) << "tick " << tick;
    }
  };
  for (int tick = 0; tick < 400; ++tick) {
    if (tick == 300) world.save(saved);
    if (tick == 250 || tick == 330) {
      for (int k = 0; k < 40; k += 7) {
        ASSERT_TRUE(world.set_linear_velocity(boxes[k], {0.0f, 2.0f, 0.5f}).ok());
      }
      check(tick);
    }
    if (tick == 340) {
      ASSERT_TRUE(world.set_transform(boxes[3], {5.0f, 2.0f, 5.0f}, Quat{}).ok());
      check(tick);
    }
    if (tick == 360) {
      world.restore(saved);
      check(tick);
    }
    world.step();
    check(tick);
  }
  EXPECT_GT(sleeping_seen, 0u) << "the heap should have slept at some point";
}

}  // namespace
}  // namespace rwd::sim::d3
