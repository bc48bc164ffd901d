// SPDX-License-Identifier: MIT
// The raycast-wheel vehicle (vehicle3d.h): what a wheel reads and pushes,
// how it refuses bad input, and that a driven car replays bit for bit from
// saved and serialized states.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rewind/core/det_math.h"
#include "rewind/scenes/vehicle_scene.h"
#include "rewind/sim/vehicle3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using scenes::add_car;
using scenes::CarSpec;
using scenes::RewindCar;

constexpr float kG = 9.81f;

/// A car resting on the test ground after `seconds` of settling.
RewindCar settled_car(World3D& world, const CarSpec& spec = {}, float seconds = 2.0f) {
  test::add_ground(world, 1.0f);
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(kG) + 0.05f, 0.0f});
  const int ticks = static_cast<int>(seconds * 60.0f);
  for (int t = 0; t < ticks; ++t) {
    EXPECT_TRUE(car.drive(world, {}).ok());
    world.step();
  }
  return car;
}

/// A scripted driver: throttle, brake and steering that change over time.
VehicleControls3D script(int tick) {
  VehicleControls3D c;
  c.throttle = (tick % 200) < 120 ? 0.8f : -0.3f;
  c.brake = (tick % 170) > 140 ? 1.0f : 0.0f;
  c.steer_rad = 0.4f * det_sin(0.02f * static_cast<float>(tick));
  return c;
}

TEST(Vehicle3D, WheelsReadTheGroundAndHoldTheCarUp) {
  World3D world;
  CarSpec spec;
  RewindCar car = settled_car(world, spec);
  const BodyId ground{0, 1};
  for (const WheelTelemetry3D& t : car.telemetry) {
    EXPECT_TRUE(t.grounded);
    EXPECT_EQ(t.contact_body, ground);
    EXPECT_NEAR(t.contact_normal.y, 1.0f, 1e-5f);
    EXPECT_NEAR(t.contact_point.y, 0.0f, 1e-4f);
    EXPECT_GT(t.suspension_force_n, 0.0f);
    EXPECT_FALSE(t.saturated);
    EXPECT_NEAR(t.hub_position.y, spec.radius_m, 1e-3f);
  }
  EXPECT_NEAR(world.position(car.chassis).y, spec.ride_height_m(kG), 2e-3f);
}

TEST(Vehicle3D, AWheelInTheAirPushesNothing) {
  World3D world;  // no ground
  CarSpec spec;
  RewindCar car = add_car(world, spec, {0.0f, 10.0f, 0.0f});
  ASSERT_TRUE(car.drive(world, {1.0f, 0.0f, 0.0f}).ok());
  for (const WheelTelemetry3D& t : car.telemetry) {
    EXPECT_FALSE(t.grounded);
    EXPECT_TRUE(t.contact_body.is_null());
    EXPECT_EQ(t.suspension_force_n, 0.0f);
    EXPECT_NEAR(t.hub_position.y, 10.0f + spec.attach_y_m - spec.rest_length_m, 1e-5f);
  }
  world.step();
  // Free fall only: no force reached the chassis.
  EXPECT_EQ(world.linear_velocity(car.chassis).z, 0.0f);
  EXPECT_NEAR(world.linear_velocity(car.chassis).y, -kG / 60.0f, 1e-5f);
}

TEST(Vehicle3D, TheChassisIsNeverItsOwnGround) {
  // Attachments inside the chassis box: without the filter's ignore every
  // ray would start inside the chassis and hit it at distance 0.
  World3D world;
  CarSpec spec;
  RewindCar car = settled_car(world, spec, 0.5f);
  for (const WheelTelemetry3D& t : car.telemetry) {
    EXPECT_NE(t.contact_body, car.chassis);
    EXPECT_LT(t.compression_m, spec.max_travel_m);
  }
}

