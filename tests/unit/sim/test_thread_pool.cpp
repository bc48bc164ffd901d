// SPDX-License-Identifier: MIT
// ThreadPool, and a world stepped on 1, 2, 4 and 8 threads: every tick's
// checksum the same as without a pool, for a pile of every shape kind on a
// mesh floor, with a joint chain, a wake-up and a restore along the way.
#include "rewind/core/thread_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <vector>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

TEST(ThreadPool, EveryIndexOnceForAnyCountGrainAndThreads) {
  for (uint32_t threads : {1u, 2u, 3u, 8u}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (uint32_t count : {0u, 1u, 7u, 64u, 1000u, 4097u}) {
      for (uint32_t grain : {0u, 1u, 5u, 64u, 5000u}) {
        std::vector<std::atomic<uint32_t>> seen(count);
        std::atomic<uint32_t> ranges{0};
        pool.parallel_for(count, grain, [&](uint32_t begin, uint32_t end) {
          ranges.fetch_add(1);
          EXPECT_LT(begin, end);
          EXPECT_LE(end, count);
          // Never shorter than the grain, unless the whole count is.
          EXPECT_GE(end - begin, std::min(count, std::max(grain, 1u)));
          for (uint32_t i = begin; i < end; ++i) seen[i].fetch_add(1);
        });
        // At most one range per thread.
        EXPECT_LE(ranges.load(), pool.threads());
        for (uint32_t i = 0; i < count; ++i) {
          ASSERT_EQ(seen[i].load(), 1u) << "threads " << threads << " count " << count << " grain "
                                        << grain << " index " << i;
        }
      }
    }
  }
}

TEST(ThreadPool, ManyJobsInARowFinishEachBeforeTheNextStarts) {
  // A step runs hundreds of short jobs back to back; a worker that wakes
  // late must never run a range of the next job with the last one's work.
  ThreadPool pool(4);
  std::vector<uint32_t> values(300, 0);
  for (uint32_t job = 1; job <= 2000; ++job) {
    pool.parallel_for(static_cast<uint32_t>(values.size()), 7, [&](uint32_t begin, uint32_t end) {
      for (uint32_t i = begin; i < end; ++i) values[i] += job;
    });
  }
  const uint32_t expected = 2000u * 2001u / 2u;
  for (uint32_t v : values) ASSERT_EQ(v, expected);
}

TEST(ThreadPool, ThreadCountIsClamped) {
  EXPECT_EQ(ThreadPool(0).threads(), 1u);
  EXPECT_EQ(ThreadPool(1000).threads(), ThreadPool::kMaxThreads);
}

TEST(ThreadPool, RangesAreEqualCutsWhicheverThreadRunsThem) {
  // Range k runs on thread k when that thread is free: a caller that
  // cuts the same data the same way finds it where it left it. Whatever
  // thread runs a range, the ranges are the same equal cuts.
  ThreadPool pool(2);
  for (int job = 0; job < 50; ++job) {
    std::vector<uint32_t> starts;
    std::mutex guard;
    pool.parallel_for(1000, 10, [&](uint32_t begin, uint32_t end) {
      std::lock_guard<std::mutex> lock(guard);
      starts.push_back(begin);
      EXPECT_EQ(end - begin, 500u);
    });
    std::sort(starts.begin(), starts.end());
    ASSERT_EQ(starts, (std::vector<uint32_t>{0, 500}));
  }
}

