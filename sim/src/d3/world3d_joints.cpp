// SPDX-License-Identifier: MIT
// World3D: creating, destroying, reading and steering joints. Every field
// of a definition is checked before the world changes; values enter the
// canonical grid like every other outside value; anchors, axes and frames
// are converted from the bodies' authored frames to their mass frames,
// the frames the solver works in.
#include <algorithm>
#include <string>

#include "d3/body_storage.h"
#include "d3/joint_math.h"
#include "d3/mass_frame.h"
#include "d3/pipeline.h"
#include "d3/state_rules.h"
#include "d3/world_scratch.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {

using d3::is_live;
using d3::kAxisX;

namespace {

Status invalid(const std::string& field, const std::string& why) {
  return Status::Error(ErrorCode::kInvalidArgument, "joint." + field + ": " + why);
}

bool finite_in(float v, float lo, float hi) {
  return is_finite(v) && v >= lo && v <= hi;
}

bool in_reach(Vec3 v, float reach) {
  return is_finite(v) && length_squared(v) <= reach * reach;
}

bool usable_axis(Vec3 v) {
  return is_finite(v) && length_squared(v) > 1e-12f;
}

Quat quantize_quat(Quat q) {
  return {quantize(q.x), quantize(q.y), quantize(q.z), quantize(q.w)};
}

// The field checks that need no world.
Status check_def(const JointDef& def) {
  const JointType type = def.type;
  if (static_cast<uint8_t>(type) >= kJointTypeCount) return invalid("type", "unknown joint type");
  if (!in_reach(def.anchor_b, d3::kMaxJointReach)) {
    return invalid("anchor_b", "must be finite, within 1e4 m of the body");
  }
  const float reach_a = def.body_a.is_null() ? d3::kMaxCoordinate : d3::kMaxJointReach;
  if (type != JointType::kGrab && !in_reach(def.anchor_a, reach_a)) {
    return invalid("anchor_a", "must be finite, within 1e4 m of the body (1e5 for the world)");
  }
  const bool axes =
      type == JointType::kHinge || type == JointType::kPrismatic || type == JointType::kBall;
  if (axes && !usable_axis(def.axis_a)) return invalid("axis_a", "must be finite and non-zero");
  if ((type == JointType::kHinge || type == JointType::kBall) && !usable_axis(def.axis_b)) {
    return invalid("axis_b", "must be finite and non-zero");
  }
  if (def.enable_limit) {
    if (type == JointType::kHinge) {
      if (!finite_in(def.lower, -kPi, kPi)) return invalid("lower", "must be in [-pi, pi] rad");
      if (!finite_in(def.upper, -kPi, kPi)) return invalid("upper", "must be in [-pi, pi] rad");
    } else if (type == JointType::kPrismatic) {
      if (!finite_in(def.lower, -d3::kMaxJointReach, d3::kMaxJointReach)) {
        return invalid("lower", "must be finite, within 1e4 m");
      }
      if (!finite_in(def.upper, -d3::kMaxJointReach, d3::kMaxJointReach)) {
        return invalid("upper", "must be finite, within 1e4 m");
      }
    }
    if ((type == JointType::kHinge || type == JointType::kPrismatic) && def.lower > def.upper) {
      return invalid("lower", "must not be above upper");
    }
    if (type == JointType::kBall) {
      if (!(def.cone_angle > 0.0f && def.cone_angle <= kPi)) {
        return invalid("cone_angle", "must be in (0, pi] rad");
      }
      if (!finite_in(def.twist_lower, -kPi, kPi)) {
        return invalid("twist_lower", "must be in [-pi, pi] rad");
      }
      if (!finite_in(def.twist_upper, -kPi, kPi)) {
        return invalid("twist_upper", "must be in [-pi, pi] rad");
      }
      if (def.twist_lower > def.twist_upper) {
        return invalid("twist_lower", "must not be above twist_upper");
      }
    }
  }
  const bool ranged =
      type == JointType::kDistance || (type == JointType::kSpring && def.enable_limit);
  if (ranged) {
    if (!finite_in(def.min_length, 0.0f, d3::kMaxJointReach)) {
      return invalid("min_length", "must be in [0, 1e4] m");
    }
    if (!finite_in(def.max_length, 0.0f, d3::kMaxJointReach)) {
      return invalid("max_length", "must be in [0, 1e4] m");
    }
    if (def.min_length > def.max_length)
      return invalid("min_length", "must not be above max_length");
  }
  if (type == JointType::kSpring && !finite_in(def.length, 0.0f, d3::kMaxJointReach)) {
    return invalid("length", "must be in [0, 1e4] m");
  }
  const bool motor =
      def.enable_motor &&
      (type == JointType::kHinge || type == JointType::kPrismatic || type == JointType::kBall);
  if (motor) {
    if (type == JointType::kBall) {
      if (!in_reach(def.motor_velocity, d3::kMaxSpeed)) {
        return invalid("motor_velocity", "must be finite, at most 1e4 rad/s");
      }
    } else if (!finite_in(def.motor_speed, -d3::kMaxSpeed, d3::kMaxSpeed)) {
      return invalid("motor_speed", "must be finite, within 1e4");
    }
    const float max = type == JointType::kPrismatic ? def.max_motor_force : def.max_motor_torque;
    if (!finite_in(max, 0.0f, d3::kMaxForce)) {
      return invalid(type == JointType::kPrismatic ? "max_motor_force" : "max_motor_torque",
                     "must be in [0, 1e12]");
    }
  }
  const bool spring =
      type == JointType::kSpring || type == JointType::kGrab ||
      (def.enable_spring &&
       (type == JointType::kHinge || type == JointType::kPrismatic || type == JointType::kBall));
  if (spring) {
    if (!(def.hertz > 0.0f && def.hertz <= 1000.0f))
      return invalid("hertz", "must be in (0, 1000]");
  }
  if (spring || type == JointType::kWeld) {
    if (!finite_in(def.damping_ratio, 0.0f, 100.0f)) {
      return invalid("damping_ratio", "must be in [0, 100]");
    }
  }
  if (spring && type == JointType::kHinge && !finite_in(def.spring_target, -kPi, kPi)) {
    return invalid("spring_target", "must be in [-pi, pi] rad");
  }
  if (spring && type == JointType::kPrismatic &&
      !finite_in(def.spring_target, -d3::kMaxJointReach, d3::kMaxJointReach)) {
    return invalid("spring_target", "must be finite, within 1e4 m");
  }
  if (spring && type == JointType::kBall &&
      (!is_finite(def.spring_rotation) || length_squared(def.spring_rotation) < 1e-6f)) {
    return invalid("spring_rotation", "must be a finite, non-zero quaternion");
  }
  if (type == JointType::kWeld) {
    if (!finite_in(def.linear_hertz, 0.0f, 1000.0f)) {
      return invalid("linear_hertz", "must be in [0, 1000]");
    }
    if (!finite_in(def.angular_hertz, 0.0f, 1000.0f)) {
      return invalid("angular_hertz", "must be in [0, 1000]");
    }
  }
  if (type == JointType::kGrab) {
    if (!is_finite(def.target)) return invalid("target", "must be finite");
    if (!(def.max_force > 0.0f && def.max_force <= d3::kMaxForce)) {
      return invalid("max_force", "must be in (0, 1e12] N");
    }
  }
  if (!finite_in(def.break_impulse, 0.0f, d3::kMaxForce)) {
    return invalid("break_impulse", "must be in [0, 1e12] (0: never breaks)");
  }
  return Status::Ok();
}

// A side of a joint: its pose in both frames (the world has identity).
struct Side {
  Vec3 position;        ///< authored frame origin
  Quat rotation;        ///< authored frame
  Vec3 center;          ///< mass frame origin
  Quat mass_rotation;   ///< mass frame
  Quat frame_rotation;  ///< mass frame in the authored frame
};

Side world_side() {
  return {};
}

}  // namespace

