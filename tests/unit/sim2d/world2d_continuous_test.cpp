// SPDX-License-Identifier: MIT
// Continuous collision: a bullet never crosses a thin wall when it asks to
// be swept, and does without it (so the test can fail).
#include "rewind/sim2d/chain2d.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

// A 5 cm ball at `speed` toward a 2 cm wall at x = 5; the ball's x after
// one second.
Fx ball_after_a_second(Fx speed, bool continuous, Vec2 direction = {1_fx, Fx()}, Vec2 start = {}) {
  World2DConfig config;
  config.gravity = {};
  config.max_linear_speed = 1000_fx;
  World2D world(config);
  add_body(world, BodyKind2D::kStatic, make_box(0.01_fx, 3_fx), {5_fx, Fx()});
  BodyDef2D def;
  def.shape = *make_circle(0.05_fx);
  def.position = start;
  def.linear_velocity = direction * speed;
  def.continuous = continuous;
  const BodyId2D ball = *world.create_body(def);
  for (int t = 0; t < 60; ++t) world.step();
  return world.position(ball).x;
}

TEST(World2DContinuous, ABulletNeverCrossesAThinWall) {
  EXPECT_GT(ball_after_a_second(500_fx, false), 5_fx) << "the wall should be crossed unswept";
  for (const Fx speed : {20_fx, 100_fx, 300_fx, 500_fx, 900_fx}) {
    EXPECT_LT(ball_after_a_second(speed, true), 5_fx) << "at " << speed.raw() / 65536 << " m/s";
  }
  // At an angle too: aimed to meet the wall at its middle.
  EXPECT_GT(ball_after_a_second(500_fx, false, {0.8_fx, 0.6_fx}, {Fx(), -3.75_fx}), 5_fx);
  EXPECT_LT(ball_after_a_second(500_fx, true, {0.8_fx, 0.6_fx}, {Fx(), -3.75_fx}), 5_fx);
}

TEST(World2DContinuous, ASweptBoxStopsAtTheWallsFace) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  add_body(world, BodyKind2D::kStatic, make_box(0.01_fx, 3_fx), {5_fx, Fx()});
  BodyDef2D def;
  def.shape = *make_box(0.1_fx, 0.1_fx);
  def.linear_velocity = {300_fx, Fx()};
  def.continuous = true;
  const BodyId2D box = *world.create_body(def);
  for (int t = 0; t < 60; ++t) {
    world.step();
    // Never past the wall's face (4.99) by more than the slop.
    EXPECT_LT(world.position(box).x + 0.1_fx, 4.99_fx + 0.006_fx) << "tick " << t;
  }
}

// A chain floor collides on its upper side only: a continuous bullet from
// above stops on it, one from below passes through, in the sweep as in the
// contacts (a sweep that disagreed would hold the bullet under the floor
// for ever, moving it back every step).
TEST(World2DContinuous, AChainFloorStopsBulletsFromItsSolidSideOnly) {
  for (const bool from_above : {true, false}) {
    World2DConfig config;
    config.gravity = {};
    World2D world(config);
    const Vec2 points[] = {{10_fx, Fx()}, {-10_fx, Fx()}};  // right to left: solid side up
    const Result<std::vector<Shape2D>> floor = make_chain(points, false);
    ASSERT_TRUE(floor.ok());
    for (const Shape2D& s : *floor) add_body(world, BodyKind2D::kStatic, s, {});
    BodyDef2D def;
    def.shape = *make_circle(0.05_fx);
    def.position = {Fx(), from_above ? 3_fx : -3_fx};
    def.linear_velocity = {Fx(), from_above ? -300_fx : 300_fx};
    def.continuous = true;
    const BodyId2D bullet = *world.create_body(def);
    for (int t = 0; t < 30; ++t) world.step();
    if (from_above) {
      EXPECT_GT(world.position(bullet).y, Fx()) << "crossed the floor from above";
    } else {
      EXPECT_GT(world.position(bullet).y, 3_fx) << "held under the floor";
    }
  }
}

// A swept body that bounces off the ground leaves it: the sweep only
// stops motion toward a surface, never away from one it starts against.
TEST(World2DContinuous, ASweptBallBouncesOffTheGround) {
  World2D world;
  add_body(world, BodyKind2D::kStatic, make_box(100_fx, 1_fx), {Fx(), -1_fx});
  BodyDef2D def;
  def.shape = *make_circle(0.5_fx);
  def.position = {Fx(), 1.5_fx};
  def.material.restitution = 0.5_fx;
  def.continuous = true;
  const BodyId2D ball = *world.create_body(def);
  Fx highest_after_bounce;
  bool bounced = false;
  for (int t = 0; t < 60; ++t) {
    world.step();
    if (world.linear_velocity(ball).y > Fx()) bounced = true;
    if (bounced) highest_after_bounce = fixed::max(highest_after_bounce, world.position(ball).y);
  }
  ASSERT_TRUE(bounced);
  // Dropped 1 m with e = 0.5: up to about 0.25 m above resting (y = 0.5).
  EXPECT_GT(highest_after_bounce, 0.7_fx);
}

}  // namespace
}  // namespace rwd::sim2d