TEST(Vehicle3D, ADynamicGroundGetsTheOppositeForce) {
  WorldConfig zero_g;
  zero_g.gravity = {0.0f, 0.0f, 0.0f};
  World3D world(zero_g);
  BodyDef slab;
  slab.shape = Shape::make_box({5.0f, 0.25f, 5.0f});
  slab.position = {0.0f, -0.25f, 0.0f};
  slab.density = 100.0f;
  auto raft = world.create_body(slab);
  ASSERT_TRUE(raft.ok());
  CarSpec spec;
  // Pressed 5 cm into its springs and driving: every wheel pushes.
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(kG) - 0.05f, 0.0f});
  ASSERT_TRUE(car.drive(world, {0.5f, 0.0f, 0.1f}).ok());
  Vec3 total;
  for (const WheelTelemetry3D& t : car.telemetry) {
    ASSERT_TRUE(t.grounded);
    EXPECT_EQ(t.contact_body, *raft);
    total += t.contact_normal * t.suspension_force_n + t.tire_force_n;
  }
  world.step();
  const Vec3 p_car = world.linear_velocity(car.chassis) * world.mass(car.chassis);
  const Vec3 p_raft = world.linear_velocity(*raft) * world.mass(*raft);
  const Vec3 expected = total * world.config().tick_seconds;
  EXPECT_NEAR(p_car.y, expected.y, 1e-3f * std::fabs(expected.y));
  EXPECT_NEAR(p_car.z, expected.z, 1e-3f * std::fabs(expected.z));
  EXPECT_NEAR(p_car.x + p_raft.x, 0.0f, 1e-3f);
  EXPECT_NEAR(p_car.y + p_raft.y, 0.0f, 1e-3f);
  EXPECT_NEAR(p_car.z + p_raft.z, 0.0f, 1e-3f);
}

TEST(Vehicle3D, SteeringTurnsTheCarTheWayTheAngleSays) {
  for (float steer : {0.3f, -0.3f}) {
    World3D world;
    RewindCar car = settled_car(world);
    ASSERT_TRUE(world.set_linear_velocity(car.chassis, {0.0f, 0.0f, 8.0f}).ok());
    for (int t = 0; t < 60; ++t) {
      ASSERT_TRUE(car.drive(world, {0.3f, 0.0f, steer}).ok());
      world.step();
    }
    // Positive steers counterclockwise about +y: from +z toward +x.
    const Vec3 p = world.position(car.chassis);
    const Vec3 heading = rotate(world.rotation(car.chassis), {0.0f, 0.0f, 1.0f});
    EXPECT_GT(p.x * steer, 0.5f) << steer;
    EXPECT_GT(heading.x * steer, 0.2f) << steer;
    EXPECT_GT(world.angular_velocity(car.chassis).y * steer, 0.0f) << steer;
  }
}

TEST(Vehicle3D, ADrivenCarReplaysBitForBitFromSavesAndBytes) {
  World3D world;
  CarSpec spec;
  RewindCar car = settled_car(world, spec, 0.5f);
  test::add_box(world, {1.0f, 0.5f, 25.0f});  // something to hit
  // Every state of the drive round-trips through serialize/deserialize,
  // including the forces the controller left for the next step.
  World3D copy;
  std::vector<uint8_t> bytes;
  std::vector<uint8_t> again;
  for (int t = 0; t < 400; ++t) {
    ASSERT_TRUE(car.drive(world, script(t)).ok());
    world.serialize(bytes);
    ASSERT_TRUE(copy.deserialize(bytes).ok()) << t;
    ASSERT_EQ(copy.checksum(), world.checksum()) << t;
    copy.serialize(again);
    ASSERT_EQ(again, bytes) << t;
    world.step();
  }
  // Restore-and-re-step and load-and-re-step, controller included.
  WorldState saved;
  world.save(saved);
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  std::vector<WheelTelemetry3D> first;
  for (int t = 400; t < 700; ++t) {
    ASSERT_TRUE(car.drive(world, script(t)).ok());
    world.step();
    sums.push_back(world.checksum());
  }
  const auto replay = [&](World3D& w, const char* how) {
    RewindCar again_car = car;
    for (int t = 400; t < 700; ++t) {
      ASSERT_TRUE(again_car.drive(w, script(t)).ok());
      w.step();
      ASSERT_EQ(w.checksum(), sums[static_cast<size_t>(t - 400)]) << how << ", tick " << t;
    }
  };
  world.restore(saved);
  replay(world, "restored");
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  replay(loaded, "loaded");
}

