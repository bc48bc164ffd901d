// SPDX-License-Identifier: MIT
// World2D: creating, destroying and steering joints. Their solver stages
// are in joint_solver2d.cpp and one file per joint type.
#include <string>

#include "body_math2d.h"
#include "fx_check.h"
#include "joint_math2d.h"
#include "rewind/fixed/fx_math.h"
#include "rewind/fixed/trig.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::sim2d {

using namespace detail;

JointDef2D spring_joint(BodyId2D a, BodyId2D b, Vec2 anchor_a, Vec2 anchor_b, Fx hertz,
                        Fx damping_ratio) {
  JointDef2D def;
  def.type = JointType2D::kDistance;
  def.body_a = a;
  def.body_b = b;
  def.anchor_a = anchor_a;
  def.anchor_b = anchor_b;
  def.length = fixed::distance(anchor_a, anchor_b);
  def.min_length = Fx();
  def.max_length = Fx::max();
  def.enable_spring = true;
  def.hertz = hertz;
  def.damping_ratio = damping_ratio;
  return def;
}

namespace {

Status invalid(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, "joint: " + message);
}

Status check_def(const JointDef2D& def) {
  if (static_cast<uint8_t>(def.type) > static_cast<uint8_t>(JointType2D::kGrab)) {
    return invalid("unknown type");
  }
  if (def.body_a == def.body_b) return invalid("body_a and body_b must differ");
  const bool spring =
      def.enable_spring || def.type == JointType2D::kWheel || def.type == JointType2D::kGrab;
  if (spring && !in_range(def.hertz, Fx::epsilon(), 1000_fx)) {
    return invalid("hertz must be in (0, 1000]");
  }
  if (spring && !in_range(def.damping_ratio, Fx(), 100_fx)) {
    return invalid("damping_ratio must be in [0, 100]");
  }
  if (def.reference_angle < -Fx::pi() || Fx::pi() < def.reference_angle) {
    return invalid("reference_angle must be in [-pi, pi]");
  }
  if (def.enable_limit && def.upper < def.lower) return invalid("upper must not be below lower");
  if (def.enable_motor && def.max_motor < Fx()) return invalid("max_motor must be >= 0");
  if (def.break_impulse < Fx()) return invalid("break_impulse must be >= 0 (0: never breaks)");
  switch (def.type) {
    case JointType2D::kDistance: {
      const Fx max_length = def.max_length == Fx() ? def.length : def.max_length;
      if (def.length < Fx() || def.min_length < Fx() || max_length < def.min_length) {
        return invalid("distance lengths must satisfy 0 <= min_length <= max_length");
      }
      break;
    }
    case JointType2D::kPrismatic:
    case JointType2D::kWheel:
      if (def.axis == Vec2{}) return invalid("axis must not be zero");
      break;
    case JointType2D::kWeld:
      if (!in_range(def.linear_hertz, Fx(), 1000_fx) ||
          !in_range(def.angular_hertz, Fx(), 1000_fx)) {
        return invalid("weld hertz must be in [0, 1000]");
      }
      if (!in_range(def.damping_ratio, Fx(), 100_fx)) {
        return invalid("damping_ratio must be in [0, 100]");
      }
      break;
    case JointType2D::kGrab:
      if (!(Fx() < def.max_force)) return invalid("max_force must be > 0");
      break;
    case JointType2D::kRevolute:
      break;
  }
  return Status::Ok();
}

}  // namespace

