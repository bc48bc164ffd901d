// SPDX-License-Identifier: MIT
// The raycast-wheel vehicle (vehicle3d.h) against analytic answers, at the
// default world settings (60 Hz, 4 substeps, g = 9.81 m/s^2), with the
// shared sedan (rewind/scenes/vehicle_scene.h: 1200 kg, four driven
// wheels, 1.5 Hz springs, tire and ground friction 1.0, so mu = 1.0).
// Each check prints its measured figure.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <iostream>
#include <string>

#include "rewind/scenes/vehicle_scene.h"
#include "rewind/sim/vehicle3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

using scenes::add_car;
using scenes::CarSpec;
using scenes::RewindCar;

constexpr double kG = 9.81;
constexpr int kTicksPerSecond = 60;

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

double error_pct(double measured, double expected) {
  return 100.0 * std::fabs(measured - expected) / std::fabs(expected);
}

/// A flat static ground (top at y = 0) of friction 1.0, 2 km long in z.
BodyId add_ground(World3D& world) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_box({50.0f, 0.5f, 1000.0f});
  def.position = {0.0f, -0.5f, 900.0f};
  def.material.friction = 1.0f;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

/// Steps the car with the same controls for `ticks` ticks.
void drive(World3D& world, RewindCar& car, const VehicleControls3D& controls, int ticks) {
  for (int t = 0; t < ticks; ++t) {
    ASSERT_TRUE(car.drive(world, controls).ok());
    world.step();
  }
}

/// The sedan on flat ground, settled for 2 s with no input.
RewindCar settled_car(World3D& world, const CarSpec& spec) {
  add_ground(world);
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(9.81f) + 0.05f, 0.0f});
  drive(world, car, {}, 2 * kTicksPerSecond);
  return car;
}

double speed_z(const World3D& world, BodyId id) {
  return world.linear_velocity(id).z;
}

// Dropped 5 cm above its ride height, the car settles in 3 s (a damping
// ratio of 0.4 at 1.5 Hz decays e^-11 in that time) with each spring
// compressed m g / (k n): within 2%.
TEST(AccuracyVehicle3D, SettlesAtTheStaticCompression) {
  World3D world;
  CarSpec spec;
  add_ground(world);
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(9.81f) + 0.05f, 0.0f});
  drive(world, car, {}, 3 * kTicksPerSecond);
  const double expected = world.mass(car.chassis) * kG / (spec.stiffness_npm * 4.0);
  double worst = 0.0;
  for (const WheelTelemetry3D& t : car.telemetry) {
    ASSERT_TRUE(t.grounded);
    worst = std::max(worst, error_pct(t.compression_m, expected));
  }
  report("vehicle_settle compression_error_pct", worst, "%", "<=", 2.0);
  report("vehicle_settle compression_m", car.telemetry[0].compression_m, "m");
  EXPECT_LE(worst, 2.0);
}

// From rest, a drive force of 3000 N (a quarter of the grip) accelerates
// the 1200 kg car at F / m for 2 s: within 1%. On flat ground the tire
// forces lie in the ground plane whatever the chassis pitch, and nothing
// else pushes horizontally (no drag, no rolling resistance), so the only
// error is rounding; 1% leaves room for the pitch settling in the first
// ticks moving the normal loads, which no force limit reaches here.
TEST(AccuracyVehicle3D, AcceleratesAtForceOverMassBelowTheGrip) {
  World3D world;
  CarSpec spec;
  RewindCar car = settled_car(world, spec);
  const double v0 = speed_z(world, car.chassis);
  drive(world, car, {0.5f, 0.0f, 0.0f}, 2 * kTicksPerSecond);
  const double a = (speed_z(world, car.chassis) - v0) / 2.0;
  const double expected = 0.5 * spec.max_drive_force_n / world.mass(car.chassis);
  report("vehicle_accel a_mps2", a, "m/s^2");
  report("vehicle_accel error_pct", error_pct(a, expected), "%", "<=", 1.0);
  EXPECT_LE(error_pct(a, expected), 1.0);
  for (const WheelTelemetry3D& t : car.telemetry) EXPECT_FALSE(t.saturated);
}

