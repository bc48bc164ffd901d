// SPDX-License-Identifier: MIT
// The 3D joints at world level: each type holds what it should, limits,
// motors, springs and breaking act at their thresholds, joints keep their
// pair from colliding while intact, join islands, go with their bodies,
// and live in the state (restore and re-step bit for bit, snapshot bytes,
// dump). Bad definitions are refused, naming the field, with the world
// unchanged.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "joint_test_helpers.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using namespace joint_test;

TEST(Joints, BallPendulumKeepsItsAnchorTogether) {
  World3D world;
  const BodyId ball = test::add_sphere(world, {1.0f, 10.0f, 0.0f}, 0.2f);
  const JointDef def = joint_at(world, JointType::kBall, {}, ball, {0.0f, 10.0f, 0.0f});
  make(world, def);
  float worst = 0.0f;
  float lowest = 10.0f;
  for (int i = 0; i < 600; ++i) {
    world.step();
    worst = std::max(worst, anchor_gap(world, {}, def.anchor_a, ball, def.anchor_b));
    lowest = std::min(lowest, world.position(ball).y);
  }
  std::printf("[ measured ] ball pendulum: worst anchor gap %.3f mm, lowest %.3f m\n",
              1000.0 * worst, lowest);
  EXPECT_LT(worst, 0.002f);
  EXPECT_NEAR(lowest, 9.0f, 0.01f);  // swings through the bottom, 1 m below the pivot
}

World3D weightless() {
  WorldConfig config;
  config.gravity = {};
  return World3D(config);
}

TEST(Joints, HingeTurnsAboutItsAxisOnly) {
  World3D world = weightless();
  // A door hinged to the world along y at its left edge, spun about every
  // axis: it keeps only the turn about y.
  const BodyId door = test::add_box(world, {0.5f, 1.0f, 0.0f}, {0.5f, 1.0f, 0.05f});
  const JointDef def = joint_at(world, JointType::kHinge, {}, door, {0.0f, 1.0f, 0.0f}, kY);
  const JointId hinge = make(world, def);
  ASSERT_TRUE(world.set_angular_velocity(door, {2.0f, 1.0f, 3.0f}).ok());
  float worst_gap = 0.0f;
  float worst_tilt = 0.0f;
  for (int i = 0; i < 120; ++i) {
    world.step();
    worst_gap = std::max(worst_gap, anchor_gap(world, {}, def.anchor_a, door, def.anchor_b));
    const Vec3 up = rotate(world.rotation(door), kY);
    worst_tilt = std::max(worst_tilt, std::acos(std::min(1.0f, up.y)));
  }
  const Vec3 w = world.angular_velocity(door);
  std::printf("[ measured ] hinge: gap %.3f mm, axis tilt %.3f deg, w (%.3f %.3f %.3f)\n",
              1000.0 * worst_gap, worst_tilt * 180.0 / kPi, w.x, w.y, w.z);
  EXPECT_LT(worst_gap, 0.005f);
  EXPECT_LT(worst_tilt, 0.5f * kPi / 180.0f);
  EXPECT_LT(std::fabs(w.x) + std::fabs(w.z), 0.01f);
  EXPECT_GT(std::fabs(w.y), 0.1f);
  // The angle it reports follows the door's turn about y.
  const Vec3 side = rotate(world.rotation(door), kX);
  const float turned = std::atan2(-side.z, side.x);
  EXPECT_NEAR(world.joint_position(hinge), turned, 1e-3f);
}

