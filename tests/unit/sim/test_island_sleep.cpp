// SPDX-License-Identifier: MIT
// Sleep: bodies at rest fall asleep after time_to_sleep, whole islands
// together; contacts and setters wake them.
#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;
using test::step_seconds;

TEST(IslandSleep, RestingStackSleepsTogether) {
  World3D world;
  add_ground(world);
  BodyId a = add_box(world, {0.0f, 0.5f, 0.0f});
  BodyId b = add_box(world, {0.0f, 1.5f, 0.0f});
  step_seconds(world, 0.25f);
  EXPECT_TRUE(world.is_awake(a));
  step_seconds(world, 3.0f);
  EXPECT_FALSE(world.is_awake(a));
  EXPECT_FALSE(world.is_awake(b));
  EXPECT_EQ(world.stats().awake_bodies, 0u);
  // Asleep means frozen: position does not change and velocity is zero.
  Vec3 p = world.position(b);
  step_seconds(world, 1.0f);
  EXPECT_EQ(world.position(b), p);
  EXPECT_EQ(world.linear_velocity(b), Vec3{});
  // Touching contacts persist while asleep, but a resting pair reports no
  // stay: a sleeping world reports nothing.
  EXPECT_EQ(world.stats().touching_manifolds, 2u);
  EXPECT_TRUE(world.events().empty());
  // Woken, both pairs stay again (never enter: they never stopped touching).
  ASSERT_TRUE(world.apply_linear_impulse(b, {0.0f, 0.0f, 1.0f}, world.position(b)).ok());
  world.step();
  ASSERT_EQ(world.events().size(), 2u);
  for (const ContactEvent& e : world.events()) EXPECT_EQ(e.type, ContactEventType::kStay);
}

// The threshold is an average speed: a body drifting through empty space
// slower than sleep_threshold_mps sleeps, one drifting faster never does,
// and a sleeping body keeps its pose (a stretch of rest starts where the
// body stands).
TEST(IslandSleep, ABodySleepsWhenSlowerThanTheThresholdOnAverage) {
  for (const float speed : {0.04f, 0.06f}) {
    WorldConfig config;
    config.gravity = {};
    World3D world(config);
    const BodyId box = add_box(world, {0.0f, 5.0f, 0.0f}, {0.1f, 0.1f, 0.1f});
    ASSERT_TRUE(world.set_linear_velocity(box, {speed, 0.0f, 0.0f}).ok());
    step_seconds(world, 3.0f);
    if (speed < config.sleep_threshold_mps) {
      EXPECT_FALSE(world.is_awake(box)) << speed << " m/s";
      const Vec3 p = world.position(box);
      step_seconds(world, 1.0f);
      EXPECT_EQ(world.position(box), p);
    } else {
      EXPECT_TRUE(world.is_awake(box)) << speed << " m/s";
      EXPECT_GT(world.position(box).x, 0.9f * speed * 3.0f);
    }
  }
}

// A rod turning slowly about its own long axis moves its surface by its
// thickness per radian, not by its length: at 0.3 rad/s no point of it
// goes faster than 0.03 m/s and it comes to rest, while the same turn
// about a cross axis sweeps its ends at 0.18 m/s and keeps it awake.
TEST(IslandSleep, ARodTurningSlowlyAboutItsLongAxisRests) {
  for (const bool long_axis : {true, false}) {
    WorldConfig config;
    config.gravity = {};
    World3D world(config);
    const BodyId rod = add_box(world, {0.0f, 5.0f, 0.0f}, {0.6f, 0.05f, 0.05f});
    const Vec3 spin = long_axis ? Vec3{0.3f, 0.0f, 0.0f} : Vec3{0.0f, 0.3f, 0.0f};
    ASSERT_TRUE(world.set_angular_velocity(rod, spin).ok());
    step_seconds(world, 3.0f);
    EXPECT_EQ(world.is_awake(rod), !long_axis) << (long_axis ? "long axis" : "cross axis");
  }
}

// A small pendulum passes through a slow turning point every half swing;
// it never counts as resting, as two stretches of half time_to_sleep_s
// each span no more than one of them.
TEST(IslandSleep, ASmallPendulumStaysAwake) {
  World3D world;
  BodyDef rod;
  rod.shape = Shape::make_box({0.05f, 0.5f, 0.05f});
  rod.position = {0.5f * 0.0998f, 9.5f, 0.0f};  // 0.1 rad from hanging straight
  rod.rotation = {0.0f, 0.0f, 0.05f, 0.99875f};
  const Result<BodyId> id = world.create_body(rod);
  ASSERT_TRUE(id.ok());
  JointDef hinge;
  hinge.type = JointType::kHinge;
  hinge.body_b = *id;
  hinge.anchor_a = {0.0f, 10.0f, 0.0f};
  hinge.anchor_b = {0.0f, 0.5f, 0.0f};
  hinge.axis_a = {0.0f, 0.0f, 1.0f};
  hinge.axis_b = {0.0f, 0.0f, 1.0f};
  ASSERT_TRUE(world.create_joint(hinge).ok());
  for (int t = 0; t < 600; ++t) {
    world.step();
    ASSERT_TRUE(world.is_awake(*id)) << "asleep at tick " << t + 1;
  }
}

TEST(IslandSleep, SetterWakesBodyAndImpactWakesIsland) {
  World3D world;
  add_ground(world);
  BodyId a = add_box(world, {0.0f, 0.5f, 0.0f});
  BodyId b = add_box(world, {0.0f, 1.5f, 0.0f});
  step_seconds(world, 3.0f);
  ASSERT_FALSE(world.is_awake(a));
  ASSERT_TRUE(world.set_linear_velocity(a, {0.0f, 0.0f, 0.0f}).ok());
  EXPECT_TRUE(world.is_awake(a));
  world.step();
  EXPECT_TRUE(world.is_awake(b));  // same island
  step_seconds(world, 3.0f);
  ASSERT_FALSE(world.is_awake(b));
  // Drop a box on the sleeping stack: the whole island wakes.
  BodyId c = add_box(world, {0.0f, 4.0f, 0.0f});
  bool woke_a = false;
  for (int i = 0; i < 90; ++i) {
    world.step();
    woke_a = woke_a || world.is_awake(a);
  }
  EXPECT_TRUE(woke_a);
  EXPECT_NEAR(world.position(c).y, 2.5f, 0.03f);  // landed on top, not through
}

TEST(IslandSleep, DisabledSleepKeepsBodiesAwake) {
  WorldConfig config;
  config.enable_sleep = false;
  World3D world(config);
  add_ground(world);
  BodyId a = add_box(world, {0.0f, 0.5f, 0.0f});
  step_seconds(world, 3.0f);
  EXPECT_TRUE(world.is_awake(a));
}

TEST(IslandSleep, DestroyingSupportWakesRestingBody) {
  World3D world;
  add_ground(world);
  BodyId a = add_box(world, {0.0f, 0.5f, 0.0f});
  BodyId b = add_box(world, {0.0f, 1.5f, 0.0f});
  step_seconds(world, 3.0f);
  ASSERT_FALSE(world.is_awake(b));
  ASSERT_TRUE(world.destroy_body(a).ok());
  EXPECT_TRUE(world.is_awake(b));
  step_seconds(world, 1.0f);
  EXPECT_NEAR(world.position(b).y, 0.5f, 0.02f);  // fell onto the ground
}

}  // namespace
}  // namespace rwd::sim