// A bin on a bumpy triangle-mesh floor with boxes, spheres, capsules, a
// hull and a compound in turn dropped into it, and a hanging chain of
// ball-jointed boxes: every stage that cuts work across threads (pairs,
// compound parts, colours, the overflow, integration) has work to cut.
void build_pile(World3D& world, uint32_t bodies) {
  GeometryStore& store = world.geometry();
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
  constexpr int kGrid = 12;
  for (int z = 0; z <= kGrid; ++z) {
    for (int x = 0; x <= kGrid; ++x) {
      const float h =
          0.15f * std::sin(0.9f * static_cast<float>(x)) * std::cos(0.7f * static_cast<float>(z));
      vertices.push_back({static_cast<float>(x - kGrid / 2), h, static_cast<float>(z - kGrid / 2)});
    }
  }
  for (int z = 0; z < kGrid; ++z) {
    for (int x = 0; x < kGrid; ++x) {
      const uint32_t i = static_cast<uint32_t>(z * (kGrid + 1) + x);
      const uint32_t row = kGrid + 1;
      for (uint32_t k : {i, i + row, i + 1, i + 1, i + row, i + row + 1}) indices.push_back(k);
    }
  }
  const GeometryId floor = *store.add_mesh(vertices, indices);
  test::add_static(world, Shape::make_mesh(floor), {0.0f, 0.0f, 0.0f});
  for (int side = 0; side < 4; ++side) {
    const float s = side < 2 ? -1.0f : 1.0f;
    const Vec3 half = side % 2 == 0 ? Vec3{0.2f, 2.0f, 3.5f} : Vec3{3.5f, 2.0f, 0.2f};
    const Vec3 at = side % 2 == 0 ? Vec3{3.5f * s, 2.0f, 0.0f} : Vec3{0.0f, 2.0f, 3.5f * s};
    test::add_static(world, Shape::make_box(half), at);
  }
  const std::vector<Vec3> rock = {
      {0.3f, 0.0f, 0.0f},  {-0.25f, 0.05f, 0.1f}, {0.0f, 0.3f, 0.05f}, {0.05f, -0.3f, 0.0f},
      {0.1f, 0.0f, 0.28f}, {-0.05f, 0.1f, -0.3f}, {0.2f, 0.2f, 0.2f},  {-0.2f, -0.2f, -0.15f}};
  const GeometryId hull = *store.add_hull(rock);
  const CompoundChild table[3] = {{Shape::make_box({0.4f, 0.05f, 0.3f}), {0.0f, 0.2f, 0.0f}, {}},
                                  {Shape::make_box({0.05f, 0.2f, 0.05f}), {0.3f, 0.0f, 0.2f}, {}},
                                  {Shape::make_capsule(0.06f, 0.15f), {-0.3f, 0.0f, -0.2f}, {}}};
  const GeometryId compound = *store.add_compound(table);
  test::Rng rng{42};
  for (uint32_t i = 0; i < bodies; ++i) {
    BodyDef def;
    switch (i % 5) {
      case 0:
        def.shape = Shape::make_box({0.25f, 0.2f, 0.3f});
        break;
      case 1:
        def.shape = Shape::make_sphere(0.25f);
        break;
      case 2:
        def.shape = Shape::make_capsule(0.15f, 0.25f);
        break;
      case 3:
        def.shape = Shape::make_hull(hull);
        break;
      default:
        def.shape = Shape::make_compound(compound);
        break;
    }
    def.position = {rng.uniform(-2.8f, 2.8f), 0.8f + 0.35f * static_cast<float>(i / 9),
                    rng.uniform(-2.8f, 2.8f)};
    def.rotation = rng.rotation();
    def.linear_velocity = {rng.uniform(-1.0f, 1.0f), 0.0f, rng.uniform(-1.0f, 1.0f)};
    ASSERT_TRUE(world.create_body(def).ok());
  }
  // The chain hangs from a static anchor above the bin.
  BodyId last = test::add_static(world, Shape::make_box({0.1f, 0.1f, 0.1f}), {0.0f, 9.0f, 0.0f});
  for (int link = 0; link < 6; ++link) {
    const BodyId box = test::add_box(world, {0.5f * static_cast<float>(link + 1), 9.0f, 0.0f},
                                     {0.2f, 0.05f, 0.05f});
    JointDef joint;
    joint.type = JointType::kBall;
    joint.body_a = last;
    joint.body_b = box;
    joint.anchor_a = {link == 0 ? 0.0f : 0.25f, 0.0f, 0.0f};
    joint.anchor_b = {-0.25f, 0.0f, 0.0f};
    ASSERT_TRUE(world.create_joint(joint).ok());
    last = box;
  }
}