Result<JointId> World3D::create_joint(const JointDef& def) {
  if (Status s = check_def(def); !s.ok()) return s;
  const JointType type = def.type;
  if (type == JointType::kGrab && !def.body_a.is_null()) {
    return invalid("body_a", "a grab joint pulls body_b alone: leave body_a null");
  }
  if (!is_live(state_, def.body_b)) {
    return Status::Error(ErrorCode::kNotFound, "joint.body_b: unknown or stale body id");
  }
  if (!def.body_a.is_null() && !is_live(state_, def.body_a)) {
    return Status::Error(ErrorCode::kNotFound, "joint.body_a: unknown or stale body id");
  }
  if (def.body_a == def.body_b) return invalid("body_b", "must differ from body_a");
  const bool dynamic_b = state_.infos[def.body_b.index].kind == BodyKind::kDynamic;
  const bool dynamic_a =
      !def.body_a.is_null() && state_.infos[def.body_a.index].kind == BodyKind::kDynamic;
  if (!dynamic_a && !dynamic_b) {
    return invalid("body_b", "at least one of the bodies must be dynamic");
  }
  if (type == JointType::kGrab && !d3::inside_bounds(state_.config, quantize(def.target))) {
    return invalid("target", "must be inside the world bounds");
  }
  if (state_.live_joints >= state_.config.max_bodies) {
    return Status::Error(ErrorCode::kCapacity, "joint: the world holds max_bodies joints already");
  }

  auto side_of = [&](BodyId id) {
    if (id.is_null()) return world_side();
    const d3::AuthoredPose pose = d3::authored_pose(state_, *geometry_, id.index);
    const d3::MassFrame frame = d3::mass_frame(state_.infos[id.index].shape, *geometry_);
    Side s;
    s.position = pose.position;
    s.rotation = pose.rotation;
    s.center = state_.sims[id.index].position;
    s.mass_rotation = state_.sims[id.index].rotation;
    s.frame_rotation = frame.rotation;
    return s;
  };
  const Side a = side_of(def.body_a);
  const Side b = side_of(def.body_b);

  JointRecord j;
  j.alive = 1;
  j.type = type;
  if (def.enable_limit && (type == JointType::kHinge || type == JointType::kPrismatic ||
                           type == JointType::kBall || type == JointType::kSpring)) {
    j.flags |= kJointLimit;
  }
  if (def.enable_motor &&
      (type == JointType::kHinge || type == JointType::kPrismatic || type == JointType::kBall)) {
    j.flags |= kJointMotor;
  }
  if (def.enable_spring &&
      (type == JointType::kHinge || type == JointType::kPrismatic || type == JointType::kBall)) {
    j.flags |= kJointSpring;
  }
  if (type == JointType::kSpring || type == JointType::kGrab) j.flags |= kJointSpring;
  if (def.disable_collision && type != JointType::kGrab) j.flags |= kJointDisableCollision;
  j.index_a = def.body_a.is_null() ? kJointWorld : def.body_a.index;
  j.generation_a = def.body_a.is_null() ? 0 : def.body_a.generation;
  j.index_b = def.body_b.index;
  j.generation_b = def.body_b.generation;

  // Anchors: authored frame -> world -> mass frame.
  const Vec3 world_anchor_a = a.position + rotate(a.rotation, quantize(def.anchor_a));
  const Vec3 world_anchor_b = b.position + rotate(b.rotation, quantize(def.anchor_b));
  j.local_anchor_a = inv_rotate(a.mass_rotation, world_anchor_a - a.center);
  j.local_anchor_b = inv_rotate(b.mass_rotation, world_anchor_b - b.center);
  // Frames: A's x axis along axis_a; B's the same frame, swung by the
  // shortest arc onto axis_b where B's axis is its own.
  const Vec3 axis_a = normalize_or_zero(rotate(a.rotation, quantize(def.axis_a)));
  const bool own_axis_b = type == JointType::kHinge || type == JointType::kBall;
  const Vec3 axis_b =
      own_axis_b ? normalize_or_zero(rotate(b.rotation, quantize(def.axis_b))) : axis_a;
  const Quat frame_world_a = d3::arc_between(kAxisX, axis_a);
  const Quat frame_world_b = normalize(d3::arc_between(axis_a, axis_b) * frame_world_a);
  j.frame_a = normalize(conjugate(a.mass_rotation) * frame_world_a);
  j.frame_b = normalize(conjugate(b.mass_rotation) * frame_world_b);

  j.lower = quantize(def.lower);
  j.upper = quantize(def.upper);
  if (j.upper < j.lower) j.upper = j.lower;  // quantizing cannot cross them
  j.cone_angle = std::min(quantize(def.cone_angle), kPi);
  j.twist_lower = std::max(quantize(def.twist_lower), -kPi);
  j.twist_upper = std::min(std::max(quantize(def.twist_upper), j.twist_lower), kPi);
  j.min_length = quantize(def.min_length);
  j.max_length = std::max(quantize(def.max_length), j.min_length);
  j.length = quantize(def.length);
  if (type == JointType::kSpring && !def.enable_limit) {
    j.min_length = 0.0f;
    j.max_length = d3::kMaxJointReach;
  }
  j.motor_speed = quantize(def.motor_speed);
  j.motor_velocity = quantize(def.motor_velocity);
  j.max_motor =
      quantize(type == JointType::kPrismatic ? def.max_motor_force : def.max_motor_torque);
  j.hertz = quantize(def.hertz);
  j.damping_ratio = quantize(def.damping_ratio);
  j.spring_target = quantize(def.spring_target);
  // B's authored frame in A's -> B's mass frame in A's mass frame.
  j.spring_rotation = normalize(conjugate(a.frame_rotation) *
                                normalize(quantize_quat(def.spring_rotation)) * b.frame_rotation);
  j.linear_hertz = quantize(def.linear_hertz);
  j.angular_hertz = quantize(def.angular_hertz);
  j.target = quantize(def.target);
  j.max_force = quantize(def.max_force);
  j.break_impulse = quantize(def.break_impulse);
  // The rule every stored joint keeps; quantizing may have nudged a value.
  if (Status s = d3::check_joint(state_.config, state_.infos, j); !s.ok()) {
    return invalid("def", "leaves the valid range on the canonical grid: " + s.message());
  }

  uint32_t index = 0;
  while (index < state_.joints.size() && state_.joints[index].alive != 0) ++index;
  if (index == state_.joints.size()) state_.joints.emplace_back();
  uint32_t generation = state_.joints[index].generation + 1;
  if (generation == 0) generation = 1;
  j.generation = generation;
  state_.joints[index] = j;
  ++state_.live_joints;
  d3::wake_body(state_, j.index_b);
  if (j.index_a != kJointWorld) d3::wake_body(state_, j.index_a);
  d3::mark_joints_edited(*scratch_);
  return JointId{index, generation};
}

