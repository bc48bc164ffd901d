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

BodyId2D add_asleep(World2D& world, const Result<Shape2D>& shape, Vec2 position) {
  BodyDef2D def;
  def.shape = *shape;
  def.position = position;
  def.awake = false;
  const Result<BodyId2D> id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : BodyId2D{};
}

// Boxes created asleep in mid-air hang there, as a settled body would,
// until each is woken its own way; then each falls.
TEST(World2DSleep, ABodyCreatedAsleepStaysPutUntilWoken) {
  World2D world;
  add_body(world, BodyKind2D::kStatic, make_box(20_fx, 0.5_fx), {Fx(), -0.5_fx});
  const auto box = [] { return make_box(0.5_fx, 0.5_fx); };
  const BodyId2D by_force = add_asleep(world, box(), {-8_fx, 3_fx});
  const BodyId2D by_impulse = add_asleep(world, box(), {-5_fx, 3_fx});
  const BodyId2D by_wake = add_asleep(world, box(), {-2_fx, 3_fx});
  const BodyId2D by_joint = add_asleep(world, box(), {1_fx, 3_fx});
  const BodyId2D by_touch = add_asleep(world, box(), {4_fx, 3_fx});
  const BodyId2D by_transform = add_asleep(world, box(), {7_fx, 3_fx});
  const BodyId2D sleepers[] = {by_force, by_impulse, by_wake, by_joint, by_touch, by_transform};
  // The same box created awake falls at once.
  const BodyId2D awake = add_body(world, BodyKind2D::kDynamic, box(), {10_fx, 3_fx});
  // A static hook for the joint.
  const BodyId2D hook = add_body(world, BodyKind2D::kStatic, make_circle(0.1_fx), {1_fx, 5_fx});
  for (const BodyId2D id : sleepers) EXPECT_FALSE(world.is_awake(id));
  EXPECT_TRUE(world.is_awake(awake));
  for (int t = 0; t < 60; ++t) world.step();
  for (const BodyId2D id : sleepers) {
    EXPECT_FALSE(world.is_awake(id)) << id.index;
    EXPECT_EQ(world.position(id).y, 3_fx) << id.index;
    EXPECT_EQ(world.linear_velocity(id), Vec2{}) << id.index;
  }
  EXPECT_LT(world.position(awake).y, 1_fx);

  ASSERT_TRUE(world.apply_force(by_force, {1_fx, Fx()}).ok());
  ASSERT_TRUE(world.apply_linear_impulse(by_impulse, {Fx(), 0.1_fx}, {-5_fx, 3_fx}).ok());
  ASSERT_TRUE(world.wake_body(by_wake).ok());
  JointDef2D rope;
  rope.type = JointType2D::kDistance;
  rope.body_a = hook;
  rope.body_b = by_joint;
  rope.anchor_a = {1_fx, 5_fx};
  rope.anchor_b = {1_fx, 3.5_fx};
  rope.length = 1.5_fx;
  rope.min_length = Fx();
  rope.max_length = 3_fx;  // slack: the box drops 1.5 m and hangs from it
  ASSERT_TRUE(world.create_joint(rope).ok());
  ASSERT_TRUE(world.set_transform(by_transform, {7_fx, 3.5_fx}, Fx()).ok());
  // A ball thrown up from below hits by_touch.
  BodyDef2D ball;
  ball.shape = *make_circle(0.2_fx);
  ball.position = {4_fx, 0.2_fx};
  ball.linear_velocity = {Fx(), 9_fx};
  ASSERT_TRUE(world.create_body(ball).ok());
  for (const BodyId2D id : sleepers) {
    EXPECT_EQ(world.is_awake(id), id != by_touch) << id.index;
  }
  int touched_at = -1;
  for (int t = 0; t < 120; ++t) {
    world.step();
    if (touched_at < 0 && world.is_awake(by_touch)) touched_at = t;
  }
  EXPECT_GT(touched_at, 0) << "the box woke before the ball reached it, or never";
  for (const BodyId2D id : {by_force, by_impulse, by_wake, by_touch, by_transform}) {
    EXPECT_LT(world.position(id).y, 1_fx) << id.index;  // fell to the ground
  }
  // Its top anchor hangs 3 m under the hook: the box's centre at 1.5 m.
  EXPECT_NEAR(world.position(by_joint).y.raw(), (1.5_fx).raw(), (0.05_fx).raw());
}