// Steps a pile of `bodies` for `ticks` on `pool` (null: none) and returns
// every tick's checksum; at tick `restore_at` it restores the state saved
// at tick `save_at` and goes on from there, as a rollback does.
std::vector<uint64_t> run_pile(ThreadPool* pool, uint32_t bodies, int ticks, int save_at,
                               int restore_at) {
  World3D world;
  build_pile(world, bodies);
  world.set_thread_pool(pool);
  std::vector<uint64_t> sums;
  WorldState saved;
  for (int t = 0; t < ticks; ++t) {
    if (t == save_at) saved = world.state();
    if (t == restore_at) world.restore(saved);
    world.step();
    sums.push_back(world.checksum());
  }
  return sums;
}

TEST(ThreadedStep, EveryTickTheSameOnOneTwoFourAndEightThreads) {
  constexpr uint32_t kBodies = 400;
  constexpr int kTicks = 150;
  const std::vector<uint64_t> alone = run_pile(nullptr, kBodies, kTicks, 60, 90);
  for (uint32_t threads : {1u, 2u, 4u, 8u}) {
    ThreadPool pool(threads);
    const std::vector<uint64_t> sums = run_pile(&pool, kBodies, kTicks, 60, 90);
    ASSERT_EQ(sums.size(), alone.size());
    for (size_t t = 0; t < sums.size(); ++t) {
      ASSERT_EQ(sums[t], alone[t]) << threads << " threads, tick " << t;
    }
  }
}

TEST(ThreadedStep, APileLargeEnoughToCutTheSolversColoursStepsTheSame) {
  // 2,500 boxes packed in a bin: the first colours hold hundreds of
  // constraints, so every solver pass cuts them across the threads, and
  // the integration cuts the bodies (the mixed pile above is too small for
  // either).
  const auto run = [](ThreadPool* pool) {
    WorldConfig config;
    config.max_bodies = 4000;
    config.enable_sleep = false;
    World3D world(config);
    test::add_ground(world);
    for (int i = 0; i < 2500; ++i) {
      const float x = -6.0f + 0.52f * static_cast<float>(i % 25);
      const float z = -6.0f + 0.52f * static_cast<float>((i / 25) % 25);
      const float y = 0.26f + 0.53f * static_cast<float>(i / 625);
      test::add_box(world, {x, y, z}, {0.25f, 0.25f, 0.25f});
    }
    world.set_thread_pool(pool);
    std::vector<uint64_t> sums;
    for (int t = 0; t < 40; ++t) {
      world.step();
      sums.push_back(world.checksum());
    }
    return sums;
  };
  const std::vector<uint64_t> alone = run(nullptr);
  for (uint32_t threads : {2u, 4u}) {
    ThreadPool pool(threads);
    EXPECT_EQ(run(&pool), alone) << threads << " threads";
  }
}

TEST(ThreadedStep, OnePoolServesWorldsSteppedInTurn) {
  // Two worlds on one thread share a pool, stepped alternately: each steps
  // as it would alone.
  const std::vector<uint64_t> alone = run_pile(nullptr, 120, 60, -1, -1);
  ThreadPool pool(2);
  World3D first;
  World3D second;
  build_pile(first, 120);
  build_pile(second, 120);
  first.set_thread_pool(&pool);
  second.set_thread_pool(&pool);
  for (size_t t = 0; t < alone.size(); ++t) {
    first.step();
    second.step();
    ASSERT_EQ(first.checksum(), alone[t]) << "tick " << t;
    ASSERT_EQ(second.checksum(), alone[t]) << "tick " << t;
  }
  first.set_thread_pool(nullptr);
  first.step();
  second.step();
  EXPECT_EQ(first.checksum(), second.checksum());
}

}  // namespace
}  // namespace rwd::sim
