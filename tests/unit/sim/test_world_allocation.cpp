// SPDX-License-Identifier: MIT
// A warmed-up world steps, saves and restores without touching the heap
// (DESIGN.md section 2: snapshots every tick must not allocate). Counts
// global operator new calls between two markers.

#include <gtest/gtest.h>

#include "allocation_counter.h"

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

TEST(WorldAllocation, WarmStepSaveRestoreDoNotAllocate) {
  WorldConfig config;
  config.enable_sleep = false;  // keep the whole pipeline running
  World3D world(config);
  test::add_ground(world);
  for (int i = 0; i < 16; ++i) {
    float x = 1.1f * static_cast<float>(i % 4) - 1.6f;
    float y = 0.5f + 1.2f * static_cast<float>(i / 4);
    if (i % 2 == 0) {
      test::add_box(world, {x, y, 0.1f * static_cast<float>(i % 3)});
    } else {
      test::add_sphere(world, {x, y, 0.0f}, 0.45f);
    }
  }
  for (int i = 0; i < 60; ++i) world.step();
  WorldState start;
  WorldState slot;
  world.save(start);
  // First pass grows every buffer to what these steps need.
  for (int i = 0; i < 120; ++i) {
    world.step();
    world.save(slot);
  }
  world.restore(start);
  rwd::test::AllocationCounter::start();
  for (int i = 0; i < 120; ++i) {
    world.step();
    world.save(slot);
  }
  world.restore(start);
  EXPECT_EQ(rwd::test::AllocationCounter::stop(), 0);
}

TEST(WorldAllocation, WarmScheduledQueriesDoNotAllocate) {
  WorldConfig config;
  config.enable_sleep = false;
  World3D world(config);
  test::add_ground(world);
  for (int i = 0; i < 8; ++i) {
    test::add_box(world,
                  {0.3f * static_cast<float>(i % 3), 0.5f + 1.1f * static_cast<float>(i), 0.0f});
  }
  Ray down;
  down.origin = {0.0f, 30.0f, 0.0f};
  ASSERT_TRUE(
      world.schedule_raycast_all(down, {}, QueryPhase::kPrePhysics, 1, QueryRepeat::kEveryStep)
          .ok());
  ASSERT_TRUE(world
                  .schedule_overlap(Shape::make_box({2.0f, 1.0f, 2.0f}), {0.0f, 1.0f, 0.0f}, Quat{},
                                    {}, QueryPhase::kPostPhysics, 2, QueryRepeat::kEveryStep)
                  .ok());
  // A one-shot query each tick, as a game scheduling from its inputs would.
  const auto tick = [&](uint64_t tag) {
    ASSERT_TRUE(world.schedule_raycast(down, {}, QueryPhase::kPostPhysics, tag).ok());
    world.step();
  };
  WorldState start;
  WorldState slot;
  world.save(start);
  for (uint64_t i = 0; i < 120; ++i) {
    tick(i);
    world.save(slot);
  }
  world.restore(start);
  rwd::test::AllocationCounter::start();
  for (uint64_t i = 0; i < 120; ++i) {
    tick(i);
    world.save(slot);
  }
  world.restore(start);
  EXPECT_EQ(rwd::test::AllocationCounter::stop(), 0);
}

}  // namespace
}  // namespace rwd::sim