namespace {

bool live_joint(const WorldState& s, JointId id) {
  return id.generation != 0 && id.index < s.joints.size() && s.joints[id.index].alive != 0 &&
         s.joints[id.index].generation == id.generation;
}

Status no_joint() {
  return Status::Error(ErrorCode::kNotFound, "unknown or stale joint id");
}

void wake_joint_bodies(WorldState& state, const JointRecord& j) {
  d3::wake_body(state, j.index_b);
  if (j.index_a != kJointWorld) d3::wake_body(state, j.index_a);
}

// Frees a joint slot, keeping its generation for the next occupant.
void free_joint(WorldState& state, uint32_t index) {
  JointRecord freed;
  freed.generation = state.joints[index].generation;
  state.joints[index] = freed;
  --state.live_joints;
}

}  // namespace

Status World3D::destroy_joint(JointId id) {
  if (!live_joint(state_, id)) return no_joint();
  wake_joint_bodies(state_, state_.joints[id.index]);
  free_joint(state_, id.index);
  d3::mark_joints_edited(*scratch_);
  return Status::Ok();
}

void World3D::destroy_body_joints(BodyId id, std::vector<JointId>* removed) {
  if (state_.live_joints == 0) return;
  for (uint32_t k = 0; k < state_.joints.size(); ++k) {
    const JointRecord& j = state_.joints[k];
    if (j.alive == 0) continue;
    const bool on_a = j.index_a == id.index && j.generation_a == id.generation;
    const bool on_b = j.index_b == id.index && j.generation_b == id.generation;
    if (!on_a && !on_b) continue;
    if (removed != nullptr) removed->push_back({k, j.generation});
    wake_joint_bodies(state_, j);
    free_joint(state_, k);
  }
  d3::mark_joints_edited(*scratch_);
}