// A drive force of 40,000 N (3.4 times the grip) is cut to the friction
// circle: the car accelerates at mu g for 1.5 s, within 2%. All four wheels
// drive, so the load moving to the rear as the car squats changes where
// the grip is, not how much there is (the normal forces still sum to m g
// once the pitch has settled; its first tenths of a second are the error).
TEST(AccuracyVehicle3D, AccelerationCapsAtMuGBeyondTheGrip) {
  World3D world;
  CarSpec spec;
  spec.max_drive_force_n = 40000.0f;
  RewindCar car = settled_car(world, spec);
  const double v0 = speed_z(world, car.chassis);
  drive(world, car, {1.0f, 0.0f, 0.0f}, 90);
  const double a = (speed_z(world, car.chassis) - v0) / 1.5;
  report("vehicle_grip_cap a_mps2", a, "m/s^2");
  report("vehicle_grip_cap error_pct", error_pct(a, kG), "%", "<=", 2.0);
  EXPECT_LE(error_pct(a, kG), 2.0);
  for (const WheelTelemetry3D& t : car.telemetry) EXPECT_TRUE(t.saturated);
}

// From 20 m/s with 40,000 N of brake (beyond the grip: the wheels lock),
// the car stops in v^2 / (2 mu g) = 20.39 m: within 3%.
TEST(AccuracyVehicle3D, BrakingDistanceIsVSquaredOverTwoMuG) {
  World3D world;
  CarSpec spec;
  spec.max_brake_force_n = 40000.0f;
  RewindCar car = settled_car(world, spec);
  ASSERT_TRUE(world.set_linear_velocity(car.chassis, {0.0f, 0.0f, 20.0f}).ok());
  const double z0 = world.position(car.chassis).z;
  int ticks = 0;
  while (speed_z(world, car.chassis) > 1e-3 && ticks < 10 * kTicksPerSecond) {
    drive(world, car, {0.0f, 1.0f, 0.0f}, 1);
    ++ticks;
  }
  const double distance = world.position(car.chassis).z - z0;
  const double expected = 20.0 * 20.0 / (2.0 * kG);
  report("vehicle_brake distance_m", distance, "m");
  report("vehicle_brake stop_s", static_cast<double>(ticks) / kTicksPerSecond, "s");
  report("vehicle_brake error_pct", error_pct(distance, expected), "%", "<=", 3.0);
  EXPECT_LT(ticks, 10 * kTicksPerSecond) << "still moving";
  EXPECT_LE(error_pct(distance, expected), 3.0);
}

// A car at rest on a kinematic platform moving at 2 m/s rides along: its
// velocity within 1% of the platform's after 3 s. Sideways, with no input
// at all (the lateral grip carries it); along its length, with the brake
// held (free wheels would let the platform roll out from under it).
TEST(AccuracyVehicle3D, RidesAlongOnAMovingPlatform) {
  struct Case {
    const char* name;
    Vec3 velocity;
    float brake;
  };
  for (const Case& c :
       {Case{"sideways", {2.0f, 0.0f, 0.0f}, 0.0f}, Case{"lengthways", {0.0f, 0.0f, 2.0f}, 1.0f}}) {
    World3D world;
    BodyDef platform;
    platform.kind = BodyKind::kKinematic;
    platform.shape = Shape::make_box({30.0f, 0.5f, 30.0f});
    platform.position = {0.0f, -0.5f, 0.0f};
    platform.linear_velocity = c.velocity;
    platform.material.friction = 1.0f;
    auto deck = world.create_body(platform);
    ASSERT_TRUE(deck.ok());
    CarSpec spec;
    RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(9.81f), 0.0f});
    drive(world, car, {0.0f, c.brake, 0.0f}, 3 * kTicksPerSecond);
    const Vec3 v = world.linear_velocity(car.chassis);
    const double off = length(v - c.velocity);
    const double pct = 100.0 * off / length(c.velocity);
    report(std::string("vehicle_platform_") + c.name + " velocity_error_pct", pct, "%", "<=", 1.0);
    EXPECT_LE(pct, 1.0) << c.name;
    for (const WheelTelemetry3D& t : car.telemetry) EXPECT_EQ(t.contact_body, *deck) << c.name;
  }
}

