// SPDX-License-Identifier: MIT
#pragma once
// A raycast-wheel vehicle for the 3D lane: one dynamic chassis body held up
// by a spring-damper and driven, braked and steered by a tire force at each
// wheel. The controller keeps no state of its own: update_vehicle() reads
// the world (the chassis and the ground under each wheel), the vehicle's
// description and this tick's controls, and adds forces for the next step.
// The game owns the description (a span of wheels it keeps), so a rollback
// that restores the world and replays the controls replays the car bit for
// bit.
#include <cstdint>
#include <span>

#include "rewind/core/status.h"
#include "rewind/sim/body.h"
#include "rewind/sim/math.h"
#include "rewind/sim/query.h"

namespace rwd::sim {

class World3D;

/// One wheel, in the chassis body's frame (the frame of BodyDef::position
/// and rotation). The suspension is a ray from `attachment` along
/// `suspension_direction`; the wheel's centre sits `rest_length_m -
/// compression` along it and its tread `radius_m` further.
struct WheelDef3D {
  /// Chassis-local point the suspension hangs from, m.
  Vec3 attachment;
  /// Chassis-local direction the suspension extends in (down); normalized
  /// by the controller.
  Vec3 suspension_direction{0.0f, -1.0f, 0.0f};
  /// Chassis-local axle direction (either way along it); the wheel rolls
  /// across it. Normalized by the controller; must not be parallel to the
  /// suspension direction.
  Vec3 axle{1.0f, 0.0f, 0.0f};
  /// Length of the unloaded spring, m, in [0, 100].
  float rest_length_m = 0.4f;
  /// How far the spring may compress, m, in [0, rest_length_m]; the spring
  /// pushes no harder beyond it (the chassis shape meets the ground).
  float max_travel_m = 0.3f;
  /// Wheel radius, m, in [0, 100].
  float radius_m = 0.35f;
  /// Spring rate, N/m, in [0, 1e8]: a vehicle of mass m on n equal wheels
  /// rests with each spring compressed by m g / (k n). For a ride frequency
  /// f Hz, k = (m / n) (2 pi f)^2 (cars: f about 1 to 2 Hz).
  float stiffness_npm = 30000.0f;
  /// Damper rate, N s/m, in [0, 1e8]; 2 zeta sqrt(k m / n) for a damping
  /// ratio zeta (cars: 0.2 to 0.5). Stiffness and damping are given in
  /// physical units rather than as a frequency and ratio so that a car
  /// keeps its ride height whatever the tick rate, and springs tuned on
  /// another engine carry over.
  float damping_nspm = 2500.0f;
  /// Tire friction coefficient, in [0, 10]. The grip at a contact is the
  /// geometric mean of this and the ground's Material::friction, as for
  /// body contacts: a 1.0 tire on 0.6 ground grips at 0.77, on 0.05 ice at
  /// 0.22.
  float friction = 1.0f;
  bool steers = false;  ///< turned by VehicleControls3D::steer_rad
  bool drives = false;  ///< shares VehicleDef3D::max_drive_force_n
  bool brakes = true;   ///< shares VehicleDef3D::max_brake_force_n
};

/// A vehicle: a dynamic chassis body and the wheels under it. Plain data
/// the game owns; nothing of it is kept between calls.
struct VehicleDef3D {
  static constexpr uint32_t kMaxWheels = 64;
  /// The chassis: a live, enabled, dynamic body.
  BodyId chassis;
  /// One to kMaxWheels wheels.
  std::span<const WheelDef3D> wheels;
  /// Chassis-local forward direction: the way positive throttle drives.
  Vec3 forward{0.0f, 0.0f, 1.0f};
  /// Drive force at full throttle, N, in [0, 1e8], shared equally by the
  /// driving wheels (one in the air delivers its share to nothing). A game
  /// with gears or a torque curve sets it per tick.
  float max_drive_force_n = 6000.0f;
  /// Brake force at full brake, N, in [0, 1e8], shared equally by the
  /// braking wheels.
  float max_brake_force_n = 12000.0f;
  /// Which bodies the wheels stand on. Its `ignore` is replaced by the
  /// chassis.
  QueryFilter filter;
};

/// One tick's driver input.
struct VehicleControls3D {
  float throttle = 0.0f;  ///< [-1, 1]; negative drives backwards
  float brake = 0.0f;     ///< [0, 1]
  /// Steering wheels turn by this about the chassis up axis (the opposite
  /// of each wheel's suspension direction), radians in [-pi/2, pi/2];
  /// positive turns counterclockwise seen from above (left, in a
  /// right-handed y-up world).
  float steer_rad = 0.0f;
};

/// What one wheel did this tick (world frame), for game logic, sound and
/// rendering.
struct WheelTelemetry3D {
  bool grounded = false;
  /// The tire force reached the friction circle (mu times the normal
  /// force): the wheel spins or skids.
  bool saturated = false;
  /// How far the spring is compressed, m, in [0, max_travel_m]; 0 in the air.
  float compression_m = 0.0f;
  /// The wheel's centre, m: where to draw it.
  Vec3 hub_position;
  /// Where the ray met the ground, its surface normal and the body; zero
  /// and the null id in the air.
  Vec3 contact_point;
  Vec3 contact_normal;
  BodyId contact_body;
  /// Speed of the chassis at the contact relative to the ground's surface
  /// (v + w x (p - com) of both bodies), m/s: along the wheel's rolling
  /// direction (a free wheel rolls it off; a locked one slides at it; a
  /// renderer spins the wheel at it over radius_m) and across it (the
  /// sideways slide the lateral grip works against).
  float longitudinal_slip_mps = 0.0f;
  float lateral_slip_mps = 0.0f;
  /// Spring-damper force along the contact normal, N (>= 0).
  float suspension_force_n = 0.0f;
  /// Drive, brake and lateral grip together, in the contact plane, N.
  Vec3 tire_force_n;
};

/// Casts one ray per wheel (the chassis ignored), and for each grounded
/// wheel applies to the chassis, at the contact point and for the next
/// step only (World3D::apply_force_at), the suspension force along the
/// contact normal and a tire force in the contact plane; a dynamic ground
/// body gets the opposite force at the same point. Speeds are measured
/// against the ground's surface velocity v + w x (p - com), so a moving
/// platform carries the car.
///
/// The tire force is the drive, plus the grip that cancels the wheel's
/// sideways slip by the end of the tick and the brake that cancels its
/// rolling speed (up to the brake force), limited by the friction circle
/// (mu times the normal force). Grip and brake are sized on each contact's
/// effective mass (the chassis's and a dynamic ground's translation and
/// rotation) over velocities predicted from gravity, the forces already on
/// the bodies and the springs, wheel after wheel for a few passes: a
/// parked car holds on a slope and the grip never overshoots, so it does
/// not rock from tick to tick. Call it once per tick before
/// World3D::step(). Fills telemetry_out[i] for wheel i.
///
/// kInvalidArgument naming the field, with the world and telemetry_out
/// unchanged, for: no wheels or more than kMaxWheels, a chassis that is not
/// a live, enabled, dynamic body, a non-finite or zero direction, an axle
/// parallel to its suspension, a length, force or coefficient out of its
/// range, controls out of range, or telemetry_out shorter than the wheels.
/// Keeps the chassis awake (it applies forces every call).
Status update_vehicle(World3D& world, const VehicleDef3D& def, const VehicleControls3D& controls,
                      std::span<WheelTelemetry3D> telemetry_out);

}  // namespace rwd::sim