TEST(Vehicle3D, BadInputIsRefusedWithTheWorldUnchanged) {
  World3D world;
  RewindCar car = settled_car(world, CarSpec{}, 0.5f);
  const BodyId ground{0, 1};
  WheelTelemetry3D marker;
  marker.compression_m = 123.0f;
  struct Case {
    const char* field;
    std::function<void(VehicleDef3D&, std::array<WheelDef3D, 4>&, VehicleControls3D&, size_t&)>
        spoil;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Case> cases = {
      {"wheels", [](auto& d, auto&, auto&, auto&) { d.wheels = {}; }},
      {"chassis", [](auto& d, auto&, auto&, auto&) { d.chassis = BodyId{}; }},
      {"chassis",
       [](auto& d, auto&, auto&, auto&) {
         d.chassis = BodyId{77, 1};
       }},
      {"chassis", [&](auto& d, auto&, auto&, auto&) { d.chassis = ground; }},
      {"forward", [](auto& d, auto&, auto&, auto&) { d.forward = {}; }},
      {"forward",
       [&](auto& d, auto&, auto&, auto&) {
         d.forward = {nan, 0.0f, 1.0f};
       }},
      {"max_drive_force_n", [](auto& d, auto&, auto&, auto&) { d.max_drive_force_n = -1.0f; }},
      {"max_brake_force_n", [&](auto& d, auto&, auto&, auto&) { d.max_brake_force_n = inf; }},
      {"wheels[2].suspension_direction",
       [](auto&, auto& w, auto&, auto&) { w[2].suspension_direction = {}; }},
      {"wheels[1].suspension_direction",
       [&](auto&, auto& w, auto&, auto&) {
         w[1].suspension_direction = {0.0f, -inf, 0.0f};
       }},
      {"wheels[0].axle", [](auto&, auto& w, auto&, auto&) { w[0].axle = {}; }},
      {"wheels[0].axle",
       [](auto&, auto& w, auto&, auto&) { w[0].axle = w[0].suspension_direction; }},
      {"wheels[3].attachment",
       [&](auto&, auto& w, auto&, auto&) {
         w[3].attachment = {nan, 0.0f, 0.0f};
       }},
      {"wheels[3].radius_m", [](auto&, auto& w, auto&, auto&) { w[3].radius_m = -0.1f; }},
      {"wheels[1].stiffness_npm", [](auto&, auto& w, auto&, auto&) { w[1].stiffness_npm = -1.0f; }},
      {"wheels[1].damping_nspm", [&](auto&, auto& w, auto&, auto&) { w[1].damping_nspm = nan; }},
      {"wheels[2].rest_length_m", [](auto&, auto& w, auto&, auto&) { w[2].rest_length_m = -1.0f; }},
      {"wheels[2].max_travel_m", [](auto&, auto& w, auto&, auto&) { w[2].max_travel_m = 1.0f; }},
      {"wheels[0].friction", [](auto&, auto& w, auto&, auto&) { w[0].friction = -0.5f; }},
      {"throttle", [](auto&, auto&, auto& c, auto&) { c.throttle = 1.5f; }},
      {"throttle", [&](auto&, auto&, auto& c, auto&) { c.throttle = nan; }},
      {"brake", [](auto&, auto&, auto& c, auto&) { c.brake = -0.1f; }},
      {"steer_rad", [](auto&, auto&, auto& c, auto&) { c.steer_rad = 2.0f; }},
      {"telemetry_out", [](auto&, auto&, auto&, auto& n) { n = 3; }},
  };
  for (const Case& c : cases) {
    std::array<WheelDef3D, 4> wheels = car.wheels;
    VehicleDef3D def = car.def();
    def.wheels = wheels;
    VehicleControls3D controls{0.5f, 0.0f, 0.1f};
    size_t telemetry_size = 4;
    c.spoil(def, wheels, controls, telemetry_size);
    std::array<WheelTelemetry3D, 4> telemetry;
    telemetry.fill(marker);
    const uint64_t before = world.checksum();
    const Status s =
        update_vehicle(world, def, controls, std::span(telemetry).first(telemetry_size));
    EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument) << c.field;
    EXPECT_NE(s.message().find(c.field), std::string::npos) << c.field << ": " << s.message();
    EXPECT_EQ(world.checksum(), before) << c.field;
    for (const WheelTelemetry3D& t : telemetry) EXPECT_EQ(t.compression_m, 123.0f) << c.field;
  }
  // A disabled chassis, and more wheels than the limit.
  std::vector<WheelDef3D> many(VehicleDef3D::kMaxWheels + 1, car.wheels[0]);
  std::vector<WheelTelemetry3D> telemetry(many.size());
  VehicleDef3D def = car.def();
  def.wheels = many;
  uint64_t before = world.checksum();
  EXPECT_EQ(update_vehicle(world, def, {}, telemetry).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.checksum(), before);
  ASSERT_TRUE(world.set_enabled(car.chassis, false).ok());
  before = world.checksum();
  const Status s = car.drive(world, {});
  EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(s.message().find("chassis"), std::string::npos) << s.message();
  EXPECT_EQ(world.checksum(), before);
}

