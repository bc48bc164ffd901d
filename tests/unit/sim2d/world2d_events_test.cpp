// SPDX-License-Identifier: MIT
#include <vector>

#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

struct Counts {
  int enter = 0;
  int stay = 0;
  int exit = 0;
};

Counts count(const World2D& world) {
  Counts c;
  for (const ContactEvent2D& e : world.events()) {
    EXPECT_LT(e.a.index, e.b.index);
    if (e.type == ContactEventType2D::kEnter) ++c.enter;
    if (e.type == ContactEventType2D::kStay) ++c.stay;
    if (e.type == ContactEventType2D::kExit) ++c.exit;
  }
  return c;
}

TEST(World2DEvents, EnterOnceThenStayThenExitWhenDestroyed) {
  World2D world;
  testing::add_round_ground(world);
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {Fx(), 1_fx});
  int enters = 0;
  int stays = 0;
  for (int i = 0; i < 120; ++i) {
    world.step();
    const Counts c = count(world);
    enters += c.enter;
    stays += c.stay;
    EXPECT_EQ(c.exit, 0) << "tick " << i;
    if (i == 20) {
      ASSERT_EQ(world.events().size(), 1u);
      const ContactEvent2D& touching = world.events()[0];
      // The ground's normal points up, from the ground (a) to the ball (b).
      EXPECT_EQ(touching.b, ball);
      EXPECT_NEAR(touching.normal.y.raw(), Fx::one().raw(), 4);
    }
  }
  EXPECT_EQ(enters, 1);
  // Stays are reported while the ball is awake; asleep, nothing is.
  EXPECT_GE(stays, 25);
  EXPECT_FALSE(world.is_awake(ball));
  EXPECT_TRUE(world.events().empty());
  ASSERT_TRUE(world.destroy_body(ball).ok());
  world.step();
  const Counts after = count(world);
  EXPECT_EQ(after.exit, 1);
  EXPECT_EQ(after.enter + after.stay, 0);
}

TEST(World2DEvents, SensorsReportOverlapAndNeverPush) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  BodyDef2D zone;
  zone.kind = BodyKind2D::kStatic;
  zone.shape = *make_circle(2_fx);
  zone.sensor = true;
  ASSERT_TRUE(world.create_body(zone).ok());
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {-5_fx, Fx()});
  ASSERT_TRUE(world.set_linear_velocity(ball, {3_fx, Fx()}).ok());
  int enters = 0;
  int exits = 0;
  for (int i = 0; i < 240; ++i) {
    world.step();
    for (const ContactEvent2D& e : world.events()) {
      EXPECT_TRUE(e.sensor);
      enters += e.type == ContactEventType2D::kEnter;
      exits += e.type == ContactEventType2D::kExit;
    }
  }
  EXPECT_EQ(enters, 1);
  EXPECT_EQ(exits, 1);
  // Straight through at an unchanged speed.
  EXPECT_EQ(world.linear_velocity(ball), (Vec2{3_fx, Fx()}));
}

TEST(World2DEvents, PendingExitSurvivesSaveAndRestore) {
  World2D world;
  testing::add_round_ground(world);
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {Fx(), 0.5_fx});
  for (int i = 0; i < 10; ++i) world.step();
  ASSERT_TRUE(world.set_enabled(ball, false).ok());
  World2DState saved;
  world.save(saved);
  world.step();
  const Counts first = count(world);
  world.restore(saved);
  EXPECT_TRUE(world.events().empty());
  world.step();
  const Counts again = count(world);
  EXPECT_EQ(first.exit, 1);
  EXPECT_EQ(again.exit, 1);
}

TEST(World2DEvents, TriggersAreSolidReportedAsTriggersAndSkippedByQueries) {
  World2D world;
  BodyDef2D plate;
  plate.kind = BodyKind2D::kStatic;
  plate.shape = *make_box(2_fx, 0.5_fx);
  plate.position = {Fx(), -0.5_fx};
  plate.trigger = true;
  const BodyId2D pad = *world.create_body(plate);
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {Fx(), 1_fx});
  bool reported = false;
  for (int i = 0; i < 60; ++i) {
    world.step();
    for (const ContactEvent2D& e : world.events()) {
      EXPECT_TRUE(e.trigger);
      EXPECT_FALSE(e.sensor);
      reported = reported || e.type == ContactEventType2D::kEnter;
    }
  }
  EXPECT_TRUE(reported);
  // Solid: the ball rests on the plate (centre 0.5 m above its top).
  EXPECT_NEAR(world.position(ball).y.raw(), (0.5_fx).raw(), (0.006_fx).raw());
  // Queries see it only when asked.
  EXPECT_FALSE(world.raycast({3_fx, -0.5_fx}, {-6_fx, Fx()}).has_value());
  QueryFilter2D with_triggers;
  with_triggers.include_triggers = true;
  const auto hit = world.raycast({3_fx, -0.5_fx}, {-6_fx, Fx()}, with_triggers);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, pad);
}

}  // namespace
}  // namespace rwd::sim2d