bool World3D::is_valid(JointId id) const {
  return live_joint(state_, id);
}

uint32_t World3D::joint_count() const {
  return state_.live_joints;
}

void World3D::joint_ids(std::vector<JointId>& out) const {
  out.clear();
  for (uint32_t k = 0; k < state_.joints.size(); ++k) {
    if (state_.joints[k].alive != 0) out.push_back({k, state_.joints[k].generation});
  }
}

JointType World3D::joint_type(JointId id) const {
  return live_joint(state_, id) ? state_.joints[id.index].type : JointType::kBall;
}

BodyId World3D::joint_body_a(JointId id) const {
  if (!live_joint(state_, id)) return {};
  const JointRecord& j = state_.joints[id.index];
  return j.index_a == kJointWorld ? BodyId{} : BodyId{j.index_a, j.generation_a};
}

BodyId World3D::joint_body_b(JointId id) const {
  if (!live_joint(state_, id)) return {};
  const JointRecord& j = state_.joints[id.index];
  return {j.index_b, j.generation_b};
}

bool World3D::is_joint_broken(JointId id) const {
  return live_joint(state_, id) && (state_.joints[id.index].flags & kJointBroken) != 0;
}

JointReaction World3D::joint_reaction(JointId id) const {
  if (!live_joint(state_, id)) return {};
  const JointRecord& j = state_.joints[id.index];
  const float rate = static_cast<float>(state_.config.substeps) / state_.config.tick_seconds;
  return {j.linear_impulse * rate, j.angular_impulse * rate};
}

