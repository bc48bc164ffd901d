// SPDX-License-Identifier: MIT
// Sleeping islands: a settled stack sleeps whole and costs no solving; a
// touch wakes the whole island in the same step; sleep is state, so a
// restored world sleeps and wakes alike.
#include <vector>

#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

std::vector<BodyId2D> build_stack(World2D& world, int boxes) {
  add_body(world, BodyKind2D::kStatic, make_box(5_fx, 0.5_fx), {Fx(), -0.5_fx});
  std::vector<BodyId2D> stack;
  for (int i = 0; i < boxes; ++i) {
    stack.push_back(
        add_body(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.5_fx), {Fx(), 0.5_fx + Fx(i)}));
  }
  return stack;
}

TEST(World2DSleep, ASettledStackSleepsWholeAndATouchWakesItWhole) {
  World2D world;
  const std::vector<BodyId2D> stack = build_stack(world, 5);
  int ticks = 0;
  while (world.is_awake(stack.back()) && ticks < 600) {
    world.step();
    ++ticks;
  }
  ASSERT_LT(ticks, 600) << "the stack never slept";
  for (const BodyId2D id : stack) EXPECT_FALSE(world.is_awake(id));
  world.step();
  EXPECT_EQ(world.stats().contact_points, 0u);
  // A ball thrown at the bottom box wakes all five in the step it touches.
  const BodyId2D ball =
      add_body(world, BodyKind2D::kDynamic, make_circle(0.25_fx), {-3_fx, 0.5_fx});
  ASSERT_TRUE(world.set_linear_velocity(ball, {10_fx, Fx()}).ok());
  int woke_at = -1;
  for (int t = 0; t < 60 && woke_at < 0; ++t) {
    world.step();
    if (world.is_awake(stack.front())) woke_at = t;
  }
  ASSERT_GE(woke_at, 0) << "the ball never woke the stack";
  for (const BodyId2D id : stack) EXPECT_TRUE(world.is_awake(id));
}

TEST(World2DSleep, SleepOffKeepsEverythingAwake) {
  World2DConfig config;
  config.enable_sleep = false;
  World2D world(config);
  const std::vector<BodyId2D> stack = build_stack(world, 3);
  for (int t = 0; t < 300; ++t) world.step();
  for (const BodyId2D id : stack) EXPECT_TRUE(world.is_awake(id));
}

TEST(World2DSleep, RestoredWorldSleepsAndWakesAlike) {
  World2D world;
  const std::vector<BodyId2D> stack = build_stack(world, 4);
  for (int t = 0; t < 20; ++t) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint64_t> first;
  for (int t = 0; t < 200; ++t) {
    if (t == 150) {
      ASSERT_TRUE(world.apply_linear_impulse(stack[2], {3_fx, Fx()}, {}).ok());
    }
    world.step();
    first.push_back(world.checksum());
  }
  world.restore(saved);
  for (int t = 0; t < 200; ++t) {
    if (t == 150) {
      ASSERT_TRUE(world.apply_linear_impulse(stack[2], {3_fx, Fx()}, {}).ok());
    }
    world.step();
    ASSERT_EQ(world.checksum(), first[static_cast<size_t>(t)]) << t;
  }
}

}  // namespace
}  // namespace rwd::sim2d
