// SPDX-License-Identifier: MIT
#pragma once
// Joints of the 3D lane. A joint ties two bodies (or a body to the world)
// with a constraint the solver works on beside the contacts, in the same
// substeps: prepared once a tick, warm started from last tick's impulses,
// solved with a soft bias, relaxed without it. Joints live in the world's
// flat state under stable ids (JointId), with their impulses, settings and
// break flag, so save/restore, the snapshot bytes, the checksum and the
// readable dump all carry them.
//
// Units: metres, radians, seconds, kilograms; forces in N, torques in N m,
// impulses in N s (linear) and N m s (angular). Anchors and axes are given
// in each body's authored frame (the frame World3D::position() and
// rotation() report); joint_at() makes a definition from one world point
// and axis instead.
#include <cstdint>

#include "rewind/sim/body.h"
#include "rewind/sim/math.h"

namespace rwd::sim {

class World3D;

/// Handle to a joint: slot index and generation (0 = null), like BodyId.
struct JointId {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return generation == 0; }
  friend bool operator==(JointId, JointId) = default;
};

enum class JointType : uint8_t {
  /// The anchors coincide; the bodies turn freely about the shared point.
  /// With enable_limit it is a cone-twist joint: axis_b may swing at most
  /// cone_angle away from axis_a, and B may twist about them between
  /// twist_lower and twist_upper (relative to the pose at creation). An
  /// angular motor (motor_velocity, max_motor_torque) and an orientation
  /// spring (spring_rotation, hertz, damping_ratio) may drive it.
  kBall = 0,
  /// The anchors coincide and axis_b stays aligned with axis_a: one turning
  /// axis. Angle limits (rad, relative to the pose at creation), a motor
  /// (motor_speed rad/s, max_motor_torque) and a spring toward
  /// spring_target (rad).
  kHinge = 1,
  /// The bodies keep the pose they had relative to each other at creation:
  /// rigid, or soft with linear_hertz / angular_hertz.
  kWeld = 2,
  /// The anchors' distance stays within [min_length, max_length]: a rod
  /// when they are equal, a rope when min_length is 0.
  kDistance = 3,
  /// B slides along axis_a (fixed in A) and does not turn relative to A.
  /// Translation limits (m of anchor B along the axis from anchor A), a
  /// motor (motor_speed m/s, max_motor_force) and a spring toward
  /// spring_target (m).
  kPrismatic = 4,
  /// A soft distance: pulls the anchors toward `length` with a spring of
  /// `hertz` and `damping_ratio`; with enable_limit also held within
  /// [min_length, max_length].
  kSpring = 5,
  /// Pulls body_b's anchor toward `target` (world) with a spring of
  /// `hertz` and `damping_ratio`, by at most max_force. body_a must be null.
  kGrab = 6,
};
inline constexpr uint32_t kJointTypeCount = 7;

/// Everything a joint is made from. World3D::create_joint() checks the
/// fields its type uses and refuses a bad definition with a message naming
/// the field, changing nothing.
struct JointDef {
  JointType type = JointType::kBall;
  /// The bodies. body_a may be null: the joint then holds body_b to the
  /// world, and anchor_a and axis_a are in world coordinates. At least one
  /// side must be a dynamic body; the two must differ.
  BodyId body_a;
  BodyId body_b;
  /// The joint's point on each body, m, in the body's authored frame
  /// (finite, within 1e4 m of the body).
  Vec3 anchor_a;
  Vec3 anchor_b;
  /// Hinge axis, slide direction (axis_a only) or twist axis, in each
  /// body's authored frame; any finite non-zero length (normalized).
  /// Welds and prismatic joints keep the relative pose of creation and
  /// read axis_b not at all.
  Vec3 axis_a{1.0f, 0.0f, 0.0f};
  Vec3 axis_b{1.0f, 0.0f, 0.0f};

