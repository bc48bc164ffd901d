// SPDX-License-Identifier: MIT
#include <vector>

#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

TEST(World2DBodies, CreateReadBackAndDestroy) {
  World2D world;
  const BodyId2D a =
      add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {1_fx, 2_fx}, 0.25_fx);
  EXPECT_TRUE(world.is_valid(a));
  EXPECT_EQ(world.body_count(), 1u);
  EXPECT_EQ(world.position(a), (Vec2{1_fx, 2_fx}));
  // The angle comes back within the trig library's ulp.
  EXPECT_LE(fixed::abs(world.angle(a) - 0.25_fx).raw(), 2);
  // pi r^2 at density 1: 0.785398 kg.
  EXPECT_NEAR(world.mass(a).to_fx().raw(), 51472, 2);
  ASSERT_TRUE(world.destroy_body(a).ok());
  EXPECT_FALSE(world.is_valid(a));
  EXPECT_EQ(world.destroy_body(a).code(), ErrorCode::kNotFound);
  // The slot is reused with a new generation: the old handle stays stale.
  const BodyId2D b = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {});
  EXPECT_EQ(b.index, a.index);
  EXPECT_NE(b.generation, a.generation);
  EXPECT_FALSE(world.is_valid(a));
}

TEST(World2DBodies, RefusesBadDefinitionsAndChangesNothing) {
  World2D world;
  BodyDef2D def;
  def.shape = *make_circle(1_fx);
  def.density = Fx();
  EXPECT_EQ(world.create_body(def).status().code(), ErrorCode::kInvalidArgument);
  def.density = 1_fx;
  def.material.restitution = 2_fx;
  EXPECT_EQ(world.create_body(def).status().code(), ErrorCode::kInvalidArgument);
  def.material.restitution = Fx();
  def.position = {32500_fx, Fx()};
  EXPECT_EQ(world.create_body(def).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.body_count(), 0u);
  EXPECT_TRUE(world.state().bodies.empty());
}

TEST(World2DBodies, ImpulsesAndVelocitiesOnlyWhereTheyMeanSomething) {
  World2D world;
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_circle(1_fx), {});
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(1_fx), {5_fx, Fx()});
  EXPECT_EQ(world.set_linear_velocity(ground, {1_fx, Fx()}).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.apply_linear_impulse(ground, {1_fx, Fx()}, {}).code(),
            ErrorCode::kInvalidArgument);
  // An impulse of m * 2 m/s at the centre gives 2 m/s and no spin.
  const Fx m = world.mass(ball).to_fx();
  ASSERT_TRUE(world.apply_linear_impulse(ball, {m * 2, Fx()}, {5_fx, Fx()}).ok());
  EXPECT_NEAR(world.linear_velocity(ball).x.raw(), (2_fx).raw(), 8);
  EXPECT_EQ(world.angular_velocity(ball), Fx());
  EXPECT_EQ(world.set_linear_velocity(BodyId2D{7, 1}, {}).code(), ErrorCode::kNotFound);
}

}  // namespace
}  // namespace rwd::sim2d
