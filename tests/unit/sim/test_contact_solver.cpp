// SPDX-License-Identifier: MIT
// Solver behaviour against analytic expectations: resting contact, stacking,
// restitution, Coulomb friction on a slope, kinematic pushing.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;
using test::add_sphere;
using test::step_seconds;

WorldConfig no_sleep() {
  WorldConfig c;
  c.enable_sleep = false;
  return c;
}

TEST(ContactSolver, BoxRestsOnGround) {
  World3D world(no_sleep());
  add_ground(world);
  BodyId box = add_box(world, {0.0f, 1.0f, 0.0f});
  step_seconds(world, 2.0f);
  float speed = length(world.linear_velocity(box)) + length(world.angular_velocity(box));
  float penetration = 0.5f - world.position(box).y;  // bottom face below y = 0
  EXPECT_LT(speed, 1e-3f);
  EXPECT_LE(penetration, 2.0f * world.config().linear_slop_m);
  EXPECT_GT(world.position(box).y, 0.49f);
  RecordProperty("resting_penetration_m", std::to_string(penetration));
  std::printf("box resting penetration %.6f m, speed %.2e m/s\n", penetration, speed);
}

TEST(ContactSolver, SphereRestsOnGround) {
  World3D world(no_sleep());
  add_ground(world);
  BodyId ball = add_sphere(world, {0.0f, 2.0f, 0.0f}, 0.5f);
  step_seconds(world, 2.0f);
  float speed = length(world.linear_velocity(ball));
  float penetration = 0.5f - world.position(ball).y;
  EXPECT_LT(speed, 1e-3f);
  EXPECT_LE(penetration, 2.0f * world.config().linear_slop_m);
  EXPECT_GT(world.position(ball).y, 0.49f);
  std::printf("sphere resting penetration %.6f m, speed %.2e m/s\n", penetration, speed);
}

// A box created inside the ground is pushed out on push velocities, never
// real ones: a shallow overlap (within four slops past the slop, pushed out
// in the solver's lanes) and a deep one (pushed out on its own, the ground
// held) both end within the slop plus a millimetre, and the box never
// moves faster than a few centimetres per second while it rises.
TEST(ContactSolver, ShallowAndDeepOverlapsArePushedOutWithoutSpeed) {
  for (const float depth : {0.012f, 0.1f}) {
    World3D world(no_sleep());
    add_ground(world);
    BodyId box = add_box(world, {0.0f, 0.5f - depth, 0.0f});
    float fastest = 0.0f;
    for (int tick = 0; tick < 60; ++tick) {
      world.step();
      fastest = std::max(fastest, length(world.linear_velocity(box)));
    }
    const float penetration = 0.5f - world.position(box).y;
    EXPECT_LE(penetration, world.config().linear_slop_m + 0.001f) << "depth " << depth;
    EXPECT_LT(fastest, 0.05f) << "depth " << depth;
    std::printf("overlap %.3f m: %.2f mm left after 1 s, fastest %.4f m/s\n", depth,
                1000.0f * penetration, fastest);
  }
}

TEST(ContactSolver, TenBoxStackStands) {
  World3D world(no_sleep());
  add_ground(world);
  BodyId boxes[10];
  for (int i = 0; i < 10; ++i) {
    boxes[i] = add_box(world, {0.0f, 0.5f + 1.0f * static_cast<float>(i), 0.0f});
  }
  Vec3 top_start = world.position(boxes[9]);
  step_seconds(world, 10.0f);
  Vec3 top = world.position(boxes[9]);
  float drift = std::sqrt((top.x - top_start.x) * (top.x - top_start.x) +
                          (top.z - top_start.z) * (top.z - top_start.z));
  float sink = top_start.y - top.y;
  EXPECT_LT(drift, 0.05f);
  // Each of the ten contacts may hold up to 2 x linear_slop of penetration.
  EXPECT_LT(sink, 10.0f * 2.0f * world.config().linear_slop_m);
  for (int i = 0; i < 10; ++i) {
    EXPECT_NEAR(world.position(boxes[i]).x, 0.0f, 0.05f) << i;
    EXPECT_NEAR(world.position(boxes[i]).z, 0.0f, 0.05f) << i;
  }
  std::printf("stack top drift %.6f m (horizontal), sink %.6f m\n", drift, sink);
}

