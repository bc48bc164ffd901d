// SPDX-License-Identifier: MIT
// A world whose every body sleeps skips its steps (WorldState::at_rest):
// the skipped steps must be exactly the steps the stages would have run,
// and anything that changes a body must end the skipping.
#include <gtest/gtest.h>

#include <vector>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;
using test::add_sphere;

// A small pyramid, a ball and a lone box on the ground, stepped until every
// body sleeps. Ids of the ball and the lone box in `ball` and `lone`.
void build_resting(World3D& world, BodyId& ball, BodyId& lone) {
  add_ground(world);
  for (int row = 0; row < 4; ++row) {
    for (int i = 0; i < 4 - row; ++i) {
      add_box(world,
              {static_cast<float>(i) * 1.02f + 0.51f * static_cast<float>(row), 0.5f + row, 0.0f});
    }
  }
  ball = add_sphere(world, {-3.0f, 0.5f, 0.0f});
  lone = add_box(world, {6.0f, 0.5f, 0.0f});
  for (int t = 0; t < 1200 && (t < 2 || world.stats().awake_bodies > 0); ++t) world.step();
  ASSERT_EQ(world.stats().awake_bodies, 0u) << "the scene did not fall asleep";
}

struct Step {
  uint64_t checksum;
  std::vector<uint8_t> bytes;
  std::vector<ContactEvent> events;
  uint32_t awake, pairs, touching, points;
};

Step record(const World3D& world) {
  Step s;
  s.checksum = world.checksum();
  world.serialize(s.bytes);
  s.events.assign(world.events().begin(), world.events().end());
  const StepStats& st = world.stats();
  s.awake = st.awake_bodies;
  s.pairs = st.broadphase_pairs;
  s.touching = st.touching_manifolds;
  s.points = st.contact_points;
  return s;
}

void expect_same(const Step& skipped, const Step& full, int tick) {
  EXPECT_EQ(skipped.checksum, full.checksum) << "tick " << tick;
  EXPECT_EQ(skipped.bytes, full.bytes) << "tick " << tick;
  ASSERT_EQ(skipped.events.size(), full.events.size()) << "tick " << tick;
  for (size_t e = 0; e < full.events.size(); ++e) {
    EXPECT_EQ(skipped.events[e].type, full.events[e].type) << "tick " << tick;
    EXPECT_EQ(skipped.events[e].a, full.events[e].a) << "tick " << tick;
    EXPECT_EQ(skipped.events[e].b, full.events[e].b) << "tick " << tick;
  }
  EXPECT_EQ(skipped.awake, full.awake) << "tick " << tick;
  EXPECT_EQ(skipped.pairs, full.pairs) << "tick " << tick;
  EXPECT_EQ(skipped.touching, full.touching) << "tick " << tick;
  EXPECT_EQ(skipped.points, full.points) << "tick " << tick;
}

