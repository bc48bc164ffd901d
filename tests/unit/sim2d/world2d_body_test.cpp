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

// A stack, a chain of jointed links lying on the ground and loose balls,
// after a second of settling: destroying a scrambled list of them at once
// leaves the state, the next step's events and every step after exactly as
// destroying them one by one in the same order does; a bad list changes
// nothing.
TEST(World2DBodies, DestroyingSeveralAtOnceIsDestroyingThemInTurn) {
  World2D world;
  testing::add_round_ground(world);
  std::vector<BodyId2D> stack;
  for (int i = 0; i < 4; ++i) {
    stack.push_back(add_body(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.5_fx),
                             {Fx(), Fx::ratio(1001 * i + 500, 1000)}));
  }
  std::vector<BodyId2D> links;
  for (int i = 0; i < 5; ++i) {
    links.push_back(
        add_body(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.1_fx), {Fx(3 + i), 0.1_fx}));
    if (i > 0) {
      JointDef2D def;
      def.body_a = links[i - 1];
      def.body_b = links[i];
      def.anchor_a = {Fx::ratio(5 + 2 * i, 2), 0.1_fx};
      def.anchor_b = def.anchor_a;
      ASSERT_TRUE(world.create_joint(def).ok());
    }
  }
  std::vector<BodyId2D> balls;
  for (int i = 0; i < 3; ++i) {
    balls.push_back(
        add_body(world, BodyKind2D::kDynamic, make_circle(0.3_fx), {Fx(-3 - i), 0.3_fx}));
  }
  for (int t = 0; t < 60; ++t) world.step();
  World2DState settled;
  world.save(settled);
  World2D one_by_one;
  one_by_one.restore(settled);

  const std::vector<BodyId2D> doomed = {stack[2], links[1], balls[0], stack[0], links[3], links[2]};
  const uint64_t before = world.checksum();
  // Refused whole: a stale id in the list, or one body twice.
  std::vector<BodyId2D> stale = doomed;
  stale.push_back(BodyId2D{stack[1].index, stack[1].generation + 1});
  EXPECT_EQ(world.destroy_bodies(stale).code(), ErrorCode::kNotFound);
  std::vector<BodyId2D> twice = doomed;
  twice.push_back(links[1]);
  EXPECT_EQ(world.destroy_bodies(twice).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.checksum(), before);
  EXPECT_EQ(world.body_count(), one_by_one.body_count());

  ASSERT_TRUE(world.destroy_bodies(doomed).ok());
  for (const BodyId2D id : doomed) ASSERT_TRUE(one_by_one.destroy_body(id).ok());
  EXPECT_EQ(world.checksum(), one_by_one.checksum());
  EXPECT_EQ(world.body_count(), one_by_one.body_count());
  EXPECT_EQ(world.joint_count(), 0u);  // each of the four joints lost a link
  for (int t = 0; t < 120; ++t) {
    world.step();
    one_by_one.step();
    ASSERT_EQ(world.checksum(), one_by_one.checksum()) << "tick " << t;
    if (t == 0) {
      // The contacts that went with the bodies end in the same order.
      ASSERT_EQ(world.events().size(), one_by_one.events().size());
      int exits = 0;
      for (size_t k = 0; k < world.events().size(); ++k) {
        const ContactEvent2D& e = world.events()[k];
        const ContactEvent2D& f = one_by_one.events()[k];
        EXPECT_EQ(e.type, f.type);
        EXPECT_EQ(e.a.index, f.a.index);
        EXPECT_EQ(e.b.index, f.b.index);
        exits += e.type == ContactEventType2D::kExit;
      }
      EXPECT_GT(exits, 3);
    }
  }
}

}  // namespace
}  // namespace rwd::sim2d