TEST(Joints, HingeLimitsHoldWithinADegree) {
  World3D world;
  // A bar hinged at one end along z, falling under gravity onto its lower
  // limit of -30 degrees; another with its upper limit at +20 pushed up.
  const BodyId bar = test::add_box(world, {0.5f, 5.0f, 0.0f}, {0.5f, 0.05f, 0.05f});
  JointDef def = joint_at(world, JointType::kHinge, {}, bar, {0.0f, 5.0f, 0.0f}, kZ);
  def.enable_limit = true;
  def.lower = -30.0f * kPi / 180.0f;
  def.upper = 20.0f * kPi / 180.0f;
  const JointId hinge = make(world, def);
  float lowest = 0.0f;
  for (int i = 0; i < 240; ++i) {
    world.step();
    lowest = std::min(lowest, world.joint_position(hinge));
  }
  std::printf("[ measured ] hinge lower limit -30 deg: lowest %.3f deg, rest %.3f deg\n",
              lowest * 180.0 / kPi, world.joint_position(hinge) * 180.0 / kPi);
  EXPECT_GT(lowest, def.lower - kPi / 180.0f);
  EXPECT_NEAR(world.joint_position(hinge), def.lower, kPi / 180.0f);
  // Spun hard the other way, it stops at the upper limit.
  ASSERT_TRUE(world.set_angular_velocity(bar, {0.0f, 0.0f, 20.0f}).ok());
  float highest = -10.0f;
  for (int i = 0; i < 30; ++i) {
    world.step();
    highest = std::max(highest, world.joint_position(hinge));
  }
  std::printf("[ measured ] hinge upper limit +20 deg hit at 20 rad/s: highest %.3f deg\n",
              highest * 180.0 / kPi);
  EXPECT_LT(highest, def.upper + kPi / 180.0f);
}

TEST(Joints, HingeMotorReachesItsSpeed) {
  World3D world = weightless();
  const BodyId wheel = add_capsule(world, {0.0f, 2.0f, 0.0f}, 0.3f, 0.2f);
  JointDef def = joint_at(world, JointType::kHinge, {}, wheel, {0.0f, 2.0f, 0.0f}, kY);
  def.enable_motor = true;
  def.motor_speed = 5.0f;
  def.max_motor_torque = 50.0f;
  const JointId motor = make(world, def);
  test::step_seconds(world, 1.0f);
  const float speed = world.angular_velocity(wheel).y;
  std::printf("[ measured ] hinge motor 5 rad/s: %.5f rad/s\n", speed);
  EXPECT_NEAR(speed, 5.0f, 0.05f);
  // A weak motor accelerates at most at its torque over the inertia.
  ASSERT_TRUE(world.set_joint_motor(motor, true, -5.0f, 0.01f).ok());
  world.step();
  EXPECT_GT(world.angular_velocity(wheel).y, 4.0f);
  EXPECT_FALSE(world.set_joint_motor(motor, true, NAN, 1.0f).ok());
}

TEST(Joints, PrismaticSlidesAlongItsAxisBetweenItsLimits) {
  World3D world;
  // A block on a rail tilted 45 degrees in the x-y plane: it slides down
  // to its lower limit at -1 m and does not turn.
  const BodyId block = test::add_box(world, {0.0f, 5.0f, 0.0f}, {0.2f, 0.2f, 0.2f});
  const Vec3 rail = normalize_or_zero(Vec3{1.0f, 1.0f, 0.0f});
  JointDef def = joint_at(world, JointType::kPrismatic, {}, block, {0.0f, 5.0f, 0.0f}, rail);
  def.enable_limit = true;
  def.lower = -1.0f;
  def.upper = 1.0f;
  const JointId slider = make(world, def);
  float off_rail = 0.0f;
  for (int i = 0; i < 180; ++i) {
    world.step();
    const Vec3 p = world.position(block) - Vec3{0.0f, 5.0f, 0.0f};
    off_rail = std::max(off_rail, length(p - rail * dot(p, rail)));
  }
  const Quat q = world.rotation(block);
  std::printf("[ measured ] prismatic: off the rail %.3f mm, at %.4f m (limit -1), turn %.2e\n",
              1000.0 * off_rail, world.joint_position(slider), 1.0 - std::fabs(q.w));
  EXPECT_LT(off_rail, 0.003f);
  EXPECT_NEAR(world.joint_position(slider), -1.0f, 0.01f);
  EXPECT_LT(1.0f - std::fabs(q.w), 1e-4f);
  // A motor drives it back up at 0.5 m/s.
  ASSERT_TRUE(world.set_joint_motor(slider, true, 0.5f, 1000.0f).ok());
  test::step_seconds(world, 0.5f);
  const float along = dot(world.linear_velocity(block), rail);
  std::printf("[ measured ] prismatic motor 0.5 m/s: %.5f m/s\n", along);
  EXPECT_NEAR(along, 0.5f, 0.005f);
}

