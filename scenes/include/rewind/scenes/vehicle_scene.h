// SPDX-License-Identifier: MIT
#pragma once
// One car, described once: its numbers (mass, chassis, wheel geometry,
// springs, tires) shared by the vehicle tests, the accuracy suite and the
// side-by-side benchmark, and its Rewind build (a box chassis and four
// raycast wheels, vehicle3d.h). Header only; depends on the engine's public
// API.
#include <array>

#include "rewind/sim/vehicle3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::scenes {

/// A 1200 kg sedan: all four wheels drive and brake, the front two steer.
/// Springs give a 1.5 Hz ride at a damping ratio of 0.4. The car faces +z
/// with +y up; its wheels' axles lie along x.
struct CarSpec {
  float mass_kg = 1200.0f;
  sim::Vec3 half_extents{0.9f, 0.3f, 2.2f};  ///< chassis box, m
  float wheel_x_m = 0.8f;                    ///< attachment, either side of the centre
  float wheel_z_m = 1.4f;                    ///< attachment, front (+) and rear (-)
  float attach_y_m = -0.2f;                  ///< attachment below the chassis centre
  float rest_length_m = 0.4f;
  float max_travel_m = 0.3f;
  float radius_m = 0.35f;
  /// (1200 / 4) kg (2 pi 1.5 Hz)^2, rounded.
  float stiffness_npm = 27000.0f;
  /// 2 x 0.4 x sqrt(27000 N/m x 300 kg), rounded.
  float damping_nspm = 2300.0f;
  float friction = 1.0f;
  float max_drive_force_n = 6000.0f;
  float max_brake_force_n = 12000.0f;

  /// Spring compression at rest on flat ground, m: m g / (k n).
  float static_compression_m(float gravity_mps2) const {
    return mass_kg * gravity_mps2 / (stiffness_npm * 4.0f);
  }
  /// Height of the chassis centre above flat ground at rest, m.
  float ride_height_m(float gravity_mps2) const {
    return -attach_y_m + rest_length_m - static_compression_m(gravity_mps2) + radius_m;
  }
  /// Wheel i (0 front left, 1 front right, 2 rear left, 3 rear right) in
  /// the chassis frame.
  sim::Vec3 attachment(int i) const {
    const float x = (i % 2 == 0) ? wheel_x_m : -wheel_x_m;  // +x is the car's left
    const float z = (i < 2) ? wheel_z_m : -wheel_z_m;
    return {x, attach_y_m, z};
  }
};

/// A Rewind car: its chassis and the wheels the game owns. Keep it alive
/// (and in place) while a def() made from it is in use.
struct RewindCar {
  sim::BodyId chassis;
  std::array<sim::WheelDef3D, 4> wheels{};
  float max_drive_force_n = 0.0f;
  float max_brake_force_n = 0.0f;
  std::array<sim::WheelTelemetry3D, 4> telemetry{};

  sim::VehicleDef3D def() const {
    sim::VehicleDef3D d;
    d.chassis = chassis;
    d.wheels = wheels;
    d.forward = {0.0f, 0.0f, 1.0f};
    d.max_drive_force_n = max_drive_force_n;
    d.max_brake_force_n = max_brake_force_n;
    return d;
  }
  /// Runs the controller for this tick.
  Status drive(sim::World3D& world, const sim::VehicleControls3D& controls) {
    return sim::update_vehicle(world, def(), controls, telemetry);
  }
};

/// The chassis box's density for the spec's mass.
inline float car_density(const CarSpec& spec) {
  const sim::Vec3 h = spec.half_extents;
  return spec.mass_kg / (8.0f * h.x * h.y * h.z);
}

/// Builds `spec` on `world` with its chassis centre at `position` (a
/// resting car on flat ground at height y stands at y + ride_height_m()),
/// facing +z, moving at `velocity_mps`.
inline RewindCar add_car(sim::World3D& world, const CarSpec& spec, sim::Vec3 position,
                         sim::Vec3 velocity_mps = {}) {
  RewindCar car;
  sim::BodyDef body;
  body.shape = sim::Shape::make_box(spec.half_extents);
  body.position = position;
  body.linear_velocity = velocity_mps;
  body.density = car_density(spec);
  body.angular_damping = 0.0f;
  auto id = world.create_body(body);
  if (id.ok()) car.chassis = *id;
  for (int i = 0; i < 4; ++i) {
    sim::WheelDef3D& w = car.wheels[static_cast<size_t>(i)];
    w.attachment = spec.attachment(i);
    w.suspension_direction = {0.0f, -1.0f, 0.0f};
    w.axle = {1.0f, 0.0f, 0.0f};
    w.rest_length_m = spec.rest_length_m;
    w.max_travel_m = spec.max_travel_m;
    w.radius_m = spec.radius_m;
    w.stiffness_npm = spec.stiffness_npm;
    w.damping_nspm = spec.damping_nspm;
    w.friction = spec.friction;
    w.steers = i < 2;
    w.drives = true;
    w.brakes = true;
  }
  car.max_drive_force_n = spec.max_drive_force_n;
  car.max_brake_force_n = spec.max_brake_force_n;
  return car;
}

}  // namespace rwd::scenes
