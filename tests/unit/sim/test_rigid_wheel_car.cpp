// SPDX-License-Identifier: MIT
// The rigid-wheel car, the other vehicle recipe beside the raycast wheels
// (vehicle3d.h): a chassis box on four sphere wheels, each on a hinge
// whose motor drives it; the front wheels hang from knuckles, hinged to
// the chassis about the vertical, that a stiff spring turns to the
// steering angle. The whole car is one joint tree, solved exactly.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr Vec3 kX{1.0f, 0.0f, 0.0f};
constexpr Vec3 kY{0.0f, 1.0f, 0.0f};

struct RigidWheelCar {
  static constexpr float kRadius = 0.4f;
  static constexpr float kWheelBase = 3.0f;  // front axle to rear axle, m
  World3D world;
  BodyId chassis;
  BodyId wheels[4];     // front left, front right, rear left, rear right
  JointId axles[4];     // wheel hinges about x
  JointId steering[2];  // knuckle hinges about y
  std::vector<JointDef> defs;

  RigidWheelCar() {
    test::add_ground(world, 1.0f);
    BodyDef body;
    body.shape = Shape::make_box({0.6f, 0.25f, 2.0f});
    body.position = {0.0f, 1.0f, 0.0f};
    body.density = 150.0f;
    chassis = *world.create_body(body);
    for (int i = 0; i < 4; ++i) {
      const float x = i % 2 == 0 ? -1.1f : 1.1f;
      const float z = i < 2 ? 0.5f * kWheelBase : -0.5f * kWheelBase;
      const Vec3 hub{x, kRadius, z};
      BodyDef wheel;
      wheel.shape = Shape::make_sphere(kRadius);
      wheel.position = hub;
      wheel.density = 300.0f;
      wheel.material.friction = 1.0f;
      wheels[i] = *world.create_body(wheel);
      BodyId carrier = chassis;
      if (i < 2) {
        // A knuckle between the chassis and the front wheel, turned about
        // the vertical by a stiff spring toward the steering angle.
        BodyDef knuckle;
        knuckle.shape = Shape::make_box({0.08f, 0.08f, 0.08f});
        knuckle.position = {x * 0.85f, kRadius, z};
        knuckle.density = 500.0f;
        const BodyId k = *world.create_body(knuckle);
        JointDef steer = joint_at(world, JointType::kHinge, chassis, k, knuckle.position, kY);
        steer.enable_spring = true;
        steer.hertz = 8.0f;
        steer.damping_ratio = 1.0f;
        steer.enable_limit = true;
        steer.lower = -0.6f;
        steer.upper = 0.6f;
        steering[i] = *world.create_joint(steer);
        defs.push_back(steer);
        carrier = k;
      }
      JointDef axle = joint_at(world, JointType::kHinge, carrier, wheels[i], hub, kX);
      axle.enable_motor = true;
      axle.max_motor_torque = 400.0f;
      axles[i] = *world.create_joint(axle);
      defs.push_back(axle);
    }
  }

  /// Drives every wheel toward `speed` m/s on the ground (a wheel rolling
  /// toward +z turns at speed / radius about +x) and steers the front
  /// knuckles to `steer` rad.
  void drive(float speed, float steer) {
    for (const JointId axle : axles) {
      ASSERT_TRUE(world.set_joint_motor(axle, true, speed / kRadius, 400.0f).ok());
    }
    for (const JointId s : steering) ASSERT_TRUE(world.set_joint_spring_target(s, steer).ok());
  }

  float forward_speed() const {
    const Vec3 forward = rotate(world.rotation(chassis), {0.0f, 0.0f, 1.0f});
    return dot(world.linear_velocity(chassis), forward);
  }

  float worst_opening() const {
    float worst = 0.0f;
    for (const JointDef& d : defs) {
      const Vec3 pa = world.position(d.body_a) + rotate(world.rotation(d.body_a), d.anchor_a);
      const Vec3 pb = world.position(d.body_b) + rotate(world.rotation(d.body_b), d.anchor_b);
      worst = std::max(worst, length(pb - pa));
    }
    return worst;
  }
};

TEST(RigidWheelCar, DrivesAtItsMotorSpeedAndTurnsWhereItIsSteered) {
  RigidWheelCar car;
  car.drive(5.0f, 0.0f);
  float opening = 0.0f;
  for (int i = 0; i < 240; ++i) {
    car.world.step();
    opening = std::max(opening, car.worst_opening());
  }
  const float straight = car.forward_speed();
  const Vec3 heading = rotate(car.world.rotation(car.chassis), {0.0f, 0.0f, 1.0f});
  std::printf(
      "[ measured ] rigid-wheel car: %.3f m/s after 4 s (motors at 5 m/s), heading x %.4f, "
      "worst joint opening %.3f mm\n",
      straight, heading.x, 1000.0 * opening);
  EXPECT_NEAR(straight, 5.0f, 0.1f);
  EXPECT_LT(std::fabs(heading.x), 0.02f);
  EXPECT_LT(opening, 0.01f);
  // Steered left (a positive turn about +y), it turns left: its yaw rate
  // near v tan(steer) / wheelbase, the bicycle model's.
  car.drive(5.0f, 0.3f);
  for (int i = 0; i < 120; ++i) car.world.step();
  const float yaw_rate = car.world.angular_velocity(car.chassis).y;
  std::printf("[ measured ] steering angles %.4f %.4f rad\n",
              car.world.joint_position(car.steering[0]), car.world.joint_position(car.steering[1]));
  const float expected = car.forward_speed() * std::tan(0.3f) / RigidWheelCar::kWheelBase;
  std::printf(
      "[ measured ] steered 0.3 rad at %.3f m/s: yaw rate %.4f rad/s (bicycle model %.4f)\n",
      car.forward_speed(), yaw_rate, expected);
  EXPECT_GT(yaw_rate, 0.5f * expected);
  EXPECT_LT(yaw_rate, 1.5f * expected);
  EXPECT_LT(car.worst_opening(), 0.01f);
}

TEST(RigidWheelCar, RestoreAndReStepIsBitForBit) {
  RigidWheelCar car;
  car.drive(4.0f, 0.2f);
  std::vector<uint64_t> reference;
  WorldState saved;
  for (int i = 0; i < 90; ++i) {
    if (i == 20) car.world.save(saved);
    car.world.step();
    reference.push_back(car.world.checksum());
  }
  car.world.restore(saved);
  for (int i = 20; i < 90; ++i) {
    car.world.step();
    ASSERT_EQ(car.world.checksum(), reference[static_cast<size_t>(i)]) << i;
  }
  std::vector<uint8_t> bytes;
  car.world.serialize(bytes);
  RigidWheelCar reader;
  ASSERT_TRUE(reader.world.deserialize(bytes).ok());
  for (int i = 0; i < 30; ++i) {
    car.world.step();
    reader.world.step();
    ASSERT_EQ(reader.world.checksum(), car.world.checksum());
  }
}

}  // namespace
}  // namespace rwd::sim