TEST(World2DSleep, CreatingAsleepNeedsNoVelocityAndOnlyMeansDynamicBodies) {
  World2D world;
  BodyDef2D def;
  def.shape = *make_box(0.5_fx, 0.5_fx);
  def.awake = false;
  def.linear_velocity = {1_fx, Fx()};
  const Result<BodyId2D> moving = world.create_body(def);
  EXPECT_EQ(moving.status().code(), ErrorCode::kInvalidArgument);
  def.linear_velocity = {};
  def.angular_velocity = 1_fx;
  EXPECT_EQ(world.create_body(def).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.body_count(), 0u);
  // A kinematic body is never asleep: it moves by its velocity.
  def.kind = BodyKind2D::kKinematic;
  def.angular_velocity = Fx();
  def.linear_velocity = {1_fx, Fx()};
  const BodyId2D kinematic = *world.create_body(def);
  world.step();
  EXPECT_GT(world.position(kinematic).x, Fx());
  // With sleep off a body created asleep still waits to be woken, and once
  // woken it stays awake.
  World2DConfig config;
  config.enable_sleep = false;
  World2D no_sleep(config);
  def.kind = BodyKind2D::kDynamic;
  def.linear_velocity = {};
  const BodyId2D box = *no_sleep.create_body(def);
  for (int t = 0; t < 30; ++t) no_sleep.step();
  EXPECT_FALSE(no_sleep.is_awake(box));
  EXPECT_EQ(no_sleep.position(box), Vec2{});
  ASSERT_TRUE(no_sleep.wake_body(box).ok());
  for (int t = 0; t < 300; ++t) no_sleep.step();
  EXPECT_TRUE(no_sleep.is_awake(box));
}

// Whether a body starts asleep is state: the checksum tells the two
// apart, and a world saved or serialized while its bodies still sleep
// (and stepped on through the wake-up) replays bit for bit.
TEST(World2DSleep, BodiesCreatedAsleepRestoreAndReloadBitForBit) {
  World2D world;
  World2D awake_world;
  for (World2D* w : {&world, &awake_world}) {
    add_body(*w, BodyKind2D::kStatic, make_box(10_fx, 0.5_fx), {Fx(), -0.5_fx});
  }
  // A leaning column of sleeping boxes; a ball rolls into its foot at
  // about tick 40.
  for (int i = 0; i < 5; ++i) {
    const Vec2 at{Fx::ratio(i, 10), 0.5_fx + Fx(i)};
    add_asleep(world, make_box(0.5_fx, 0.5_fx), at);
    add_body(awake_world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.5_fx), at);
  }
  BodyDef2D ball;
  ball.shape = *make_circle(0.25_fx);
  ball.position = {-4_fx, 0.25_fx};
  ball.linear_velocity = {5_fx, Fx()};
  ASSERT_TRUE(world.create_body(ball).ok());
  ASSERT_TRUE(awake_world.create_body(ball).ok());
  EXPECT_NE(world.checksum(), awake_world.checksum());
  for (int t = 0; t < 10; ++t) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<BodyId2D> ids;
  world.body_ids(ids);
  const BodyId2D foot = ids[1];
  EXPECT_FALSE(world.is_awake(foot));
  std::vector<uint64_t> expected;
  int woke_at = -1;
  for (int t = 0; t < 120; ++t) {
    world.step();
    expected.push_back(world.checksum());
    if (woke_at < 0 && world.is_awake(foot)) woke_at = t;
  }
  // The replay below starts asleep and runs through the wake-up.
  EXPECT_GT(woke_at, 0);
  world.restore(saved);
  World2D copy;
  ASSERT_TRUE(copy.deserialize(bytes).ok());
  EXPECT_FALSE(copy.is_awake(foot));
  for (size_t t = 0; t < expected.size(); ++t) {
    world.step();
    copy.step();
    ASSERT_EQ(world.checksum(), expected[t]) << t;
    ASSERT_EQ(copy.checksum(), expected[t]) << t;
  }
}

}  // namespace
}  // namespace rwd::sim2d