TEST(Joints, WeldHoldsTwoBodiesAsOne) {
  World3D world;
  test::add_ground(world);
  const BodyId a = test::add_box(world, {0.0f, 3.0f, 0.0f});
  const BodyId b = test::add_box(world, {1.0f, 3.0f, 0.0f}, {0.5f, 0.25f, 0.25f});
  const JointId weld = make(world, joint_at(world, JointType::kWeld, a, b, {0.5f, 3.0f, 0.0f}));
  ASSERT_TRUE(world.set_angular_velocity(a, {1.0f, 2.0f, 0.5f}).ok());
  test::step_seconds(world, 3.0f);
  // In A's frame B still sits 1 m along x, unturned.
  const Vec3 rel = inv_rotate(world.rotation(a), world.position(b) - world.position(a));
  const Quat turn = conjugate(world.rotation(a)) * world.rotation(b);
  std::printf("[ measured ] weld after 3 s: offset error %.3f mm, relative turn %.2e\n",
              1000.0 * length(rel - kX), 1.0 - std::fabs(turn.w));
  EXPECT_LT(length(rel - kX), 0.005f);
  EXPECT_LT(1.0f - std::fabs(turn.w), 1e-4f);
  EXPECT_FALSE(world.is_joint_broken(weld));
}

TEST(Joints, DistanceRodRopeAndSpring) {
  World3D world;
  // A rod holds the distance, a rope only its upper bound, a spring
  // settles where its force carries the weight.
  const BodyId rod_bob = test::add_sphere(world, {0.0f, 8.0f, 0.0f}, 0.1f);
  make(world, joint_between(world, JointType::kDistance, {}, rod_bob, {0.0f, 10.0f, 0.0f},
                            {0.0f, 8.0f, 0.0f}));
  const BodyId rope_bob = test::add_sphere(world, {3.0f, 9.5f, 0.0f}, 0.1f);
  JointDef rope = joint_between(world, JointType::kDistance, {}, rope_bob, {3.0f, 10.0f, 0.0f},
                                {3.0f, 9.5f, 0.0f});
  rope.min_length = 0.0f;
  rope.max_length = 2.0f;
  make(world, rope);
  const BodyId spring_bob = test::add_sphere(world, {6.0f, 9.0f, 0.0f}, 0.1f);
  JointDef spring = joint_between(world, JointType::kSpring, {}, spring_bob, {6.0f, 10.0f, 0.0f},
                                  {6.0f, 9.0f, 0.0f});
  spring.hertz = 2.0f;
  spring.damping_ratio = 1.0f;
  make(world, spring);
  test::step_seconds(world, 4.0f);
  std::printf("[ measured ] rod %.4f m (2), rope %.4f m (max 2), spring at %.4f m\n",
              10.0f - world.position(rod_bob).y, 10.0f - world.position(rope_bob).y,
              10.0f - world.position(spring_bob).y);
  EXPECT_NEAR(10.0f - world.position(rod_bob).y, 2.0f, 0.002f);
  EXPECT_NEAR(10.0f - world.position(rope_bob).y, 2.0f, 0.005f);
  // A spring of f hertz on mass m stretches by g / (2 pi f)^2 under gravity.
  const float omega = 2.0f * kPi * 2.0f;
  const float stretch = 9.81f / (omega * omega);
  EXPECT_NEAR(10.0f - world.position(spring_bob).y, 1.0f + stretch, 0.01f);
}