namespace {

// Where a joint's two sides are now, as its rows measure them.
struct JointPose {
  Vec3 anchor_a;
  Vec3 anchor_b;
  Quat frame_a;
  Quat frame_b;
};

JointPose joint_pose(const WorldState& state, const JointRecord& j) {
  JointPose p;
  const BodySim& b = state.sims[j.index_b];
  p.anchor_b = b.position + rotate(b.rotation, j.local_anchor_b);
  p.frame_b = b.rotation * j.frame_b;
  if (j.type == JointType::kGrab) {
    p.anchor_a = j.target;
    p.frame_a = j.frame_a;
  } else if (j.index_a == kJointWorld) {
    p.anchor_a = j.local_anchor_a;
    p.frame_a = j.frame_a;
  } else {
    const BodySim& a = state.sims[j.index_a];
    p.anchor_a = a.position + rotate(a.rotation, j.local_anchor_a);
    p.frame_a = a.rotation * j.frame_a;
  }
  return p;
}

}  // namespace

float World3D::joint_position(JointId id) const {
  if (!live_joint(state_, id)) return 0.0f;
  const JointRecord& j = state_.joints[id.index];
  const JointPose p = joint_pose(state_, j);
  switch (j.type) {
    case JointType::kBall:
    case JointType::kHinge:
      return d3::twist_angle(conjugate(p.frame_a) * p.frame_b);
    case JointType::kPrismatic:
      return dot(p.anchor_b - p.anchor_a, rotate(p.frame_a, kAxisX));
    case JointType::kDistance:
    case JointType::kSpring:
    case JointType::kGrab:
      return length(p.anchor_b - p.anchor_a);
    case JointType::kWeld:
      break;
  }
  return 0.0f;
}

float World3D::joint_swing(JointId id) const {
  if (!live_joint(state_, id)) return 0.0f;
  const JointPose p = joint_pose(state_, state_.joints[id.index]);
  const Vec3 xa = rotate(p.frame_a, kAxisX);
  const Vec3 xb = rotate(p.frame_b, kAxisX);
  return det_atan2(length(cross(xa, xb)), dot(xa, xb));
}

Status World3D::set_joint_motor(JointId id, bool enabled, float speed, float max_torque_or_force) {
  if (!live_joint(state_, id)) return no_joint();
  JointRecord& j = state_.joints[id.index];
  if (j.type != JointType::kHinge && j.type != JointType::kPrismatic) {
    return invalid("type", "set_joint_motor drives hinge and prismatic joints");
  }
  if (!finite_in(speed, -d3::kMaxSpeed, d3::kMaxSpeed)) {
    return invalid("motor_speed", "must be finite, within 1e4");
  }
  if (!finite_in(max_torque_or_force, 0.0f, d3::kMaxForce)) {
    return invalid(j.type == JointType::kPrismatic ? "max_motor_force" : "max_motor_torque",
                   "must be in [0, 1e12]");
  }
  j.flags = enabled ? (j.flags | kJointMotor) : (j.flags & ~kJointMotor);
  j.motor_speed = quantize(speed);
  j.max_motor = quantize(max_torque_or_force);
  if (!enabled) j.motor_impulse = {};
  wake_joint_bodies(state_, j);
  return Status::Ok();
}

Status World3D::set_joint_motor_velocity(JointId id, bool enabled, Vec3 velocity_radps,
                                         float max_torque_nm) {
  if (!live_joint(state_, id)) return no_joint();
  JointRecord& j = state_.joints[id.index];
  if (j.type != JointType::kBall) {
    return invalid("type", "set_joint_motor_velocity drives ball joints");
  }
  if (!in_reach(velocity_radps, d3::kMaxSpeed)) {
    return invalid("motor_velocity", "must be finite, at most 1e4 rad/s");
  }
  if (!finite_in(max_torque_nm, 0.0f, d3::kMaxForce)) {
    return invalid("max_motor_torque", "must be in [0, 1e12]");
  }
  j.flags = enabled ? (j.flags | kJointMotor) : (j.flags & ~kJointMotor);
  j.motor_velocity = quantize(velocity_radps);
  j.max_motor = quantize(max_torque_nm);
  if (!enabled) j.motor_impulse = {};
  wake_joint_bodies(state_, j);
  return Status::Ok();
}

