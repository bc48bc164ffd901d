// SPDX-License-Identifier: MIT
// Contact events: enter / stay / exit sequences and their order, the
// details they carry (point, normal, depth, impulse), and the per-body
// switch that keeps a body's contacts out of them.
#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;

int count(const World3D& w, ContactEventType type) {
  int n = 0;
  for (const ContactEvent& e : w.events()) n += e.type == type ? 1 : 0;
  return n;
}

TEST(ContactEvents, FallingBoxEntersStaysAndExits) {
  World3D world;
  BodyId ground = add_ground(world);
  BodyId box = add_box(world, {0.0f, 1.5f, 0.0f});
  int enter_step = -1;
  for (int i = 0; i < 120 && enter_step < 0; ++i) {
    world.step();
    if (count(world, ContactEventType::kEnter) > 0) enter_step = i;
    EXPECT_EQ(count(world, ContactEventType::kExit), 0);
  }
  ASSERT_GE(enter_step, 0);
  // Falls 1 m: about 0.45 s.
  EXPECT_NEAR(enter_step, 27, 3);
  const ContactEvent e = world.events()[0];
  EXPECT_EQ(e.a, ground);
  EXPECT_EQ(e.b, box);
  EXPECT_FALSE(e.sensor);
  for (int i = 0; i < 10; ++i) {
    world.step();
    ASSERT_EQ(world.events().size(), 1u);
    EXPECT_EQ(world.events()[0].type, ContactEventType::kStay);
  }
  // Lift it away: exit once, then silence.
  ASSERT_TRUE(world.set_transform(box, {0.0f, 5.0f, 0.0f}, Quat{}).ok());
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  EXPECT_EQ(world.events()[0].type, ContactEventType::kExit);
  world.step();
  EXPECT_TRUE(world.events().empty());
}

TEST(ContactEvents, DestroyEmitsExitOnTheNextStep) {
  World3D world;
  BodyId ground = add_ground(world);
  BodyId box = add_box(world, {0.0f, 0.5f, 0.0f});
  world.step();
  ASSERT_EQ(count(world, ContactEventType::kEnter), 1);
  ASSERT_TRUE(world.destroy_body(box).ok());
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  const ContactEvent e = world.events()[0];
  EXPECT_EQ(e.type, ContactEventType::kExit);
  EXPECT_EQ(e.a, ground);
  EXPECT_EQ(e.b, box);  // the destroyed id, generation included
  world.step();
  EXPECT_TRUE(world.events().empty());
}

TEST(ContactEvents, SlotReuseGivesExitOfOldAndEnterOfNew) {
  World3D world;
  add_ground(world);
  BodyId old_box = add_box(world, {0.0f, 0.5f, 0.0f});
  world.step();
  ASSERT_TRUE(world.destroy_body(old_box).ok());
  BodyId new_box = add_box(world, {0.0f, 0.5f, 0.0f});
  ASSERT_EQ(new_box.index, old_box.index);
  ASSERT_EQ(new_box.generation, old_box.generation + 1);
  world.step();
  ASSERT_EQ(world.events().size(), 2u);
  EXPECT_EQ(world.events()[0].type, ContactEventType::kEnter);
  EXPECT_EQ(world.events()[0].b, new_box);
  EXPECT_EQ(world.events()[1].type, ContactEventType::kExit);
  EXPECT_EQ(world.events()[1].b, old_box);
}

TEST(ContactEvents, OrderedByIndexPairAndSensorsReportButDoNotPush) {
  World3D world;
  add_ground(world);
  BodyDef sensor;
  sensor.kind = BodyKind::kStatic;
  sensor.sensor = true;
  sensor.shape = Shape::make_box({3.0f, 1.0f, 3.0f});
  sensor.position = {0.0f, 1.0f, 0.0f};
  BodyId zone = *world.create_body(sensor);
  BodyId b1 = add_box(world, {1.0f, 0.5f, 0.0f});
  BodyId b2 = add_box(world, {-1.0f, 0.5f, 0.0f});
  world.step();
  auto events = world.events();
  ASSERT_EQ(events.size(), 4u);  // ground-b1, ground-b2, zone-b1, zone-b2
  for (size_t i = 1; i < events.size(); ++i) {
    bool ordered =
        events[i - 1].a.index < events[i].a.index ||
        (events[i - 1].a.index == events[i].a.index && events[i - 1].b.index < events[i].b.index);
    EXPECT_TRUE(ordered) << i;
  }
  EXPECT_EQ(events[2].a, zone);
  EXPECT_EQ(events[2].b, b1);
  EXPECT_TRUE(events[2].sensor);
  EXPECT_EQ(events[3].b, b2);
  // A dynamic box inside a sensor is not pushed: it rests on the ground.
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_NEAR(world.position(b1).y, 0.5f, 0.01f);
  EXPECT_NEAR(world.position(b1).x, 1.0f, 0.01f);
}