TEST(Joints, GrabPullsTowardItsTargetWithBoundedForce) {
  World3D world = weightless();
  const BodyId box = test::add_box(world, {0.0f, 0.0f, 0.0f});
  JointDef def = joint_at(world, JointType::kGrab, {}, box, {0.0f, 0.0f, 0.0f});
  def.target = {3.0f, 0.0f, 0.0f};
  def.hertz = 5.0f;
  def.damping_ratio = 1.0f;
  def.max_force = 10.0f;  // the 1000 kg box: at most 0.01 m/s^2
  const JointId grab = make(world, def);
  test::step_seconds(world, 1.0f);
  const float v = world.linear_velocity(box).x;
  std::printf("[ measured ] grab at 10 N on %.0f kg: %.5f m/s after 1 s\n", world.mass(box), v);
  EXPECT_GT(v, 0.0f);
  EXPECT_LE(v, 10.0f / world.mass(box) * 1.0f * 1.001f);
  // Strong enough, it brings the box to the target.
  ASSERT_TRUE(world.destroy_joint(grab).ok());
  def.max_force = 1e6f;
  const JointId strong = make(world, def);
  test::step_seconds(world, 3.0f);
  EXPECT_NEAR(world.position(box).x, 3.0f, 0.01f);
  ASSERT_TRUE(world.set_grab_target(strong, {3.0f, 2.0f, 0.0f}).ok());
  test::step_seconds(world, 3.0f);
  EXPECT_NEAR(world.position(box).y, 2.0f, 0.01f);
  EXPECT_FALSE(world.set_grab_target(strong, {1e9f, 0.0f, 0.0f}).ok());
}

TEST(Joints, BallConeAndTwistLimitsHold) {
  World3D world;
  // A capsule hanging from a ball joint with a 30 degree cone about -y,
  // kicked sideways, and twisted hard against a +-20 degree twist range.
  const Quat upright{};
  const BodyId arm = add_capsule(world, {0.0f, 4.0f, 0.0f}, 0.1f, 0.4f, upright);
  JointDef def = joint_at(world, JointType::kBall, {}, arm, {0.0f, 4.5f, 0.0f}, -kY);
  def.enable_limit = true;
  def.cone_angle = 30.0f * kPi / 180.0f;
  def.twist_lower = -20.0f * kPi / 180.0f;
  def.twist_upper = 20.0f * kPi / 180.0f;
  const JointId ball = make(world, def);
  ASSERT_TRUE(world.set_linear_velocity(arm, {6.0f, 0.0f, 2.0f}).ok());
  ASSERT_TRUE(world.set_angular_velocity(arm, {0.0f, 15.0f, 0.0f}).ok());
  float swing = 0.0f;
  float twist = 0.0f;
  for (int i = 0; i < 240; ++i) {
    world.step();
    swing = std::max(swing, world.joint_swing(ball));
    twist = std::max(twist, std::fabs(world.joint_position(ball)));
  }
  std::printf("[ measured ] cone 30 deg: widest swing %.3f deg; twist 20 deg: widest %.3f deg\n",
              swing * 180.0 / kPi, twist * 180.0 / kPi);
  EXPECT_LT(swing, def.cone_angle + kPi / 180.0f);
  EXPECT_LT(twist, def.twist_upper + kPi / 180.0f);
  EXPECT_GT(swing, 20.0f * kPi / 180.0f);  // it did reach the cone
}

TEST(Joints, BallMotorAndOrientationSpring) {
  World3D world = weightless();
  const BodyId body = test::add_box(world, {0.0f, 0.0f, 0.0f}, {0.3f, 0.2f, 0.1f});
  JointDef def = joint_at(world, JointType::kBall, {}, body, {0.0f, 0.0f, 0.0f});
  def.enable_motor = true;
  def.motor_velocity = {0.0f, 2.0f, 1.0f};
  def.max_motor_torque = 100.0f;
  const JointId ball = make(world, def);
  test::step_seconds(world, 0.5f);
  const Vec3 w = world.angular_velocity(body);
  std::printf("[ measured ] ball motor (0, 2, 1) rad/s: (%.4f %.4f %.4f)\n", w.x, w.y, w.z);
  EXPECT_LT(length(w - def.motor_velocity), 0.02f);
  // Motor off, a stiff damped spring turns it to a quarter turn about z.
  ASSERT_TRUE(world.set_joint_motor_velocity(ball, false, {}, 0.0f).ok());
  const float h = std::sqrt(0.5f);
  ASSERT_TRUE(world.set_joint_spring_rotation(ball, Quat{0.0f, 0.0f, h, h}).ok());
  EXPECT_FALSE(world.set_joint_spring_rotation(ball, Quat{0.0f, 0.0f, 0.0f, 0.0f}).ok());
  // (enable_spring was off at creation: turn it on by recreating.)
  ASSERT_TRUE(world.destroy_joint(ball).ok());
  def.enable_motor = false;
  def.enable_spring = true;
  def.hertz = 3.0f;
  def.damping_ratio = 1.0f;
  def.spring_rotation = Quat{0.0f, 0.0f, h, h};
  make(world, def);
  test::step_seconds(world, 3.0f);
  const Quat q = world.rotation(body);
  const float err = 2.0f * std::acos(std::min(1.0f, std::fabs(q.z * h + q.w * h)));
  std::printf("[ measured ] ball spring to a quarter turn: %.3f deg off\n", err * 180.0 / kPi);
  EXPECT_LT(err, kPi / 180.0f);
}