TEST(Vehicle3D, ABrakedCarHoldsOnASlopeAndAFreeOneRollsDown) {
  // A 10 degree slope rising toward +z; the car faces up it.
  const float half = 0.5f * 10.0f * kPi / 180.0f;
  const Quat tilt{-std::sin(half), 0.0f, 0.0f, std::cos(half)};
  const Vec3 normal = rotate(tilt, {0.0f, 1.0f, 0.0f});
  for (float brake : {1.0f, 0.0f}) {
    World3D world;
    BodyDef slope;
    slope.kind = BodyKind::kStatic;
    slope.shape = Shape::make_box({20.0f, 0.5f, 40.0f});
    slope.position = normal * -0.5f;
    slope.rotation = tilt;
    slope.material.friction = 1.0f;
    ASSERT_TRUE(world.create_body(slope).ok());
    CarSpec spec;
    RewindCar car = add_car(world, spec, normal * spec.ride_height_m(kG));
    ASSERT_TRUE(world.set_transform(car.chassis, world.position(car.chassis), tilt).ok());
    const Vec3 start = world.position(car.chassis);
    for (int t = 0; t < 180; ++t) {
      ASSERT_TRUE(car.drive(world, {0.0f, brake, 0.0f}).ok());
      world.step();
    }
    const Vec3 moved = world.position(car.chassis) - start;
    const Vec3 up_slope = rotate(tilt, {0.0f, 0.0f, 1.0f});
    if (brake > 0.0f) {
      EXPECT_LT(length(moved), 0.01f) << "the braked car crept";
    } else {
      EXPECT_LT(dot(moved, up_slope), -1.0f) << "the free car did not roll down";
    }
  }
}

TEST(Vehicle3D, FrictionIsTheGeometricMeanOfTireAndGround) {
  // On 0.04 ground a 1.0 tire grips at 0.2: full throttle (far beyond the
  // grip) accelerates at 0.2 g.
  World3D world;
  test::add_ground(world, 0.04f);
  CarSpec spec;
  spec.max_drive_force_n = 50000.0f;
  RewindCar car = add_car(world, spec, {0.0f, spec.ride_height_m(kG), 0.0f});
  for (int t = 0; t < 60; ++t) {
    ASSERT_TRUE(car.drive(world, {}).ok());
    world.step();
  }
  const float v0 = world.linear_velocity(car.chassis).z;
  for (int t = 0; t < 60; ++t) {
    ASSERT_TRUE(car.drive(world, {1.0f, 0.0f, 0.0f}).ok());
    world.step();
  }
  const float a = world.linear_velocity(car.chassis).z - v0;
  EXPECT_NEAR(a, 0.2f * kG, 0.03f * 0.2f * kG);
  for (const WheelTelemetry3D& t : car.telemetry) EXPECT_TRUE(t.saturated);
}

}  // namespace
}  // namespace rwd::sim