Status World3D::set_joint_spring_target(JointId id, float target) {
  if (!live_joint(state_, id)) return no_joint();
  JointRecord& j = state_.joints[id.index];
  if (j.type == JointType::kHinge) {
    if (!finite_in(target, -kPi, kPi)) return invalid("spring_target", "must be in [-pi, pi] rad");
  } else if (j.type == JointType::kPrismatic) {
    if (!finite_in(target, -d3::kMaxJointReach, d3::kMaxJointReach)) {
      return invalid("spring_target", "must be finite, within 1e4 m");
    }
  } else {
    return invalid("type", "set_joint_spring_target sets hinge and prismatic springs");
  }
  j.spring_target = quantize(target);
  wake_joint_bodies(state_, j);
  return Status::Ok();
}

Status World3D::set_joint_spring_rotation(JointId id, Quat target) {
  if (!live_joint(state_, id)) return no_joint();
  JointRecord& j = state_.joints[id.index];
  if (j.type != JointType::kBall) {
    return invalid("type", "set_joint_spring_rotation sets ball joint springs");
  }
  if (!is_finite(target) || length_squared(target) < 1e-6f) {
    return invalid("spring_rotation", "must be a finite, non-zero quaternion");
  }
  const Quat fa = j.index_a == kJointWorld
                      ? Quat{}
                      : d3::mass_frame(state_.infos[j.index_a].shape, *geometry_).rotation;
  const Quat fb = d3::mass_frame(state_.infos[j.index_b].shape, *geometry_).rotation;
  j.spring_rotation = normalize(conjugate(fa) * normalize(quantize_quat(target)) * fb);
  wake_joint_bodies(state_, j);
  return Status::Ok();
}

Status World3D::set_grab_target(JointId id, Vec3 target) {
  if (!live_joint(state_, id)) return no_joint();
  JointRecord& j = state_.joints[id.index];
  if (j.type != JointType::kGrab) return invalid("type", "only grab joints have a target");
  if (!is_finite(target) || !d3::inside_bounds(state_.config, quantize(target))) {
    return invalid("target", "must be finite and inside the world bounds");
  }
  j.target = quantize(target);
  d3::wake_body(state_, j.index_b);
  return Status::Ok();
}

std::span<const JointId> World3D::broken_joints() const {
  return scratch_->broken_joints;
}

// --- definitions from world points -------------------------------------------

namespace {

// A world point and direction in a body's authored frame (the world's own
// frame for a null id or an unknown body).
Vec3 to_local_point(const World3D& world, BodyId id, Vec3 p) {
  if (!world.is_valid(id)) return p;
  return inv_rotate(world.rotation(id), p - world.position(id));
}
Vec3 to_local_direction(const World3D& world, BodyId id, Vec3 v) {
  if (!world.is_valid(id)) return v;
  return inv_rotate(world.rotation(id), v);
}

}  // namespace

JointDef joint_at(const World3D& world, JointType type, BodyId a, BodyId b, Vec3 anchor_world,
                  Vec3 axis_world) {
  JointDef def;
  def.type = type;
  def.body_a = type == JointType::kGrab ? BodyId{} : a;
  def.body_b = b;
  def.anchor_a = to_local_point(world, def.body_a, anchor_world);
  def.anchor_b = to_local_point(world, b, anchor_world);
  def.axis_a = to_local_direction(world, def.body_a, axis_world);
  def.axis_b = to_local_direction(world, b, axis_world);
  def.target = anchor_world;
  const Quat qa = world.is_valid(def.body_a) ? world.rotation(def.body_a) : Quat{};
  const Quat qb = world.is_valid(b) ? world.rotation(b) : Quat{};
  def.spring_rotation = normalize(conjugate(qa) * qb);
  def.min_length = def.max_length = def.length = 0.0f;
  return def;
}

JointDef joint_between(const World3D& world, JointType type, BodyId a, BodyId b,
                       Vec3 anchor_a_world, Vec3 anchor_b_world) {
  JointDef def = joint_at(world, type, a, b, anchor_a_world);
  def.anchor_b = to_local_point(world, b, anchor_b_world);
  const float distance = length(anchor_b_world - anchor_a_world);
  def.min_length = def.max_length = def.length = distance;
  return def;
}

}  // namespace rwd::sim