TEST(Joints, BreakAtTheThresholdAndNotBelow) {
  // A mass hanging still from a joint loads it with m g dt a tick.
  for (const float factor : {0.95f, 1.05f}) {
    World3D world;
    const BodyId bob = test::add_sphere(world, {0.0f, 9.0f, 0.0f}, 0.2f);
    const float load = world.mass(bob) * 9.81f * world.config().tick_seconds;
    JointDef def = joint_between(world, JointType::kDistance, {}, bob, {0.0f, 10.0f, 0.0f},
                                 {0.0f, 9.0f, 0.0f});
    def.break_impulse = factor * load;
    const JointId joint = make(world, def);
    int broke_at = -1;
    for (int i = 0; i < 120 && broke_at < 0; ++i) {
      world.step();
      for (const JointId id : world.broken_joints()) {
        if (id == joint) broke_at = i;
      }
    }
    std::printf("[ measured ] break at %.2f x m g dt: %s (tick %d); reaction %.3f N (m g %.3f)\n",
                factor, broke_at >= 0 ? "broke" : "held", broke_at,
                length(world.joint_reaction(joint).force_n), world.mass(bob) * 9.81f);
    if (factor < 1.0f) {
      EXPECT_GE(broke_at, 0);
      EXPECT_TRUE(world.is_joint_broken(joint));
      // Sticky, inert, and the body falls free.
      test::step_seconds(world, 0.5f);
      EXPECT_TRUE(world.is_joint_broken(joint));
      EXPECT_LT(world.position(bob).y, 8.0f);
    } else {
      EXPECT_LT(broke_at, 0);
      EXPECT_NEAR(world.position(bob).y, 9.0f, 0.01f);
    }
  }
}

TEST(Joints, DisableCollisionKeepsThePairApartUntilItBreaks) {
  World3D world;
  test::add_ground(world);
  // Two boxes built overlapping, welded: no contact between them while
  // the weld holds; a separate pair not jointed does collide.
  const BodyId a = test::add_box(world, {0.0f, 0.5f, 0.0f});
  const BodyId b = test::add_box(world, {0.6f, 0.5f, 0.0f});
  JointDef def = joint_at(world, JointType::kWeld, a, b, {0.3f, 0.5f, 0.0f});
  make(world, def);
  world.step();
  bool pair_touched = false;
  for (int i = 0; i < 30; ++i) {
    world.step();
    pair_touched |= world.contact_manifold(a, b).has_value() &&
                    std::any_of(world.events().begin(), world.events().end(),
                                [&](const ContactEvent& e) { return e.a == a && e.b == b; });
  }
  EXPECT_FALSE(pair_touched);
  EXPECT_LT(length(world.linear_velocity(a)), 0.05f);  // not pushed apart
  // With collisions kept, a joint between overlapping boxes sees them push.
  World3D other;
  test::add_ground(other);
  const BodyId c = test::add_box(other, {0.0f, 0.5f, 0.0f});
  const BodyId d = test::add_box(other, {0.6f, 0.5f, 0.0f});
  JointDef keep =
      joint_between(other, JointType::kDistance, c, d, {0.0f, 0.5f, 0.0f}, {0.6f, 0.5f, 0.0f});
  keep.min_length = 0.0f;
  keep.max_length = 5.0f;
  keep.disable_collision = false;
  make(other, keep);
  test::step_seconds(other, 0.5f);
  EXPECT_GT(length(other.position(d) - other.position(c)), 0.95f);
}