// Runs `change` on two identical resting worlds, then steps one as it
// steps itself (skipping while at rest) and the other through a restore
// of its own state before every step (which ends any rest, so the stages
// always run); both must agree on every tick.
template <class Change>
void expect_skipping_is_stepping(Change change, int ticks = 90) {
  World3D skipping;
  World3D stepping;
  BodyId ball, lone, ball2, lone2;
  build_resting(skipping, ball, lone);
  build_resting(stepping, ball2, lone2);
  ASSERT_EQ(skipping.checksum(), stepping.checksum());
  change(skipping, ball, lone);
  change(stepping, ball2, lone2);
  for (int t = 0; t < ticks; ++t) {
    skipping.step();
    WorldState state;
    stepping.save(state);
    stepping.restore(state);
    stepping.step();
    expect_same(record(skipping), record(stepping), t);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(WorldAtRest, SkippedStepsAreTheStepsTheStagesWouldRun) {
  expect_skipping_is_stepping([](World3D&, BodyId, BodyId) {});
}

TEST(WorldAtRest, ASleepingWorldReportsNothingAndKeepsItsContacts) {
  World3D world;
  BodyId ball, lone;
  build_resting(world, ball, lone);
  world.step();
  const StepStats rest = world.stats();
  const uint64_t before = world.step_count();
  const Vec3 where = world.position(ball);
  for (int t = 0; t < 30; ++t) world.step();
  EXPECT_EQ(world.step_count(), before + 30);
  EXPECT_TRUE(world.events().empty());
  EXPECT_EQ(world.stats().touching_manifolds, rest.touching_manifolds);
  EXPECT_GT(world.stats().touching_manifolds, 10u);
  EXPECT_EQ(world.position(ball), where);
}

TEST(WorldAtRest, AnImpulseWakesIt) {
  expect_skipping_is_stepping([](World3D& world, BodyId ball, BodyId) {
    ASSERT_TRUE(world.apply_linear_impulse(ball, {200.0f, 0.0f, 0.0f}, world.position(ball)).ok());
  });
  World3D world;
  BodyId ball, lone;
  build_resting(world, ball, lone);
  const Vec3 where = world.position(ball);
  ASSERT_TRUE(world.apply_linear_impulse(ball, {200.0f, 0.0f, 0.0f}, world.position(ball)).ok());
  world.step();
  EXPECT_GT(world.position(ball).x, where.x);
}

TEST(WorldAtRest, DestroyingABodyOnTheGroundReportsItsExit) {
  // The lone box touches only the static ground: destroying it wakes
  // nobody, and its pair's exit must still be reported.
  expect_skipping_is_stepping(
      [](World3D& world, BodyId, BodyId lone) { ASSERT_TRUE(world.destroy_body(lone).ok()); });
  World3D world;
  BodyId ball, lone;
  build_resting(world, ball, lone);
  ASSERT_TRUE(world.destroy_body(lone).ok());
  world.step();
  bool exit = false;
  for (const ContactEvent& e : world.events()) {
    exit = exit || (e.type == ContactEventType::kExit && e.b == lone);
  }
  EXPECT_TRUE(exit);
}

TEST(WorldAtRest, ANewBodyFalls) {
  expect_skipping_is_stepping([](World3D& world, BodyId, BodyId) {
    add_box(world, {6.0f, 4.0f, 0.0f});
  });
}

TEST(WorldAtRest, MovingOrSwitchingABodyEndsTheRest) {
  expect_skipping_is_stepping([](World3D& world, BodyId, BodyId lone) {
    ASSERT_TRUE(world.set_transform(lone, {6.0f, 3.0f, 0.0f}, Quat{}).ok());
  });
  expect_skipping_is_stepping([](World3D& world, BodyId ball, BodyId) {
    ASSERT_TRUE(world.set_enabled(ball, false).ok());
  });
  expect_skipping_is_stepping([](World3D& world, BodyId, BodyId lone) {
    ASSERT_TRUE(world.set_linear_velocity(lone, {0.0f, 0.0f, 2.0f}).ok());
  });
}

TEST(WorldAtRest, AFewAwakeBodiesAmongSleepingOnesStepAsTheFullMergeWould) {
  // The steady contact cache collides only the records of awake bodies
  // while no body wakes; here the ball rolls into the sleeping pyramid and
  // wakes it, the lone box hops (its ground pair goes and comes back), a
  // new box lands beside it, and everything falls asleep again. Every tick
  // must equal the world restored before the step (a full merge).
  expect_skipping_is_stepping(
      [](World3D& world, BodyId ball, BodyId lone) {
        ASSERT_TRUE(world.set_linear_velocity(ball, {3.0f, 0.0f, 0.0f}).ok());
        ASSERT_TRUE(world.set_linear_velocity(lone, {0.0f, 3.0f, 0.0f}).ok());
        add_box(world, {7.5f, 2.0f, 0.0f});
      },
      600);
}

TEST(WorldAtRest, AJointWakesItsBodies) {
  expect_skipping_is_stepping([](World3D& world, BodyId ball, BodyId lone) {
    JointDef def;
    def.type = JointType::kDistance;
    def.body_a = ball;
    def.body_b = lone;
    def.anchor_a = {};
    def.anchor_b = {};
    def.min_length = 5.0f;
    def.max_length = 5.0f;
    ASSERT_TRUE(world.create_joint(def).ok());
  });
}

TEST(WorldAtRest, ARestoredRestingWorldStepsAlike) {
  World3D world;
  BodyId ball, lone;
  build_resting(world, ball, lone);
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  for (int t = 0; t < 60; ++t) {
    if (t == 30) {
      ASSERT_TRUE(world.apply_torque(ball, {0.0f, 0.0f, 50.0f}).ok());
    }
    world.step();
    sums.push_back(world.checksum());
  }
  world.restore(saved);
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  for (int t = 0; t < 60; ++t) {
    if (t == 30) {
      ASSERT_TRUE(world.apply_torque(ball, {0.0f, 0.0f, 50.0f}).ok());
      ASSERT_TRUE(loaded.apply_torque(ball, {0.0f, 0.0f, 50.0f}).ok());
    }
    world.step();
    loaded.step();
    ASSERT_EQ(world.checksum(), sums[static_cast<size_t>(t)]) << "restored, tick " << t;
    ASSERT_EQ(loaded.checksum(), sums[static_cast<size_t>(t)]) << "loaded, tick " << t;
  }
}

}  // namespace
}  // namespace rwd::sim