  /// Hinge: angle limits (rad in [-pi, pi]); prismatic: translation limits
  /// (m); ball: the cone and twist limits below; spring: the length range.
  bool enable_limit = false;
  float lower = 0.0f;
  float upper = 0.0f;
  /// Ball with enable_limit: largest swing of axis_b away from axis_a,
  /// rad in (0, pi], and the twist range about them, rad in [-pi, pi].
  float cone_angle = 0.5f * 3.14159265f;
  float twist_lower = -3.14159265f;
  float twist_upper = 3.14159265f;

  /// Distance: the range the anchors' distance is held in, m,
  /// 0 <= min_length <= max_length <= 1e4. Spring: its rest length
  /// (`length`), and the range when enable_limit is set.
  float min_length = 0.0f;
  float max_length = 1.0f;
  float length = 1.0f;

  /// Hinge: target angular speed of B relative to A about the axis, rad/s,
  /// with at most max_motor_torque (N m >= 0). Prismatic: speed along the
  /// axis, m/s, with at most max_motor_force (N >= 0). Ball: target
  /// angular velocity of B relative to A, rad/s in world axes, with at
  /// most max_motor_torque (the torque vector's length). Speeds within
  /// 1e4.
  bool enable_motor = false;
  float motor_speed = 0.0f;
  Vec3 motor_velocity;
  float max_motor_torque = 0.0f;
  float max_motor_force = 0.0f;

  /// A spring (hertz in (0, 1000], damping_ratio in [0, 100]: 0 undamped,
  /// 1 critical). Hinge: toward spring_target (rad); prismatic: toward
  /// spring_target (m); ball: toward the orientation spring_rotation of
  /// B's authored frame in A's (a unit quaternion; q_A^-1 q_B). Spring and
  /// grab joints always use hertz and damping_ratio; welds use
  /// damping_ratio with their own hertz.
  bool enable_spring = false;
  float hertz = 4.0f;
  float damping_ratio = 0.7f;
  float spring_target = 0.0f;
  Quat spring_rotation;

  /// Weld: stiffness of the linear and angular parts, Hz in [0, 1000];
  /// 0 is rigid.
  float linear_hertz = 0.0f;
  float angular_hertz = 0.0f;

  /// Grab: where body_b's anchor is pulled (m, world; inside the world
  /// bounds) and the largest pulling force (N, > 0).
  Vec3 target;
  float max_force = 1000.0f;

  /// The joint breaks when the reaction impulse it applies in one tick
  /// (summed over the substeps, its linear part in N s or its angular part
  /// in N m s, motors and limits excluded) exceeds this. A break is
  /// sticky: the joint stays in the world, inert, until destroyed, and the
  /// step reports it (World3D::broken_joints()). 0: never breaks.
  float break_impulse = 0.0f;
  /// While the joint is intact its two bodies do not collide with each
  /// other (collision resumes the step after a break).
  bool disable_collision = true;
};

/// A definition of `type` between `a` and `b` (a may be null: the world)
/// at one world point with one world axis, from the bodies' poses now:
/// both anchors at `anchor_world`, both axes along `axis_world`, a ball
/// joint's spring_rotation the bodies' relative orientation now. Unknown
/// bodies are kept as given (create_joint refuses them).
JointDef joint_at(const World3D& world, JointType type, BodyId a, BodyId b, Vec3 anchor_world,
                  Vec3 axis_world = {1.0f, 0.0f, 0.0f});
/// A distance or spring joint between two world points: min_length,
/// max_length and length are their distance now (a rod, or a spring at
/// rest; lower min_length for a rope).
JointDef joint_between(const World3D& world, JointType type, BodyId a, BodyId b,
                       Vec3 anchor_a_world, Vec3 anchor_b_world);

/// The structural reaction of a joint over the last tick: what it did to
/// body_b (the opposite to body_a), motors and limits excluded.
struct JointReaction {
  Vec3 force_n;    ///< the linear impulse over the tick / tick, N
  Vec3 torque_nm;  ///< the angular impulse over the tick / tick, N m
};

}  // namespace rwd::sim
