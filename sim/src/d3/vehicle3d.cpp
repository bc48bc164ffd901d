// SPDX-License-Identifier: MIT
// The raycast-wheel vehicle (vehicle3d.h): validate everything, cast the
// wheels' rays, compute every wheel's spring and tire force (the tires by a
// short Gauss-Seidel solve over the wheels on predicted velocities), check
// that the world will accept them all, then apply them. Nothing is kept between calls; the
// only trigonometry is det_sin/det_cos of the steering angle.
#include "rewind/sim/vehicle3d.h"

#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "d3/body_storage.h"
#include "d3/state_rules.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// Bounds of the description's values: wide enough for any vehicle, narrow
// enough that no wheel's force can overflow the world's force limits.
constexpr float kMaxLength = 100.0f;      // m: rest length, radius
constexpr float kMaxRate = 1e8f;          // N/m, N s/m, N
constexpr float kMaxFriction = 10.0f;     // as Material::friction
constexpr float kMaxWheelForceN = 1e8f;   // a spring at its bump stop pushes no harder
constexpr float kMinNormalCosine = 0.1f;  // the damper's speed is read along the strut
constexpr float kMinDirectionLength = 1e-6f;

Status invalid(const std::string& what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

bool in_range(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

bool usable_direction(Vec3 v) {
  if (!is_finite(v)) return false;
  const float len2 = length_squared(v);
  return std::isfinite(len2) && len2 >= kMinDirectionLength * kMinDirectionLength;
}

Status validate_wheel(const WheelDef3D& w, uint32_t i) {
  const std::string at = "wheels[" + std::to_string(i) + "].";
  if (!is_finite(w.attachment) || !in_range(w.attachment.x, -1e4f, 1e4f) ||
      !in_range(w.attachment.y, -1e4f, 1e4f) || !in_range(w.attachment.z, -1e4f, 1e4f)) {
    return invalid(at + "attachment must be finite, each component within 1e4 m");
  }
  if (!usable_direction(w.suspension_direction)) {
    return invalid(at + "suspension_direction must be finite and non-zero");
  }
  if (!usable_direction(w.axle)) return invalid(at + "axle must be finite and non-zero");
  const Vec3 across = cross(normalize_or_zero(w.axle), normalize_or_zero(w.suspension_direction));
  if (length_squared(across) < 1e-6f) {
    return invalid(at + "axle must not be parallel to suspension_direction");
  }
  if (!in_range(w.rest_length_m, 0.0f, kMaxLength)) {
    return invalid(at + "rest_length_m must be in [0, 100]");
  }
  if (!in_range(w.max_travel_m, 0.0f, w.rest_length_m)) {
    return invalid(at + "max_travel_m must be in [0, rest_length_m]");
  }
  if (!in_range(w.radius_m, 0.0f, kMaxLength)) return invalid(at + "radius_m must be in [0, 100]");
  if (!in_range(w.stiffness_npm, 0.0f, kMaxRate)) {
    return invalid(at + "stiffness_npm must be in [0, 1e8]");
  }
  if (!in_range(w.damping_nspm, 0.0f, kMaxRate)) {
    return invalid(at + "damping_nspm must be in [0, 1e8]");
  }
  if (!in_range(w.friction, 0.0f, kMaxFriction)) return invalid(at + "friction must be in [0, 10]");
  return Status::Ok();
}

Status validate(const World3D& world, const VehicleDef3D& def, const VehicleControls3D& controls,
                size_t telemetry_size) {
  if (def.wheels.empty()) return invalid("wheels: a vehicle needs at least one wheel");
  if (def.wheels.size() > VehicleDef3D::kMaxWheels) return invalid("wheels: at most 64 wheels");
  if (!world.is_valid(def.chassis)) return invalid("chassis: not a live body");
  if (world.kind(def.chassis) != BodyKind::kDynamic) return invalid("chassis: must be dynamic");
  if (!world.is_enabled(def.chassis)) return invalid("chassis: the body is disabled");
  if (!usable_direction(def.forward)) return invalid("forward must be finite and non-zero");
  if (!in_range(def.max_drive_force_n, 0.0f, kMaxRate)) {
    return invalid("max_drive_force_n must be in [0, 1e8]");
  }
  if (!in_range(def.max_brake_force_n, 0.0f, kMaxRate)) {
    return invalid("max_brake_force_n must be in [0, 1e8]");
  }
  for (uint32_t i = 0; i < def.wheels.size(); ++i) {
    if (Status s = validate_wheel(def.wheels[i], i); !s.ok()) return s;
  }
  if (!in_range(controls.throttle, -1.0f, 1.0f)) return invalid("throttle must be in [-1, 1]");
  if (!in_range(controls.brake, 0.0f, 1.0f)) return invalid("brake must be in [0, 1]");
  if (!in_range(controls.steer_rad, -0.5f * kPi, 0.5f * kPi)) {
    return invalid("steer_rad must be in [-pi/2, pi/2]");
  }
  if (telemetry_size < def.wheels.size()) {
    return invalid("telemetry_out: shorter than wheels");
  }
  return Status::Ok();
}

/// v turned by the angle whose cosine and sine are c, s about the unit axis u.
Vec3 turn_about(Vec3 v, Vec3 u, float c, float s) {
  return v * c + cross(u, v) * s + u * (dot(u, v) * (1.0f - c));
}

/// What the passes share about one wheel beyond its telemetry.
struct WheelWork {
  Vec3 force;    // on the chassis at the contact point, N
  Vec3 axle;     // world, unit
  Vec3 forward;  // world, unit, the chassis forward turned with the wheel
  Vec3 down;     // world, unit, the suspension direction
  bool dynamic_ground = false;
  // The grip solve's view of the contact (grounded wheels with a frame).
  bool has_frame = false;
  uint32_t ground_slot = 0;    // in the solve's motions; 0: a ground that does not move by force
  Vec3 roll;                   // world, unit, the rolling direction in the contact plane
  Vec3 side;                   // world, unit, across it
  Vec3 ground_point_v;         // surface velocity of static and kinematic ground, m/s
  float roll_mass = 0.0f;      // effective mass of the contact along roll, kg
  float side_mass = 0.0f;      // and across, kg
  float drive = 0.0f;          // drive impulse this tick, N s
  float brake = 0.0f;          // most brake impulse this tick, N s
  float limit = 0.0f;          // friction circle radius this tick, N s
  float brake_impulse = 0.0f;  // accumulated, N s
  float long_impulse = 0.0f;   // accumulated, drive and brake, N s
  float side_impulse = 0.0f;   // accumulated, N s
  float side_impulse_applied = 0.0f;  // what the predicted velocities hold, N s
};

/// A body's velocities as the grip solve sees them: the end of this tick,
/// predicted from gravity, the forces already on the body and the springs,
/// then moved by each tire impulse the solve adds.
struct Motion {
  Vec3 com;
  Vec3 v;
  Vec3 w;
  float inv_mass = 0.0f;
  Mat3 inv_inertia = mat3_zero();

  Vec3 point_velocity(Vec3 p) const { return v + cross(w, p - com); }
  void push(Vec3 impulse, Vec3 p) {
    v += impulse * inv_mass;
    w += inv_inertia * cross(p - com, impulse);
  }
  /// 1 / the effective mass of the body at p along the unit t.
  float inverse_mass_along(Vec3 p, Vec3 t) const {
    const Vec3 rt = cross(p - com, t);
    return inv_mass + dot(rt, inv_inertia * rt);
  }
};

/// A dynamic body's Motion at the start of the solve: its velocities plus
/// gravity and the forces already accumulated for the next step over `dt`.
Motion motion_of(const WorldState& state, uint32_t index, Vec3 gravity, float dt) {
  const BodyInfo& info = state.infos[index];
  const BodySim& sim = state.sims[index];
  const BodyMass& mass = state.masses[index];
  Motion m;
  m.com = sim.position;
  m.inv_mass = mass.inv_mass;
  m.inv_inertia =
      d3::lock_inverse_inertia(info.lock_rotation, d3::world_inverse_inertia(mass, sim.rotation));
  m.v = sim.linear_velocity + (gravity * info.gravity_scale + sim.force * mass.inv_mass) * dt;
  m.w = sim.angular_velocity + m.inv_inertia * (sim.torque * dt);
  return m;
}

constexpr int kGripIterations = 8;

/// Adds forces to a body's accumulators the way World3D::apply_force_at
/// does (same quantization, same order) and tells whether the world would
/// take every one; the check that keeps a refused call from applying half
/// a car.
class ForceCheck {
 public:
  ForceCheck(const WorldState& state, BodyId id)
      : com_(state.sims[id.index].position),
        force_(state.sims[id.index].force),
        torque_(state.sims[id.index].torque) {}
  void add(Vec3 force_n, Vec3 point) {
    const Vec3 f = quantize(force_n);
    force_ = force_ + f;
    torque_ = torque_ + cross(quantize(point) - com_, f);
    ok_ = ok_ && is_finite(force_) && is_finite(torque_) &&
          length_squared(force_) <= d3::kMaxForce * d3::kMaxForce &&
          length_squared(torque_) <= d3::kMaxTorque * d3::kMaxTorque;
  }
  bool ok() const { return ok_; }

 private:
  Vec3 com_;
  Vec3 force_;
  Vec3 torque_;
  bool ok_ = true;
};

}  // namespace

Status update_vehicle(World3D& world, const VehicleDef3D& def, const VehicleControls3D& controls,
                      std::span<WheelTelemetry3D> telemetry_out) {
  if (Status s = validate(world, def, controls, telemetry_out.size()); !s.ok()) return s;

  const WorldState& state = world.state();
  const uint32_t wheel_count = static_cast<uint32_t>(def.wheels.size());
  const BodyId chassis = def.chassis;
  const float dt = world.config().tick_seconds;
  const Vec3 gravity = world.config().gravity;
  const Vec3 chassis_position = world.position(chassis);
  const Quat chassis_rotation = world.rotation(chassis);
  const Vec3 chassis_com = world.center_of_mass(chassis);
  const Vec3 chassis_v = world.linear_velocity(chassis);
  const Vec3 chassis_w = world.angular_velocity(chassis);
  const Vec3 forward_local = normalize_or_zero(def.forward);
  const float steer_cos = det_cos(controls.steer_rad);
  const float steer_sin = det_sin(controls.steer_rad);

  QueryFilter filter = def.filter;
  filter.ignore = chassis;

  std::array<WheelTelemetry3D, VehicleDef3D::kMaxWheels> out{};
  std::array<WheelWork, VehicleDef3D::kMaxWheels> work{};

  // Pass 1: where each wheel stands.
  uint32_t driving = 0;
  uint32_t braking = 0;
  for (uint32_t i = 0; i < wheel_count; ++i) {
    const WheelDef3D& wheel = def.wheels[i];
    if (wheel.drives) ++driving;
    if (wheel.brakes) ++braking;
    const Vec3 down_local = normalize_or_zero(wheel.suspension_direction);
    Vec3 axle_local = normalize_or_zero(wheel.axle);
    Vec3 wheel_forward_local = forward_local;
    if (wheel.steers) {
      const Vec3 up_local = -down_local;
      axle_local = turn_about(axle_local, up_local, steer_cos, steer_sin);
      wheel_forward_local = turn_about(wheel_forward_local, up_local, steer_cos, steer_sin);
    }
    WheelWork& w = work[i];
    w.down = rotate(chassis_rotation, down_local);
    w.axle = rotate(chassis_rotation, axle_local);
    w.forward = rotate(chassis_rotation, wheel_forward_local);
    const Vec3 top = chassis_position + rotate(chassis_rotation, wheel.attachment);

    WheelTelemetry3D& t = out[i];
    t.hub_position = top + w.down * wheel.rest_length_m;
    const Ray ray{top, w.down, wheel.rest_length_m + wheel.radius_m};
    const std::optional<RayHit> hit = world.raycast(ray, filter);
    // A surface the ray meets edge-on or from behind holds no wheel.
    if (!hit || dot(hit->normal, w.down) >= 0.0f) continue;
    const float length = hit->distance - wheel.radius_m;
    float compression = wheel.rest_length_m - length;
    compression = compression < 0.0f ? 0.0f : compression;
    compression = compression > wheel.max_travel_m ? wheel.max_travel_m : compression;
    t.grounded = true;
    t.compression_m = compression;
    t.hub_position = top + w.down * (wheel.rest_length_m - compression);
    t.contact_point = hit->point;
    t.contact_normal = hit->normal;
    t.contact_body = hit->body;
  }

  // Pass 2: each grounded wheel's spring and the frame its tire works in.
  // motions[0] is the chassis; each dynamic ground body gets one more.
  std::array<Motion, VehicleDef3D::kMaxWheels + 1> motions{};
  std::array<uint32_t, VehicleDef3D::kMaxWheels + 1> motion_body{};
  uint32_t motion_count = 1;
  motions[0] = motion_of(state, chassis.index, gravity, dt);
  motion_body[0] = chassis.index;
  for (uint32_t i = 0; i < wheel_count; ++i) {
    WheelTelemetry3D& t = out[i];
    if (!t.grounded) continue;
    const WheelDef3D& wheel = def.wheels[i];
    WheelWork& w = work[i];
    const Vec3 n = t.contact_normal;
    const Vec3 p = t.contact_point;
    const BodyId ground = t.contact_body;
    const BodyInfo& ground_info = state.infos[ground.index];

    // The ground's surface velocity at the contact: a platform, a raft or
    // a truck bed carries the wheel.
    const Vec3 ground_v = world.linear_velocity(ground) +
                          cross(world.angular_velocity(ground), p - world.center_of_mass(ground));
    const Vec3 v_rel = chassis_v + cross(chassis_w, p - chassis_com) - ground_v;
    w.ground_point_v = ground_v;
    if (ground_info.kind == BodyKind::kDynamic) {
      w.dynamic_ground = true;
      uint32_t slot = 1;
      while (slot < motion_count && motion_body[slot] != ground.index) ++slot;
      if (slot == motion_count) {
        motions[slot] = motion_of(state, ground.index, gravity, dt);
        motion_body[slot] = ground.index;
        ++motion_count;
      }
      w.ground_slot = slot;
    }

    // Suspension: a spring-damper along the strut. The ground takes the
    // strut's force along its normal (cos of the angle between the two);
    // the rest of it is the tire's grip, which the solve below supplies.
    // The damper's speed is the strut's closing speed, read from the
    // normal speed divided by that cosine (floored, so a wheel grazing a
    // wall does not blow up).
    const float cosine = -dot(n, w.down);
    const float closing_mps =
        -dot(v_rel, n) / (cosine > kMinNormalCosine ? cosine : kMinNormalCosine);
    float strut_n = wheel.stiffness_npm * t.compression_m + wheel.damping_nspm * closing_mps;
    strut_n = strut_n < 0.0f ? 0.0f : strut_n;  // a strut pushes, never pulls
    strut_n = strut_n > kMaxWheelForceN ? kMaxWheelForceN : strut_n;
    const float normal_n = strut_n * cosine;
    t.suspension_force_n = normal_n;
    w.force = n * normal_n;
    motions[0].push(n * (normal_n * dt), p);
    if (w.dynamic_ground) motions[w.ground_slot].push(n * (-normal_n * dt), p);

    // The tire's frame in the contact plane: it rolls across its axle, the
    // way the (steered) chassis forward points.
    Vec3 roll = cross(w.axle, n);
    const float roll_len = length(roll);
    if (roll_len <= 1e-3f) continue;  // the axle stands on the ground: no grip
    roll = roll * (1.0f / roll_len);
    if (dot(roll, w.forward) < 0.0f) roll = -roll;
    w.roll = roll;
    w.side = cross(n, roll);
    w.has_frame = true;
    t.longitudinal_slip_mps = dot(v_rel, w.roll);
    t.lateral_slip_mps = dot(v_rel, w.side);
    if (wheel.drives) {
      w.drive = controls.throttle * def.max_drive_force_n / static_cast<float>(driving) * dt;
    }
    if (wheel.brakes) {
      w.brake = controls.brake * def.max_brake_force_n / static_cast<float>(braking) * dt;
    }
    // Friction circle: drive, brake and grip share mu times the normal
    // force, mu the geometric mean of tire and ground.
    w.limit = std::sqrt(wheel.friction * ground_info.material.friction) * normal_n * dt;
  }

  // Grip: the tire impulses that cancel each wheel's slip by the end of
  // the tick (sideways always, along the roll as far as the brake allows),
  // on top of the drive, each limited by its friction circle. They are
  // found by a few Gauss-Seidel passes over the wheels, each wheel's
  // impulse computed from its contact's effective mass (the translation
  // and rotation of the chassis and of a dynamic ground) and applied to
  // the predicted velocities before the next wheel looks.
  //
  // Why not a force proportional to slip speed, or the slip cancelled for
  // a share m / n of the mass: the contact is below the centre of mass, so
  // a sideways push also rolls the chassis, and the contact's effective
  // mass is a fraction of m / n (about a third for the sedan of the
  // tests). A grip sized on m / n overshoots the slip, and at 60 Hz the
  // car rocks between the two ends of the friction circle every tick. An
  // impulse that cancels the slip at the contact's own effective mass, per
  // wheel in turn, never overshoots (Gauss-Seidel on the contacts'
  // mass matrix converges monotonically), holds a parked car on a slope
  // without creeping, and needs no stiffness to tune.
  for (uint32_t i = 0; i < wheel_count; ++i) {
    WheelWork& w = work[i];
    if (!out[i].grounded || !w.has_frame) continue;
    const Vec3 p = out[i].contact_point;
    float roll_k = motions[0].inverse_mass_along(p, w.roll);
    float side_k = motions[0].inverse_mass_along(p, w.side);
    if (w.dynamic_ground) {
      roll_k += motions[w.ground_slot].inverse_mass_along(p, w.roll);
      side_k += motions[w.ground_slot].inverse_mass_along(p, w.side);
    }
    w.roll_mass = roll_k > 0.0f ? 1.0f / roll_k : 0.0f;
    w.side_mass = side_k > 0.0f ? 1.0f / side_k : 0.0f;
  }
  for (int pass = 0; pass <= kGripIterations; ++pass) {
    for (uint32_t i = 0; i < wheel_count; ++i) {
      WheelWork& w = work[i];
      if (!out[i].grounded || !w.has_frame) continue;
      const Vec3 p = out[i].contact_point;
      if (pass > 0) {
        // Pass 0 only lays down the drive; later passes solve for the slip.
        const Vec3 ground_v =
            w.dynamic_ground ? motions[w.ground_slot].point_velocity(p) : w.ground_point_v;
        const Vec3 slip = motions[0].point_velocity(p) - ground_v;
        float brake = w.brake_impulse - w.roll_mass * dot(slip, w.roll);
        brake = brake > w.brake ? w.brake : (brake < -w.brake ? -w.brake : brake);
        w.brake_impulse = brake;
        w.side_impulse -= w.side_mass * dot(slip, w.side);
      }
      float along = w.drive + w.brake_impulse;
      float across = w.side_impulse;
      const float magnitude = std::sqrt(along * along + across * across);
      if (magnitude > w.limit) {
        const float scale = magnitude > 0.0f ? w.limit / magnitude : 0.0f;
        along = along * scale;
        across = across * scale;
        out[i].saturated = true;
      } else {
        out[i].saturated = false;
      }
      // What the circle kept is what the wheel holds from here on.
      w.brake_impulse = along - w.drive;
      w.side_impulse = across;
      const Vec3 delta =
          w.roll * (along - w.long_impulse) + w.side * (across - w.side_impulse_applied);
      w.long_impulse = along;
      w.side_impulse_applied = across;
      motions[0].push(delta, p);
      if (w.dynamic_ground) motions[w.ground_slot].push(-delta, p);
    }
  }
  for (uint32_t i = 0; i < wheel_count; ++i) {
    WheelWork& w = work[i];
    if (!out[i].grounded || !w.has_frame) continue;
    const Vec3 tire = (w.roll * w.long_impulse + w.side * w.side_impulse_applied) * (1.0f / dt);
    out[i].tire_force_n = tire;
    w.force += tire;
  }

  // Pass 3: every force the world will be given must fit its limits, or
  // nothing is applied.
  ForceCheck chassis_check(state, chassis);
  for (uint32_t i = 0; i < wheel_count; ++i) {
    if (!out[i].grounded) continue;
    chassis_check.add(work[i].force, out[i].contact_point);
  }
  bool fits = chassis_check.ok();
  for (uint32_t i = 0; i < wheel_count && fits; ++i) {
    if (!out[i].grounded || !work[i].dynamic_ground) continue;
    bool first = true;  // check each ground body once, over all its wheels
    for (uint32_t j = 0; j < i; ++j) {
      if (out[j].grounded && out[j].contact_body == out[i].contact_body) first = false;
    }
    if (!first) continue;
    ForceCheck ground_check(state, out[i].contact_body);
    for (uint32_t j = i; j < wheel_count; ++j) {
      if (out[j].grounded && out[j].contact_body == out[i].contact_body) {
        ground_check.add(-work[j].force, out[j].contact_point);
      }
    }
    fits = ground_check.ok();
  }
  if (!fits) {
    return invalid("forces: the wheels' forces would exceed the world's limits (1e12 N, 1e12 N m)");
  }

  // Pass 4: apply, wheel by wheel, the reaction on a dynamic ground body
  // at the same point (what the car pushes back, a raft takes).
  for (uint32_t i = 0; i < wheel_count; ++i) {
    if (!out[i].grounded) continue;
    const Vec3 p = out[i].contact_point;
    if (Status s = world.apply_force_at(chassis, work[i].force, p); !s.ok()) return s;
    if (work[i].dynamic_ground) {
      if (Status s = world.apply_force_at(out[i].contact_body, -work[i].force, p); !s.ok()) {
        return s;
      }
    }
  }
  for (uint32_t i = 0; i < wheel_count; ++i) telemetry_out[i] = out[i];
  return Status::Ok();
}

}  // namespace rwd::sim