TEST(Joints, DestroyingABodyRemovesItsJointsAndReportsThem) {
  World3D world;
  const BodyId a = test::add_sphere(world, {0.0f, 5.0f, 0.0f}, 0.2f);
  const BodyId b = test::add_sphere(world, {1.0f, 5.0f, 0.0f}, 0.2f);
  const BodyId c = test::add_sphere(world, {2.0f, 5.0f, 0.0f}, 0.2f);
  const JointId ab = make(world, joint_at(world, JointType::kBall, a, b, {0.5f, 5.0f, 0.0f}));
  const JointId bc = make(world, joint_at(world, JointType::kBall, b, c, {1.5f, 5.0f, 0.0f}));
  const JointId top = make(world, joint_at(world, JointType::kBall, {}, a, {0.0f, 6.0f, 0.0f}));
  EXPECT_EQ(world.joint_count(), 3u);
  std::vector<JointId> removed;
  ASSERT_TRUE(world.destroy_body(b, removed).ok());
  EXPECT_EQ(removed, (std::vector<JointId>{ab, bc}));
  EXPECT_FALSE(world.is_valid(ab));
  EXPECT_FALSE(world.is_valid(bc));
  EXPECT_TRUE(world.is_valid(top));
  EXPECT_EQ(world.joint_count(), 1u);
  // The freed slot takes a new generation: the old id stays dead.
  const JointId again = make(world, joint_at(world, JointType::kBall, a, c, {1.0f, 5.0f, 0.0f}));
  EXPECT_EQ(again.index, ab.index);
  EXPECT_NE(again.generation, ab.generation);
  EXPECT_FALSE(world.is_valid(ab));
  EXPECT_EQ(world.destroy_joint(ab).code(), ErrorCode::kNotFound);
  EXPECT_EQ(world.destroy_body(b, removed).code(), ErrorCode::kNotFound);
  EXPECT_TRUE(removed.empty());
}

// A chain of `links` capsules hanging from a static post by ball joints,
// with a ball of `load` times a link's mass at its end.
struct HangingChain {
  World3D world;
  std::vector<BodyId> links;
  BodyId bob;
  float top = 10.0f;
  float link = 0.25f;
  HangingChain(int count, float load) {
    const BodyId post = add_static_box(world, {0.0f, top + 0.2f, 0.0f});
    BodyId prev = post;
    for (int i = 0; i < count; ++i) {
      const float y = top - link * (static_cast<float>(i) + 0.5f);
      const BodyId b = add_capsule(world, {0.0f, y, 0.0f}, 0.05f, 0.5f * link - 0.05f);
      make(world, joint_at(world, JointType::kBall, prev, b,
                           {0.0f, top - link * static_cast<float>(i), 0.0f}));
      links.push_back(b);
      prev = b;
    }
    const float end = top - link * static_cast<float>(count);
    BodyDef def;
    def.shape = Shape::make_sphere(0.15f);
    def.position = {0.0f, end - 0.15f, 0.0f};
    def.density = load * world.mass(links[0]) / (4.0f / 3.0f * kPi * 0.15f * 0.15f * 0.15f);
    bob = *world.create_body(def);
    make(world, joint_at(world, JointType::kBall, prev, bob, {0.0f, end, 0.0f}));
  }
  float stretch() const {
    const float reach =
        length(world.position(bob) + Vec3{0.0f, 0.15f, 0.0f} - Vec3{0.0f, top, 0.0f});
    return reach / (link * static_cast<float>(links.size())) - 1.0f;
  }
};