TEST(ContactSolver, RestitutionBounceHeight) {
  // A ball dropped from h rebounds to e^2 h when the bounce is elastic in
  // the normal direction with coefficient e.
  for (float e : {0.5f, 0.8f}) {
    World3D world(no_sleep());
    add_ground(world);
    const float radius = 0.25f;
    const float drop = 2.0f;
    BodyId ball = add_sphere(world, {0.0f, radius + drop, 0.0f}, radius, e);
    bool bounced = false;
    float apex = 0.0f;
    for (int i = 0; i < 240; ++i) {
      world.step();
      float vy = world.linear_velocity(ball).y;
      float y = world.position(ball).y - radius;
      if (vy > 0.0f) bounced = true;
      if (bounced) {
        if (y > apex) apex = y;
        if (vy < 0.0f) break;
      }
    }
    ASSERT_TRUE(bounced);
    float expected = e * e * drop;
    // Tolerance: the discrete step samples the apex (v*dt ~ 1 cm) and the
    // impact happens mid-step; 7% covers both at 60 Hz.
    EXPECT_NEAR(apex, expected, 0.07f * expected) << "e = " << e;
    std::printf("restitution %.2f: apex %.4f m, expected %.4f m\n", e, apex, expected);
  }
}

// A box on a plane tilted by `angle` radians about z, friction mu on both.
float slide_distance(float angle, float mu) {
  World3D world(no_sleep());
  float c = det_cos(0.5f * angle);
  float s = det_sin(0.5f * angle);
  Quat tilt{0.0f, 0.0f, s, c};
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box({20.0f, 0.5f, 20.0f});
  ground.rotation = tilt;
  ground.material.friction = mu;
  EXPECT_TRUE(world.create_body(ground).ok());
  BodyDef box;
  box.shape = Shape::make_box({0.5f, 0.5f, 0.5f});
  box.rotation = tilt;
  box.position = rotate(tilt, Vec3{0.0f, 1.0f, 0.0f});  // resting on the plane
  box.material.friction = mu;
  BodyId id = *world.create_body(box);
  Vec3 start = world.position(id);
  step_seconds(world, 2.0f);
  return length(world.position(id) - start);
}

TEST(ContactSolver, FrictionHoldsBelowAndSlidesAboveTheFrictionAngle) {
  const float mu = 0.5f;
  const float friction_angle = det_atan2(mu, 1.0f);  // 26.6 degrees
  float below = slide_distance(friction_angle - 0.08f, mu);
  float above = slide_distance(friction_angle + 0.08f, mu);
  EXPECT_LT(below, 0.02f);
  EXPECT_GT(above, 0.3f);
  std::printf("slope: %.4f m below the friction angle, %.4f m above\n", below, above);
}

TEST(ContactSolver, KinematicBodyPushesDynamicBox) {
  World3D world(no_sleep());
  add_ground(world, 0.3f);
  BodyId box = add_box(world, {0.0f, 0.5f, 0.0f});
  BodyDef pusher;
  pusher.kind = BodyKind::kKinematic;
  pusher.shape = Shape::make_box({0.25f, 0.5f, 1.0f});
  pusher.position = {-1.5f, 0.5f, 0.0f};
  pusher.linear_velocity = {1.0f, 0.0f, 0.0f};
  BodyId k = *world.create_body(pusher);
  step_seconds(world, 3.0f);
  // The pusher moved 3 m and is unaffected by the contact.
  EXPECT_NEAR(world.position(k).x, 1.5f, 1e-3f);
  EXPECT_NEAR(world.linear_velocity(k).x, 1.0f, 1e-6f);
  // The box was pushed ahead of the pusher's front face (x = pusher + 0.25).
  float front = world.position(k).x + 0.25f;
  EXPECT_GT(world.position(box).x, front + 0.5f - 0.03f);
  EXPECT_GT(world.position(box).x, 1.0f);
}

}  // namespace
}  // namespace rwd::sim