Result<JointId2D> World2D::create_joint(const JointDef2D& def) {
  if (Status s = check_def(def); !s.ok()) return s;
  if (!is_valid(def.body_a) || !is_valid(def.body_b)) {
    return Status::Error(ErrorCode::kNotFound, "joint: no such body");
  }
  // Both bodies may be static or kinematic (as Box2D allows): such a joint
  // moves nothing, but it is kept, saved and reported like any other, so a
  // scene authored that way loads whole.
  const BodyRecord2D& a = state_.bodies[def.body_a.index];
  const BodyRecord2D& b = state_.bodies[def.body_b.index];
  const Xf xa = origin_transform(a);
  const Xf xb = origin_transform(b);

  JointRecord2D j;
  j.type = def.type;
  j.flags = kJointLive;
  if (def.collide_connected) j.flags |= kJointCollideConnected;
  if (def.enable_limit) j.flags |= kJointLimit;
  if (def.enable_motor) j.flags |= kJointMotor;
  if (def.enable_spring || def.type == JointType2D::kWheel || def.type == JointType2D::kGrab) {
    j.flags |= kJointSpring;
  }
  j.a = def.body_a.index;
  j.b = def.body_b.index;
  j.local_anchor_a = inv_transform_point(xa, v_from(def.anchor_a));
  j.local_anchor_b = inv_transform_point(xb, v_from(def.anchor_b));
  j.local_axis_a = inv_rotate(xa.q, vnormalize(v_from(def.axis)).unit);
  j.reference_angle = angle_of(rinv_mul(xa.q, xb.q)) + w_from(def.reference_angle);
  j.length = w_from(def.length);
  j.min_length = w_from(def.min_length);
  j.max_length = def.max_length == Fx() ? j.length : w_from(def.max_length);
  j.lower = w_from(def.lower);
  j.upper = w_from(def.upper);
  j.motor_speed = w_from(def.motor_speed);
  j.max_motor = w_from(def.max_motor);
  j.hertz = w_from(def.hertz);
  j.damping_ratio = w_from(def.damping_ratio);
  j.linear_hertz = w_from(def.linear_hertz);
  j.angular_hertz = w_from(def.angular_hertz);
  j.max_force = w_from(def.max_force);
  j.break_impulse = w_from(def.break_impulse);
  j.target = v_from(def.target);

  auto& joints = state_.joints;
  uint32_t index = state_.live_joints == joints.size() ? static_cast<uint32_t>(joints.size()) : 0;
  while (index < joints.size() && (joints[index].flags & kJointLive)) ++index;
  if (index == joints.size()) {
    if (state_.live_joints >= state_.config.max_bodies) {
      return Status::Error(ErrorCode::kCapacity,
                           "joint: the world holds max_bodies joints already");
    }
    joints.emplace_back();
  }
  j.generation = joints[index].generation == UINT32_MAX ? 1 : joints[index].generation + 1;
  joints[index] = j;
  ++state_.live_joints;
  wake(state_.bodies[j.a]);
  wake(state_.bodies[j.b]);
  return JointId2D{index, j.generation};
}

bool World2D::is_valid(JointId2D id) const {
  return id.generation != 0 && id.index < state_.joints.size() &&
         (state_.joints[id.index].flags & kJointLive) &&
         state_.joints[id.index].generation == id.generation;
}

Status World2D::destroy_joint(JointId2D id) {
  if (!is_valid(id)) return Status::Error(ErrorCode::kNotFound, "no such joint");
  JointRecord2D& joint = state_.joints[id.index];
  wake(state_.bodies[joint.a]);
  wake(state_.bodies[joint.b]);
  JointRecord2D freed;
  freed.generation = id.generation;
  joint = freed;
  --state_.live_joints;
  return Status::Ok();
}

uint32_t World2D::joint_count() const {
  return state_.live_joints;
}

bool World2D::is_joint_broken(JointId2D id) const {
  return is_valid(id) && (state_.joints[id.index].flags & kJointBroken) != 0;
}

Vec2 World2D::joint_force(JointId2D id) const {
  if (!is_valid(id)) return {};
  const W rate = w_int(int64_t{state_.config.tick_hz} * state_.config.substeps);
  return v_to_fx(vscale(rate, state_.joints[id.index].linear_impulse));
}

Status World2D::set_motor_speed(JointId2D id, Fx speed) {
  if (!is_valid(id)) return Status::Error(ErrorCode::kNotFound, "no such joint");
  JointRecord2D& j = state_.joints[id.index];
  if (j.type != JointType2D::kRevolute && j.type != JointType2D::kPrismatic &&
      j.type != JointType2D::kWheel) {
    return invalid("only revolute, prismatic and wheel joints have a motor");
  }
  j.motor_speed = w_from(speed);
  wake(state_.bodies[j.a]);
  wake(state_.bodies[j.b]);
  return Status::Ok();
}

Status World2D::set_grab_target(JointId2D id, Vec2 target) {
  if (!is_valid(id)) return Status::Error(ErrorCode::kNotFound, "no such joint");
  JointRecord2D& j = state_.joints[id.index];
  if (j.type != JointType2D::kGrab) return invalid("only grab joints have a target");
  j.target = v_from(target);
  wake(state_.bodies[j.b]);
  return Status::Ok();
}

}  // namespace rwd::sim2d
