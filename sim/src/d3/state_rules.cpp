// SPDX-License-Identifier: MIT
#include "d3/state_rules.h"

#include "d3/shape_ops.h"

#include <cmath>

#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

Status invalid(const char* what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

bool finite_in(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

// Speeds are limited by length, not per component, so the rule does not
// depend on how the world is oriented.
bool in_speed_range(Vec3 v) {
  return is_finite(v) && length_squared(v) <= kMaxSpeed * kMaxSpeed;
}

// Every component finite and within [-limit, limit].
bool in_box_range(Vec3 v, float limit) {
  return is_finite(v) && std::fabs(v.x) <= limit && std::fabs(v.y) <= limit &&
         std::fabs(v.z) <= limit;
}

// How far from 1 the squared length of a stored unit vector or rotation may
// be (rounding of a rotated unit vector stays far below this).
constexpr float kUnitTolerance = 1e-3f;

bool in_coordinate_range(Vec3 v) {
  return is_finite(v) && std::fabs(v.x) <= kMaxCoordinate && std::fabs(v.y) <= kMaxCoordinate &&
         std::fabs(v.z) <= kMaxCoordinate;
}

float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// Fields a BodyDef and a stored body share: kind, shape, material, tuning.
Status check_common(const GeometryStore& store, BodyKind kind, const Shape& shape, float density,
                    float linear_damping, float angular_damping, float gravity_scale,
                    const Material& material) {
  if (kind != BodyKind::kStatic && kind != BodyKind::kKinematic && kind != BodyKind::kDynamic) {
    return invalid("unknown body kind");
  }
  if (Status s = check_shape(shape, store); !s.ok()) return s;
  if (kind == BodyKind::kDynamic && !shape_ops(shape.type).solid) {
    return invalid("a triangle mesh or height field cannot be dynamic (static or kinematic only)");
  }
  if (!(std::isfinite(density) && density > 0.0f && density <= 1e9f)) {
    return invalid("density must be in (0, 1e9] kg/m^3");
  }
  if (!finite_in(linear_damping, 0.0f, 1e4f) || !finite_in(angular_damping, 0.0f, 1e4f)) {
    return invalid("damping must be in [0, 1e4] 1/s");
  }
  if (!(std::isfinite(gravity_scale) && std::fabs(gravity_scale) <= 1e3f)) {
    return invalid("gravity_scale must be finite, |g| <= 1000");
  }
  if (!finite_in(material.friction, 0.0f, 10.0f)) return invalid("friction must be in [0, 10]");
  if (!finite_in(material.rolling_resistance, 0.0f, 1.0f)) {
    return invalid("rolling resistance must be in [0, 1]");
  }
  if (!finite_in(material.restitution, 0.0f, 1.0f)) {
    return invalid("restitution must be in [0, 1]");
  }
  return Status::Ok();
}

}  // namespace

Status check_config(const WorldConfig& c) {
  if (!is_finite(c.gravity) || std::fabs(c.gravity.x) > 1e4f || std::fabs(c.gravity.y) > 1e4f ||
      std::fabs(c.gravity.z) > 1e4f) {
    return invalid("gravity must be finite, |g| <= 1e4 m/s^2");
  }
  if (!(c.tick_seconds > 0.0f && c.tick_seconds <= 0.1f)) {
    return invalid("tick_seconds must be in (0, 0.1]");
  }
  if (c.substeps < 1 || c.substeps > 64) return invalid("substeps must be in [1, 64]");
  if (substep_seconds(c) > kMaxSubstepSeconds * kSubstepTolerance) {
    return invalid(
        "a substep (tick_seconds / substeps) must be at most 1/240 s: raise substeps (at 60 Hz "
        "ticks, 4 or more; at 30 Hz, 8); stacks and joint chains fall apart with longer "
        "substeps");
  }
  if (c.relax_iterations < 0 || c.relax_iterations > 16) {
    return invalid("relax_iterations must be in [0, 16]");
  }
  if (!finite_in(c.contact_hertz, 1e-3f, 1e4f)) {
    return invalid("contact_hertz must be in [1e-3, 1e4]");
  }
  if (!finite_in(c.contact_damping_ratio, 0.0f, 1e4f)) {
    return invalid("contact_damping_ratio must be in [0, 1e4]");
  }
  if (!finite_in(c.contact_push_max_mps, 0.0f, 1e4f)) {
    return invalid("contact_push_max_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.restitution_threshold_mps, 0.0f, 1e4f)) {
    return invalid("restitution_threshold_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.linear_slop_m, 0.0f, 1.0f)) return invalid("linear_slop_m must be in [0, 1]");
  if (!finite_in(c.speculative_distance_m, 0.0f, 10.0f)) {
    return invalid("speculative_distance_m must be in [0, 10]");
  }
  if (!finite_in(c.sleep_threshold_mps, 0.0f, 1e4f)) {
    return invalid("sleep_threshold_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.time_to_sleep_s, 0.0f, 1e6f)) {
    return invalid("time_to_sleep_s must be in [0, 1e6]");
  }
  if (c.max_bodies < 1 || c.max_bodies > (1u << 24)) {
    return invalid("max_bodies must be in [1, 2^24]");
  }
  if (!in_coordinate_range(c.bounds_lower) || !in_coordinate_range(c.bounds_upper)) {
    return invalid("bounds must be finite, each component in [-1e5, 1e5] m");
  }
  if (!(c.bounds_lower.x < c.bounds_upper.x && c.bounds_lower.y < c.bounds_upper.y &&
        c.bounds_lower.z < c.bounds_upper.z)) {
    return invalid("bounds_lower must be below bounds_upper on every axis");
  }
  return Status::Ok();
}

Status check_shape(const Shape& shape, const GeometryStore& store) {
  if (!is_known_shape(shape.type)) return invalid("unknown shape type");
  return shape_ops(shape.type).check(shape, store);
}

Status check_body_def(const WorldConfig& config, const GeometryStore& store, const BodyDef& def) {
  if (def.lock_rotation > kLockRotationAll) {
    return invalid("lock_rotation must be kLockRotation* bits (0 to 7)");
  }
  if ((def.event_mask & ~kEventAll) != 0) {
    return invalid("event_mask must be kEvent* bits (0 to 63)");
  }
  if (Status s = check_common(store, def.kind, def.shape, def.density, def.linear_damping,
                              def.angular_damping, def.gravity_scale, def.material);
      !s.ok()) {
    return s;
  }
  if (!is_finite(def.position) || !inside_bounds(config, def.position)) {
    return invalid("position must be finite and inside the world bounds");
  }
  if (!is_finite(def.rotation) || length_squared(def.rotation) < 1e-6f) {
    return invalid("rotation must be a finite, non-zero quaternion");
  }
  if (!in_speed_range(def.linear_velocity) || !in_speed_range(def.angular_velocity)) {
    return invalid("velocities must be finite, at most 1e4 m/s and 1e4 rad/s");
  }
  if (def.kind == BodyKind::kStatic &&
      (!(def.linear_velocity == Vec3{}) || !(def.angular_velocity == Vec3{}))) {
    return invalid("static bodies cannot have a velocity");
  }
  return Status::Ok();
}

Status check_mass(BodyKind kind, const BodyMass& m) {
  if (kind != BodyKind::kDynamic) return Status::Ok();
  if (!(std::isfinite(m.mass) && m.mass > 0.0f && std::isfinite(m.inv_mass) && m.inv_mass > 0.0f &&
        is_finite(m.inv_inertia_local))) {
    return invalid("degenerate mass: shape too small or density too extreme");
  }
  return Status::Ok();
}

Status check_body(const WorldConfig& config, const GeometryStore& store, const BodyInfo& info,
                  const BodySim& sim) {
  if (info.alive != 1 || info.generation == 0) return invalid("not a live body");
  if (info.sensor > 1 || info.awake > 1 || info.enabled > 1 || info.continuous > 1) {
    return invalid("flag out of range");
  }
  if ((info.event_mask & ~kEventAll) != 0) return invalid("event mask out of range");
  if (Status s = check_common(store, info.kind, info.shape, info.density, info.linear_damping,
                              info.angular_damping, info.gravity_scale, info.material);
      !s.ok()) {
    return s;
  }
  if (!is_finite(sim.position) || !inside_bounds(config, sim.position)) {
    return invalid("position outside the world bounds");
  }
  if (!is_finite(sim.rotation) ||
      std::fabs(length_squared(sim.rotation) - 1.0f) > kRotationTolerance) {
    return invalid("rotation is not a unit quaternion");
  }
  if (!in_speed_range(sim.linear_velocity) || !in_speed_range(sim.angular_velocity)) {
    return invalid("speed above 1e4");
  }
  if (!is_finite(sim.force) || length_squared(sim.force) > kMaxForce * kMaxForce) {
    return invalid("force above 1e12 N");
  }
  if (!is_finite(sim.torque) || length_squared(sim.torque) > kMaxTorque * kMaxTorque) {
    return invalid("torque above 1e12 N m");
  }
  if (info.lock_rotation > kLockRotationAll) return invalid("rotation lock out of range");
  if (!angular_velocity_respects_locks(info.lock_rotation, sim.angular_velocity)) {
    return invalid("angular velocity about a locked axis");
  }
  if (!(std::isfinite(sim.sleep_time) && sim.sleep_time >= 0.0f)) {
    return invalid("sleep time must be finite and >= 0");
  }
  if (!is_finite(sim.sleep_position) || !is_finite(sim.sleep_rotation) ||
      std::fabs(length_squared(sim.sleep_rotation) - 1.0f) > kRotationTolerance) {
    return invalid("sleep pose must be finite with a unit rotation");
  }
  const bool still = sim.linear_velocity == Vec3{} && sim.angular_velocity == Vec3{} &&
                     sim.force == Vec3{} && sim.torque == Vec3{};
  if (info.kind == BodyKind::kStatic && (info.awake != 0 || !still)) {
    return invalid("a static body is awake or moving");
  }
  if (info.enabled == 0 && (info.awake != 0 || !still)) {
    return invalid("a disabled body is awake or moving");
  }
  return Status::Ok();
}

Status check_contact(const std::vector<BodyInfo>& infos, const ContactRecord& r,
                     const ContactRecord* previous) {
  if (r.index_a >= r.index_b || r.index_b >= infos.size()) {
    return invalid("body indices out of order or out of range");
  }
  if (r.generation_a == 0 || r.generation_b == 0 || r.generation_a > infos[r.index_a].generation ||
      r.generation_b > infos[r.index_b].generation) {
    return invalid("body generation never existed");
  }
  if (r.touching > 1 || r.sensor > 1) return invalid("flag out of range");
  if (r.point_count > kMaxManifoldPoints || (r.sensor != 0 && r.point_count != 0)) {
    return invalid("point count out of range");
  }
  for (uint32_t p = 0; p < r.point_count; ++p) {
    const CachedContactPoint& c = r.points[p];
    if (!std::isfinite(c.normal_impulse) || !std::isfinite(c.tangent_impulse1) ||
        !std::isfinite(c.tangent_impulse2)) {
      return invalid("impulse not finite");
    }
    // A point lies on A's surface and its separation spans the two shapes:
    // no step puts either much past the largest shapes.
    if (!in_box_range(c.local_a, 2.0f * kMaxShapeSize) ||
        !finite_in(c.separation, -4.0f * kMaxShapeSize, 4.0f * kMaxShapeSize)) {
      return invalid("contact point out of range");
    }
  }
  if (r.point_count > 0) {
    // B's centre relative to A's lies within the world's span; the
    // rotation and normal are unit up to rounding.
    const Quat q = r.frame_rotation;
    const float q_sq = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    if (!in_box_range(r.frame_position, 4.0f * kMaxCoordinate) ||
        !finite_in(q_sq, 1.0f - kUnitTolerance, 1.0f + kUnitTolerance) ||
        !finite_in(length_squared(r.frame_normal), 1.0f - kUnitTolerance, 1.0f + kUnitTolerance)) {
      return invalid("manifold frame out of range or not unit");
    }
  }
  // Sorted by (index_a, index_b), a pair's parts 0, 1, ... in a row, all
  // of the same bodies, and parts past 0 only for a solid compound pair.
  const bool same_pair =
      previous != nullptr && previous->index_a == r.index_a && previous->index_b == r.index_b;
  if (previous != nullptr && !same_pair &&
      (previous->index_a > r.index_a ||
       (previous->index_a == r.index_a && previous->index_b > r.index_b))) {
    return invalid("records out of order");
  }
  if (r.part >= kMaxContactParts || (same_pair ? r.part != previous->part + 1 : r.part != 0)) {
    return invalid("contact parts out of order");
  }
  if (same_pair && (previous->generation_a != r.generation_a ||
                    previous->generation_b != r.generation_b || r.sensor != 0)) {
    return invalid("contact parts of different bodies");
  }
  // (Bodies destroyed since, their slots perhaps reused, are not asked.)
  const BodyInfo& ia = infos[r.index_a];
  const BodyInfo& ib = infos[r.index_b];
  const bool live = ia.alive != 0 && ib.alive != 0 && ia.generation == r.generation_a &&
                    ib.generation == r.generation_b;
  if (r.part > 0 && live && ia.shape.type != ShapeType::kCompound &&
      ib.shape.type != ShapeType::kCompound) {
    return invalid("contact parts of a pair without a compound");
  }
  return Status::Ok();
}

namespace {

bool live_slot(const std::vector<BodyInfo>& infos, uint32_t index, uint32_t generation) {
  return index < infos.size() && infos[index].alive != 0 && generation != 0 &&
         infos[index].generation == generation;
}

bool unit_quat(Quat q) {
  return is_finite(q) && finite_in(length_squared(q), 1.0f - kUnitTolerance, 1.0f + kUnitTolerance);
}

bool joint_impulse_ok(Vec3 v) {
  return in_box_range(v, kMaxForce);
}

}  // namespace

Status check_joint(const WorldConfig& config, const std::vector<BodyInfo>& infos,
                   const JointRecord& j) {
  if (static_cast<uint8_t>(j.type) >= kJointTypeCount) return invalid("unknown joint type");
  if (j.flags > 0x1Fu) return invalid("joint flags out of range");
  if (!live_slot(infos, j.index_b, j.generation_b)) return invalid("body_b is not a live body");
  if (j.index_a == kJointWorld) {
    if (j.generation_a != 0) return invalid("a world anchor has no generation");
  } else if (!live_slot(infos, j.index_a, j.generation_a)) {
    return invalid("body_a is not a live body");
  } else if (j.index_a == j.index_b) {
    return invalid("body_a and body_b are the same body");
  }
  if (j.type == JointType::kGrab && j.index_a != kJointWorld) {
    return invalid("a grab joint has no body_a");
  }
  const float reach = j.index_a == kJointWorld ? kMaxCoordinate : kMaxJointReach;
  if (!in_box_range(j.local_anchor_a, reach) || !in_box_range(j.local_anchor_b, kMaxJointReach)) {
    return invalid("anchor out of range");
  }
  if (!unit_quat(j.frame_a) || !unit_quat(j.frame_b) || !unit_quat(j.spring_rotation)) {
    return invalid("joint frame or spring rotation not unit");
  }
  if (!finite_in(j.lower, -kMaxJointReach, kMaxJointReach) ||
      !finite_in(j.upper, j.lower, kMaxJointReach)) {
    return invalid("limits out of range or lower above upper");
  }
  if (!finite_in(j.cone_angle, 0.0f, kPi) || !finite_in(j.twist_lower, -kPi, kPi) ||
      !finite_in(j.twist_upper, j.twist_lower, kPi)) {
    return invalid("cone or twist limits out of range");
  }
  if (!finite_in(j.min_length, 0.0f, kMaxJointReach) ||
      !finite_in(j.max_length, j.min_length, kMaxJointReach) ||
      !finite_in(j.length, 0.0f, kMaxJointReach)) {
    return invalid("lengths out of range");
  }
  if (!finite_in(j.motor_speed, -kMaxSpeed, kMaxSpeed) ||
      !in_box_range(j.motor_velocity, kMaxSpeed) || !finite_in(j.max_motor, 0.0f, kMaxForce)) {
    return invalid("motor out of range");
  }
  if (!finite_in(j.hertz, 0.0f, 1000.0f) || !finite_in(j.damping_ratio, 0.0f, 100.0f) ||
      !finite_in(j.linear_hertz, 0.0f, 1000.0f) || !finite_in(j.angular_hertz, 0.0f, 1000.0f)) {
    return invalid("spring out of range");
  }
  if (!finite_in(j.spring_target, -kMaxJointReach, kMaxJointReach)) {
    return invalid("spring target out of range");
  }
  if (!in_coordinate_range(j.target) ||
      (j.type == JointType::kGrab && !inside_bounds(config, j.target))) {
    return invalid("grab target outside the world bounds");
  }
  if (!finite_in(j.max_force, 0.0f, kMaxForce) || !finite_in(j.break_impulse, 0.0f, kMaxForce)) {
    return invalid("max force or break impulse out of range");
  }
  if (!joint_impulse_ok(j.linear_impulse) || !joint_impulse_ok(j.angular_impulse) ||
      !joint_impulse_ok(j.motor_impulse) || !joint_impulse_ok(j.spring_impulse) ||
      !finite_in(j.axial_impulse, -kMaxForce, kMaxForce) ||
      !finite_in(j.lower_impulse, 0.0f, kMaxForce) ||
      !finite_in(j.upper_impulse, 0.0f, kMaxForce) || !finite_in(j.cone_impulse, 0.0f, kMaxForce)) {
    return invalid("joint impulse out of range");
  }
  return Status::Ok();
}

Status check_query_ray(const Ray& ray) {
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) {
    return invalid("ray origin and direction must be finite");
  }
  // The queries normalize it the same way and refuse what this refuses.
  if (normalize_or_zero(ray.direction) == Vec3{}) return invalid("ray direction must not be zero");
  if (!finite_in(ray.max_distance, 0.0f, kMaxQueryDistance)) {
    return invalid("ray max_distance must be in [0, 1e6] m");
  }
  return Status::Ok();
}

Status check_query_pose(Vec3 position, Quat rotation) {
  if (!in_box_range(position, kMaxQueryDistance) || !is_finite(rotation)) {
    return invalid(
        "query position must be finite, each component in [-1e6, 1e6] m, and its "
        "rotation finite");
  }
  if (length_squared(rotation) < 1e-6f) return invalid("query rotation must not be zero");
  return Status::Ok();
}

Status check_query(const GeometryStore& store, const ScheduledQueryRecord& q, uint64_t last_ticket,
                   const ScheduledQueryRecord* previous) {
  if (q.ticket == 0 || q.ticket > last_ticket) return invalid("ticket never handed out");
  if (previous != nullptr && previous->ticket >= q.ticket) return invalid("tickets out of order");
  if (static_cast<uint8_t>(q.kind) > static_cast<uint8_t>(ScheduledQueryKind::kOverlap) ||
      static_cast<uint8_t>(q.phase) > static_cast<uint8_t>(QueryPhase::kPostPhysics) ||
      q.repeat > 1) {
    return invalid("kind, phase or repeat out of range");
  }
  if (q.kind != ScheduledQueryKind::kOverlap) return check_query_ray(q.ray);
  if (Status s = check_shape(q.shape, store); !s.ok()) return s;
  if (Status s = check_query_pose(q.position, q.rotation); !s.ok()) return s;
  if (!unit_quat(q.rotation)) return invalid("query rotation not unit");
  return Status::Ok();
}

bool inside_bounds(const WorldConfig& c, Vec3 p) {
  return p.x >= c.bounds_lower.x && p.x <= c.bounds_upper.x && p.y >= c.bounds_lower.y &&
         p.y <= c.bounds_upper.y && p.z >= c.bounds_lower.z && p.z <= c.bounds_upper.z;
}

Vec3 clamp_length(Vec3 v, float max) {
  if (!is_finite(v)) return {};
  const float len_sq = length_squared(v);
  if (!(len_sq > max * max)) return v;
  // Shorten a little below the limit so rounding cannot land above it.
  Vec3 out = v * ((max * 0.999f) / std::sqrt(len_sq));
  return is_finite(out) ? out : Vec3{};
}

bool settle_body(const WorldConfig& config, const BodySim& before, BodyInfo& info, BodySim& sim) {
  if (!is_finite(sim.position)) sim.position = before.position;
  if (!is_finite(sim.rotation) ||
      std::fabs(length_squared(sim.rotation) - 1.0f) > kRotationTolerance) {
    sim.rotation = before.rotation;
  }
  sim.linear_velocity = clamp_length(sim.linear_velocity, kMaxSpeed);
  sim.angular_velocity = clamp_length(sim.angular_velocity, kMaxSpeed);
  if (!is_finite(sim.force) || length_squared(sim.force) > kMaxForce * kMaxForce) sim.force = {};
  if (!is_finite(sim.torque) || length_squared(sim.torque) > kMaxTorque * kMaxTorque) {
    sim.torque = {};
  }
  if (!(std::isfinite(sim.sleep_time) && sim.sleep_time >= 0.0f)) sim.sleep_time = 0.0f;
  if (!is_finite(sim.sleep_position) || !is_finite(sim.sleep_rotation) ||
      std::fabs(length_squared(sim.sleep_rotation) - 1.0f) > kRotationTolerance) {
    sim.sleep_time = 0.0f;
    sim.sleep_position = sim.position;
    sim.sleep_rotation = sim.rotation;
  }
  if (inside_bounds(config, sim.position)) return false;
  sim.position = {clampf(sim.position.x, config.bounds_lower.x, config.bounds_upper.x),
                  clampf(sim.position.y, config.bounds_lower.y, config.bounds_upper.y),
                  clampf(sim.position.z, config.bounds_lower.z, config.bounds_upper.z)};
  disable_body(info, sim);
  return true;
}

void disable_body(BodyInfo& info, BodySim& sim) {
  info.enabled = 0;
  info.awake = 0;
  sim.linear_velocity = {};
  sim.angular_velocity = {};
  sim.force = {};
  sim.torque = {};
  sim.sleep_time = 0.0f;
}

}  // namespace rwd::sim::d3