TEST(ContactEvents, StayEventsCarryPointNormalDepthAndImpulse) {
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  const BodyId ground = add_ground(world);
  const BodyId box = add_box(world, {1.0f, 0.52f, 2.0f});
  test::step_seconds(world, 1.0f);
  ASSERT_EQ(world.events().size(), 1u);
  const ContactEvent e = world.events()[0];
  EXPECT_EQ(e.type, ContactEventType::kStay);
  EXPECT_EQ(e.a, ground);
  EXPECT_EQ(e.b, box);
  EXPECT_NEAR(e.normal.y, 1.0f, 1e-4f);  // from the ground up to the box
  EXPECT_NEAR(e.point.y, 0.0f, c.linear_slop_m);
  EXPECT_NEAR(e.point.x, 1.0f, 0.51f);  // a corner of the box's base
  EXPECT_NEAR(e.point.z, 2.0f, 0.51f);
  EXPECT_GE(e.depth, 0.0f);
  EXPECT_LE(e.depth, c.linear_slop_m + 1e-3f);
  // At rest the ground holds the box's weight: m g per tick.
  const float weight_per_tick = world.mass(box) * 9.81f * c.tick_seconds;
  EXPECT_NEAR(e.impulse, weight_per_tick, 0.05f * weight_per_tick);
}

TEST(ContactEvents, ARollingBallReportsItsWeight) {
  // A rolling ball's contact lifts off its anchor late in each tick; the
  // event still reports the tick's whole normal impulse, m g per tick.
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  add_ground(world);
  BodyDef ball;
  ball.shape = Shape::make_sphere(0.25f);
  ball.position = {-20.0f, 0.25f, 0.0f};
  ball.linear_velocity = {3.0f, 0.0f, 0.0f};
  ball.angular_velocity = {0.0f, 0.0f, -12.0f};
  const BodyId b = *world.create_body(ball);
  test::step_seconds(world, 0.5f);
  ASSERT_EQ(world.events().size(), 1u);
  const float weight_per_tick = world.mass(b) * 9.81f * c.tick_seconds;
  EXPECT_NEAR(world.events()[0].impulse, weight_per_tick, 0.1f * weight_per_tick);
}

// A fast body is stopped by a speculative contact before its surfaces
// meet: the tick whose impulse stops it is the tick that reports it, with
// that impulse, and the next tick's stay carries only the resting weight.
TEST(ContactEvents, AnImpactIsReportedInTheTickItsImpulseIsApplied) {
  for (const float speed : {4.0f, 8.0f, 15.0f}) {
    SCOPED_TRACE(speed);
    World3D world;
    add_ground(world);
    const BodyId box = add_box(world, {0.0f, 2.0f, 0.0f});
    ASSERT_TRUE(world.set_linear_velocity(box, {0.0f, -speed, 0.0f}).ok());
    const float mass = world.mass(box);
    const float dt = world.config().tick_seconds;
    const float gravity = world.config().gravity.y;
    bool impacted = false;
    for (int i = 0; i < 120 && !impacted; ++i) {
      const float before = world.linear_velocity(box).y;
      world.step();
      // N s the ground pushed with this tick: the momentum change less gravity's.
      const float pushed = mass * (world.linear_velocity(box).y - before) - mass * gravity * dt;
      if (pushed < 0.05f * mass * speed) {
        EXPECT_EQ(count(world, ContactEventType::kEnter), 0) << "tick " << i;
        continue;
      }
      impacted = true;
      ASSERT_EQ(count(world, ContactEventType::kEnter), 1)
          << "tick " << i << ": impulse " << pushed << " N s with no event";
      EXPECT_NEAR(world.events()[0].impulse, pushed, 0.05f * pushed);
      world.step();
      ASSERT_EQ(count(world, ContactEventType::kStay), 1);
      EXPECT_LT(world.events()[0].impulse, 0.25f * pushed);
    }
    EXPECT_TRUE(impacted);
  }
}

TEST(ContactEvents, SensorEventsCarryTheOverlap) {
  World3D world;
  BodyDef zone;
  zone.kind = BodyKind::kStatic;
  zone.sensor = true;
  zone.shape = Shape::make_box({1.0f, 1.0f, 1.0f});
  const BodyId z = *world.create_body(zone);
  BodyDef ball;
  ball.shape = Shape::make_sphere(0.5f);
  ball.position = {0.0f, 1.3f, 0.0f};
  ball.gravity_scale = 0.0f;
  const BodyId b = *world.create_body(ball);
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  const ContactEvent e = world.events()[0];
  EXPECT_TRUE(e.sensor);
  EXPECT_EQ(e.a, z);
  EXPECT_EQ(e.b, b);
  EXPECT_NEAR(e.normal.y, 1.0f, 1e-4f);
  EXPECT_NEAR(e.depth, 0.2f, 1e-3f);  // the ball reaches 0.2 m into the zone
  EXPECT_EQ(e.impulse, 0.0f);
}

TEST(ContactEvents, BodiesCanKeepTheirContactsOutOfEvents) {
  World3D world;
  const BodyId ground = add_ground(world);
  BodyDef quiet;
  quiet.position = {0.0f, 0.5f, 0.0f};
  quiet.contact_events = false;
  const BodyId debris = *world.create_body(quiet);
  const BodyId loud = add_box(world, {3.0f, 0.5f, 0.0f});
  world.step();
  // The ground reports, so both pairs would show; switch the ground off.
  EXPECT_EQ(world.events().size(), 2u);
  ASSERT_TRUE(world.set_contact_events(ground, false).ok());
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  EXPECT_EQ(world.events()[0].b, loud);
  // The debris's pair still exists (it rests); it just is not reported.
  ASSERT_TRUE(world.set_contact_events(debris, true).ok());
  world.step();
  EXPECT_EQ(world.events().size(), 2u);
  EXPECT_EQ(world.set_contact_events(BodyId{77, 1}, true).code(), ErrorCode::kNotFound);
}

}  // namespace
}  // namespace rwd::sim