TEST(Joints, AChainHoldingAHundredTimesALinkBarelyStretches) {
  // The joints of a chain form a tree: solved as one system, a light link
  // holding the heavy ball does not sag the way a row-by-row solve's
  // softness lets it (six per cent).
  HangingChain chain(20, 100.0f);
  ASSERT_NEAR(chain.world.mass(chain.bob) / chain.world.mass(chain.links[0]), 100.0f, 0.5f);
  float worst = 0.0f;
  for (int i = 0; i < 300; ++i) {
    chain.world.step();
    worst = std::max(worst, chain.stretch());
  }
  std::printf("[ measured ] 20-link chain holding 100x a link: worst stretch %.4f%%, asleep %d\n",
              100.0 * worst, chain.world.is_awake(chain.bob) ? 0 : 1);
  EXPECT_LT(worst, 0.001f);
  EXPECT_FALSE(chain.world.is_awake(chain.bob));
  // Swung hard sideways it still holds together.
  ASSERT_TRUE(chain.world.set_linear_velocity(chain.bob, {8.0f, 0.0f, 3.0f}).ok());
  worst = 0.0f;
  for (int i = 0; i < 180; ++i) {
    chain.world.step();
    worst = std::max(worst, chain.stretch());
  }
  std::printf("[ measured ] the same chain swung at 8.5 m/s: worst stretch %.4f%%\n",
              100.0 * worst);
  // Swinging, the ball pulls about 3800 N (m v^2 / r + m g): the chain
  // gives a little under it, and holds.
  EXPECT_LT(worst, 0.025f);
}

TEST(Joints, ALoopOfJointsIsSolvedRowByRowAndHolds) {
  // Four boxes joined in a ring by ball joints (a loop: no tree), one of
  // them pinned to the world: the row-by-row solve keeps it together.
  World3D world;
  const Vec3 corners[4] = {
      {0.0f, 5.0f, 0.0f}, {1.0f, 5.0f, 0.0f}, {1.0f, 5.0f, 1.0f}, {0.0f, 5.0f, 1.0f}};
  BodyId boxes[4];
  for (int i = 0; i < 4; ++i) boxes[i] = test::add_box(world, corners[i], {0.2f, 0.2f, 0.2f});
  std::vector<JointDef> defs;
  for (int i = 0; i < 4; ++i) {
    const Vec3 mid = (corners[i] + corners[(i + 1) % 4]) * 0.5f;
    defs.push_back(joint_at(world, JointType::kBall, boxes[i], boxes[(i + 1) % 4], mid));
    make(world, defs.back());
  }
  make(world, joint_at(world, JointType::kBall, {}, boxes[0], corners[0] + Vec3{0.0f, 0.2f, 0.0f}));
  float worst = 0.0f;
  for (int t = 0; t < 240; ++t) {
    world.step();
    for (int i = 0; i < 4; ++i) {
      const JointDef& d = defs[static_cast<size_t>(i)];
      worst = std::max(worst, anchor_gap(world, d.body_a, d.anchor_a, d.body_b, d.anchor_b));
    }
  }
  std::printf("[ measured ] ring of four ball joints: worst opening %.3f mm\n", 1000.0 * worst);
  EXPECT_LT(worst, 0.01f);
}

TEST(Joints, JointedBodiesSleepTogetherAndWakeTogether) {
  World3D world;
  test::add_ground(world);
  // A chain of three boxes lying on the ground, ball-jointed.
  const BodyId a = test::add_box(world, {0.0f, 0.25f, 0.0f}, {0.25f, 0.25f, 0.25f});
  const BodyId b = test::add_box(world, {0.6f, 0.25f, 0.0f}, {0.25f, 0.25f, 0.25f});
  const BodyId c = test::add_box(world, {1.2f, 0.25f, 0.0f}, {0.25f, 0.25f, 0.25f});
  make(world, joint_at(world, JointType::kBall, a, b, {0.3f, 0.25f, 0.0f}));
  make(world, joint_at(world, JointType::kBall, b, c, {0.9f, 0.25f, 0.0f}));
  test::step_seconds(world, 2.0f);
  EXPECT_FALSE(world.is_awake(a));
  EXPECT_FALSE(world.is_awake(b));
  EXPECT_FALSE(world.is_awake(c));
  // Lifting one end wakes the whole chain on the next step.
  ASSERT_TRUE(world.set_linear_velocity(a, {0.0f, 3.0f, 0.0f}).ok());
  world.step();
  EXPECT_TRUE(world.is_awake(b));
  EXPECT_TRUE(world.is_awake(c));
}

}  // namespace
}  // namespace rwd::sim
