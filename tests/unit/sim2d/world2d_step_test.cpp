// SPDX-License-Identifier: MIT
#include <string>

#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

// A substep longer than 1/240 s is refused (tick_hz * substeps >= 240),
// and a world made with such a config takes the defaults instead.
TEST(World2DStep, SubstepsLongerThanA240thOfASecondAreRefused) {
  const auto config = [](int32_t tick_hz, int32_t substeps) {
    World2DConfig c;
    c.tick_hz = tick_hz;
    c.substeps = substeps;
    return c;
  };
  EXPECT_TRUE(World2D::validate_config(config(60, 4)).ok());
  EXPECT_TRUE(World2D::validate_config(config(30, 8)).ok());
  EXPECT_TRUE(World2D::validate_config(config(240, 1)).ok());
  for (const World2DConfig& c : {config(60, 3), config(60, 1), config(30, 7), config(1, 32)}) {
    const Status s = World2D::validate_config(c);
    EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument) << c.tick_hz << " Hz, " << c.substeps;
    EXPECT_NE(s.message().find("1/240 s"), std::string::npos) << s.message();
  }
  const World2D world(config(60, 2));
  EXPECT_EQ(world.config().substeps, World2DConfig{}.substeps);
  // create() refuses what the constructor repairs.
  auto refused = World2D::create(config(60, 2));
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  auto made = World2D::create(config(30, 8));
  ASSERT_TRUE(made.ok()) << made.status().message();
  EXPECT_EQ((*made)->config().substeps, 8);
}

TEST(World2DStep, FreeFallMatchesTheSemiImplicitEulerSum) {
  World2D world;  // g = -10, 60 Hz, 4 substeps
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {Fx(), 100_fx});
  for (int i = 0; i < 60; ++i) world.step();
  // After 240 substeps of h = 1/240 s: v = -10 m/s, and y drops by
  // g h^2 n (n + 1) / 2 = 10 * 241 / 480 = 5.0208333 m.
  EXPECT_NEAR(world.linear_velocity(ball).y.raw(), (-10_fx).raw(), 2);
  EXPECT_NEAR(world.position(ball).y.raw(), (100_fx - 5.0208333_fx).raw(), 4);
  EXPECT_EQ(world.step_count(), 60u);
}

TEST(World2DStep, BallComesToRestOnTheGround) {
  World2D world;
  testing::add_round_ground(world);
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {Fx(), 3_fx});
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_GT(world.stats().contact_points, 0u);
  for (int i = 0; i < 180; ++i) world.step();
  // Resting within the slop of touching (centre at y = 0.5), and asleep:
  // no contact is solved any more.
  EXPECT_NEAR(world.position(ball).y.raw(), (0.5_fx).raw(), (0.006_fx).raw());
  EXPECT_EQ(world.linear_velocity(ball), Vec2());
  EXPECT_FALSE(world.is_awake(ball));
  EXPECT_EQ(world.stats().contact_points, 0u);
  // A push wakes it.
  ASSERT_TRUE(world.apply_linear_impulse(ball, {1_fx, Fx()}, world.position(ball)).ok());
  EXPECT_TRUE(world.is_awake(ball));
  world.step();
  EXPECT_GT(world.stats().contact_points, 0u);
}

TEST(World2DStep, KinematicBodyMovesByItsVelocityAndPushes) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  const BodyId2D pusher = add_body(world, BodyKind2D::kKinematic, make_circle(1_fx), {Fx(), Fx()});
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {3_fx, Fx()});
  ASSERT_TRUE(world.set_linear_velocity(pusher, {2_fx, Fx()}).ok());
  for (int i = 0; i < 120; ++i) world.step();
  // Two seconds at 2 m/s, untouched by the ball it pushed.
  EXPECT_NEAR(world.position(pusher).x.raw(), (4_fx).raw(), 16);
  EXPECT_EQ(world.linear_velocity(pusher), (Vec2{2_fx, Fx()}));
  EXPECT_GT(world.position(ball).x, 5_fx);
}

}  // namespace
}  // namespace rwd::sim2d