// A car driving on a floating raft (a 4000 kg dynamic slab with gravity
// scale 0, nothing else in the world) pushes it back: horizontal momentum
// of car + raft stays zero within 1% of the car's own over a 3 s drive.
// The raft's rotation is locked: free, the car's weight off its centre
// would tip it over within the drive. (The pair still falls: the car's
// weight is the one outside force, and it is vertical.)
TEST(AccuracyVehicle3D, DrivingOnARaftConservesMomentum) {
  World3D world;
  BodyDef slab;
  slab.shape = Shape::make_box({12.0f, 0.25f, 12.0f});
  slab.position = {0.0f, -0.25f, 0.0f};
  slab.density = 4000.0f / (24.0f * 0.5f * 24.0f);
  slab.gravity_scale = 0.0f;
  slab.angular_damping = 0.0f;
  slab.lock_rotation = kLockRotationAll;
  slab.material.friction = 1.0f;
  auto raft = world.create_body(slab);
  ASSERT_TRUE(raft.ok());
  CarSpec spec;
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(9.81f), -8.0f});
  drive(world, car, {0.5f, 0.0f, 0.05f}, 3 * kTicksPerSecond);
  const Vec3 p_car = world.linear_velocity(car.chassis) * world.mass(car.chassis);
  const Vec3 p_raft = world.linear_velocity(*raft) * world.mass(*raft);
  const double car_h = std::sqrt(p_car.x * p_car.x + p_car.z * p_car.z);
  const double sum_h = std::sqrt((p_car.x + p_raft.x) * (p_car.x + p_raft.x) +
                                 (p_car.z + p_raft.z) * (p_car.z + p_raft.z));
  report("vehicle_raft car_momentum_nps", car_h, "N s");
  report("vehicle_raft raft_speed_mps", length(world.linear_velocity(*raft)), "m/s");
  report("vehicle_raft momentum_error_pct", 100.0 * sum_h / car_h, "%", "<=", 1.0);
  EXPECT_LE(100.0 * sum_h / car_h, 1.0);
  EXPECT_LT(world.linear_velocity(*raft).z, -0.1f) << "the raft did not move back";
  for (const WheelTelemetry3D& t : car.telemetry) EXPECT_EQ(t.contact_body, *raft);
}

// Steering at 5 m/s with both front wheels at 0.2 rad turns the car left
// (positive yaw about +y, toward +x). Below the grip limit the tires cancel
// their sideways slip, so the car follows the kinematic bicycle path, yaw
// rate v tan(delta) / wheelbase, within 10%: both fronts turn by the same
// angle (no Ackermann geometry), so the inner and outer wheel disagree on
// the turn's centre by half the track either side of the bicycle model's
// radius (0.8 m in 13.8 m, 6%), and the grip settles between them.
TEST(AccuracyVehicle3D, SteeringTurnsAtTheKinematicRate) {
  World3D world;
  CarSpec spec;
  RewindCar car = settled_car(world, spec);
  ASSERT_TRUE(world.set_linear_velocity(car.chassis, {0.0f, 0.0f, 5.0f}).ok());
  const float steer = 0.2f;
  drive(world, car, {0.0f, 0.0f, steer}, kTicksPerSecond);
  const Vec3 v = world.linear_velocity(car.chassis);
  const double speed = std::sqrt(v.x * v.x + v.z * v.z);
  const double yaw = world.angular_velocity(car.chassis).y;
  const double expected = speed * std::tan(steer) / (2.0 * spec.wheel_z_m);
  report("vehicle_steer yaw_rate_radps", yaw, "rad/s");
  report("vehicle_steer yaw_rate_error_pct", error_pct(yaw, expected), "%", "<=", 10.0);
  EXPECT_GT(yaw, 0.0);
  EXPECT_GT(world.position(car.chassis).x, 0.0f);
  EXPECT_LE(error_pct(yaw, expected), 10.0);
}

}  // namespace
}  // namespace rwd::sim
