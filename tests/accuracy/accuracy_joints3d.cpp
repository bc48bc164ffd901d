// SPDX-License-Identifier: MIT
// The 3D joints (joint.h) against analytic answers, at the default world
// settings (60 Hz, 4 substeps, g = 9.81 m/s^2): a hinge pendulum's period
// against the physical pendulum's, a hinge motor and a prismatic motor
// holding their speed against gravity, hinge and cone limits driven into
// hard, and the break threshold against the load of a mass hanging still.
// Each check prints its measured figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "rewind/core/det_math.h"
#include "rewind/scenes/joint_scene_meter.h"
#include "rewind/scenes/joint_scenes.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

constexpr double kG = 9.81;
constexpr int kTicksPerSecond = 60;
constexpr double kDegree = 3.14159265358979 / 180.0;
constexpr Vec3 kY{0.0f, 1.0f, 0.0f};
constexpr Vec3 kZ{0.0f, 0.0f, 1.0f};

void report(const std::string& what, double value, const char* unit, const char* bound = "",
            double limit = 0.0) {
  std::cout << "[ measured ] " << what << " = " << value << " " << unit;
  if (*bound != '\0') std::cout << " (" << bound << " " << limit << ")";
  std::cout << "\n";
  std::string key = what;
  for (char& c : key) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

BodyId add_box(World3D& world, Vec3 position, Vec3 half, float angular_damping = 0.05f) {
  BodyDef def;
  def.shape = Shape::make_box(half);
  def.position = position;
  def.angular_damping = angular_damping;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : BodyId{};
}

JointId make(World3D& world, const JointDef& def) {
  auto id = world.create_joint(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : JointId{};
}

// A box rod (0.1 x 1 x 0.1 m, no damping) on a hinge at its end, let go
// 0.05 rad from hanging straight down (the shared scene of
// rewind/scenes/joint_scenes.h). Its period, measured from its zero
// crossings over 10 s (six periods), is within 0.5% of the physical
// pendulum's 2 pi sqrt(I_pivot / (m g d)) (I_pivot = m (w^2 + l^2) / 12 +
// m d^2, d = l / 2; lengthened by 1 + a^2 / 16 for the amplitude a, a
// 0.016% correction).
TEST(AccuracyJoints3D, HingePendulumPeriodIsThePhysicalPendulums) {
  const scenes::JointScene scene = scenes::hinge_pendulum(0.05f);
  World3D world;
  const scenes::RewindJointScene built = scenes::build_rewind(world, scene);
  ASSERT_TRUE(built.error.empty()) << built.error;
  scenes::JointSceneMeter meter(scene);
  std::vector<scenes::JointBodyState> states;
  built.states(world, states);
  meter.observe(states, 0.0);
  for (int t = 1; t <= 10 * kTicksPerSecond; ++t) {
    world.step();
    built.states(world, states);
    meter.observe(states, static_cast<double>(t) / kTicksPerSecond);
  }
  report("pendulum analytic_period_s", scene.analytic_period_s, "s");
  report("pendulum period_s", meter.period_s(), "s");
  report("pendulum zero_crossings", meter.crossings(), "");
  report("pendulum period_error_pct", meter.period_error_pct(), "%", "<=", 0.5);
  report("pendulum worst_opening_m", meter.max_opening_m, "m");
  ASSERT_GE(meter.crossings(), 10);
  EXPECT_LE(meter.period_error_pct(), 0.5);
}

// A 10 kg arm (0.1 x 1 x 0.1 m) on a hinge at its end about a horizontal
// axis, its motor set to 2 rad/s with up to 200 N m: gravity's torque on
// the arm swings between +-49 N m as it goes round, so the motor must work
// to hold its speed. After 2 s of spin-up, the arm's speed about the axis
// stays within 1% of 2 rad/s over the next 3 s (most of a turn).
TEST(AccuracyJoints3D, HingeMotorHoldsItsSpeedUnderLoad) {
  World3D world;
  const BodyId arm = add_box(world, {0.0f, 4.5f, 0.0f}, {0.05f, 0.5f, 0.05f});
  JointDef def = joint_at(world, JointType::kHinge, {}, arm, {0.0f, 5.0f, 0.0f}, kZ);
  def.enable_motor = true;
  def.motor_speed = 2.0f;
  def.max_motor_torque = 200.0f;
  make(world, def);
  for (int t = 0; t < 2 * kTicksPerSecond; ++t) world.step();
  double worst = 0.0;
  double sum = 0.0;
  const int ticks = 3 * kTicksPerSecond;
  for (int t = 0; t < ticks; ++t) {
    world.step();
    const double w = world.angular_velocity(arm).z;
    worst = std::max(worst, 100.0 * std::fabs(w - 2.0) / 2.0);
    sum += w;
  }
  report("hinge_motor load_torque_nm", world.mass(arm) * kG * 0.5, "N m");
  report("hinge_motor mean_speed_radps", sum / ticks, "rad/s");
  report("hinge_motor worst_speed_error_pct", worst, "%", "<=", 1.0);
  EXPECT_LE(worst, 1.0);
}

// A 64 kg block (0.4 m) on a vertical prismatic rail, its motor set to
// 0.5 m/s up with up to 2000 N (its weight is 628 N). After 1 s its speed
// along the rail stays within 1% of 0.5 m/s over the next 2 s.
TEST(AccuracyJoints3D, PrismaticMotorPushesABlockUpAtItsSpeed) {
  World3D world;
  const BodyId block = add_box(world, {0.0f, 5.0f, 0.0f}, {0.2f, 0.2f, 0.2f});
  JointDef def = joint_at(world, JointType::kPrismatic, {}, block, {0.0f, 5.0f, 0.0f}, kY);
  def.enable_motor = true;
  def.motor_speed = 0.5f;
  def.max_motor_force = 2000.0f;
  make(world, def);
  for (int t = 0; t < kTicksPerSecond; ++t) world.step();
  double worst = 0.0;
  double sum = 0.0;
  const int ticks = 2 * kTicksPerSecond;
  for (int t = 0; t < ticks; ++t) {
    world.step();
    const double v = world.linear_velocity(block).y;
    worst = std::max(worst, 100.0 * std::fabs(v - 0.5) / 0.5);
    sum += v;
  }
  report("prismatic_motor load_n", world.mass(block) * kG, "N");
  report("prismatic_motor mean_speed_mps", sum / ticks, "m/s");
  report("prismatic_motor worst_speed_error_pct", worst, "%", "<=", 1.0);
  EXPECT_LE(worst, 1.0);
}

// A 10 kg bar hinged at its end, limits -30 and +20 degrees, spun at
// 20 rad/s into each limit and then held against it by a motor at
// 20 rad/s with up to 500 N m (ten times gravity's torque on the bar), for
// 2 s each way. Criterion: it never goes more than 1 degree past either.
TEST(AccuracyJoints3D, HingeLimitsHoldWithinADegreeWhenDrivenHard) {
  World3D world;
  const BodyId bar = add_box(world, {0.5f, 5.0f, 0.0f}, {0.5f, 0.05f, 0.05f});
  JointDef def = joint_at(world, JointType::kHinge, {}, bar, {0.0f, 5.0f, 0.0f}, kZ);
  def.enable_limit = true;
  def.lower = static_cast<float>(-30.0 * kDegree);
  def.upper = static_cast<float>(20.0 * kDegree);
  const JointId hinge = make(world, def);
  double past = 0.0;
  for (const float dir : {-1.0f, 1.0f}) {
    ASSERT_TRUE(world.set_angular_velocity(bar, {0.0f, 0.0f, 20.0f * dir}).ok());
    ASSERT_TRUE(world.set_joint_motor(hinge, true, 20.0f * dir, 500.0f).ok());
    double extreme = 0.0;
    for (int t = 0; t < 2 * kTicksPerSecond; ++t) {
      world.step();
      const double angle = world.joint_position(hinge);
      const double over = dir < 0.0f ? def.lower - angle : angle - def.upper;
      extreme = std::max(extreme, over);
    }
    report(std::string("hinge_limit ") + (dir < 0.0f ? "lower" : "upper") + "_past_deg",
           extreme / kDegree, "deg", "<=", 1.0);
    report(std::string("hinge_limit ") + (dir < 0.0f ? "lower" : "upper") + "_rest_deg",
           world.joint_position(hinge) / kDegree, "deg");
    past = std::max(past, extreme);
  }
  EXPECT_LE(past / kDegree, 1.0);
}

// A 4 kg arm (0.1 x 0.8 x 0.1 m) hanging from a ball joint at its top with
// a 30 degree cone about straight down, kicked sideways at 8 m/s and
// driven into the cone by the joint's motor (10 rad/s about z with up to
// 500 N m, sixty times gravity's torque at the cone's edge) for 3 s.
// Criterion: its swing never exceeds the cone by more than 1 degree.
TEST(AccuracyJoints3D, BallConeLimitHoldsWithinADegreeWhenDrivenHard) {
  World3D world;
  const BodyId arm = add_box(world, {0.0f, 4.0f, 0.0f}, {0.05f, 0.4f, 0.05f});
  JointDef def = joint_at(world, JointType::kBall, {}, arm, {0.0f, 4.4f, 0.0f}, -kY);
  def.enable_limit = true;
  def.cone_angle = static_cast<float>(30.0 * kDegree);
  def.enable_motor = true;
  def.motor_velocity = {0.0f, 0.0f, 10.0f};
  def.max_motor_torque = 500.0f;
  const JointId ball = make(world, def);
  ASSERT_TRUE(world.set_linear_velocity(arm, {8.0f, 0.0f, 3.0f}).ok());
  double widest = 0.0;
  for (int t = 0; t < 3 * kTicksPerSecond; ++t) {
    world.step();
    widest = std::max(widest, static_cast<double>(world.joint_swing(ball)));
  }
  report("cone_limit widest_swing_deg", widest / kDegree, "deg");
  report("cone_limit past_deg", (widest - def.cone_angle) / kDegree, "deg", "<=", 1.0);
  report("cone_limit rest_swing_deg", world.joint_swing(ball) / kDegree, "deg");
  EXPECT_LE((widest - def.cone_angle) / kDegree, 1.0);
  EXPECT_GT(widest, def.cone_angle - kDegree) << "the arm never reached the cone";
}

// A 33.5 kg sphere hanging still from a joint at its top loads the joint
// with m g dt every tick. Each joint type that can hold it (ball, hinge,
// weld, distance) breaks within the first second at a break_impulse of
// 0.98 m g dt, and holds for 5 s at 1.02 m g dt.
TEST(AccuracyJoints3D, BreakImpulseBreaksAtItsThresholdAndNotBelow) {
  struct Case {
    const char* name;
    JointType type;
  };
  for (const Case c : {Case{"ball", JointType::kBall}, Case{"hinge", JointType::kHinge},
                       Case{"weld", JointType::kWeld}, Case{"distance", JointType::kDistance}}) {
    for (const double factor : {0.98, 1.02}) {
      World3D world;
      BodyDef def;
      def.shape = Shape::make_sphere(0.2f);
      def.position = {0.0f, 9.0f, 0.0f};
      auto bob = world.create_body(def);
      ASSERT_TRUE(bob.ok());
      const double load = world.mass(*bob) * kG * world.config().tick_seconds;
      JointDef j =
          c.type == JointType::kDistance
              ? joint_between(world, c.type, {}, *bob, {0.0f, 10.0f, 0.0f}, {0.0f, 9.2f, 0.0f})
              : joint_at(world, c.type, {}, *bob, {0.0f, 9.2f, 0.0f}, kZ);
      j.break_impulse = static_cast<float>(factor * load);
      const JointId joint = make(world, j);
      int broke_at = -1;
      for (int t = 1; t <= 5 * kTicksPerSecond && broke_at < 0; ++t) {
        world.step();
        for (const JointId id : world.broken_joints()) {
          if (id == joint) broke_at = t;
        }
      }
      report(std::string("break ") + c.name + " at " + (factor < 1.0 ? "0.98" : "1.02") +
                 " m g dt: broke_at_tick",
             broke_at, "");
      if (factor < 1.0) {
        EXPECT_GE(broke_at, 1) << c.name << " held below its load";
        EXPECT_LE(broke_at, kTicksPerSecond) << c.name;
      } else {
        EXPECT_LT(broke_at, 0) << c.name << " broke above its load";
        EXPECT_FALSE(world.is_joint_broken(joint)) << c.name;
        EXPECT_NEAR(world.position(*bob).y, 9.0f, 0.01f) << c.name;
      }
    }
  }
}

}  // namespace
}  // namespace rwd::sim
