// SPDX-License-Identifier: MIT
#pragma once
// Joints of the 2D lane. A joint ties two bodies (either may be static or
// kinematic) with a constraint the soft-step solver works on beside the
// contacts: warm started, part of the world state and the checksum.
// Anchors are given in world coordinates at creation and kept in each
// body's frame.
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/body2d.h"

namespace rwd::sim2d {

/// Handle to a joint, like BodyId2D: slot index and generation (0 = null).
struct JointId2D {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return generation == 0; }
  friend bool operator==(JointId2D, JointId2D) = default;
};

enum class JointType2D : uint8_t {
  /// Keeps the anchors' distance at `length`, or within [min_length,
  /// max_length]; with enable_spring, a spring of `hertz` and
  /// `damping_ratio` pulls toward `length` (a spring joint).
  kDistance = 0,
  /// A shared point the bodies turn about; angle limits and a motor.
  kRevolute = 1,
  /// Slides along `axis` (fixed in body A) without turning; translation
  /// limits, a motor and a spring along the axis.
  kPrismatic = 2,
  /// A wheel on a suspension: slides along `axis` on a spring of `hertz`
  /// and `damping_ratio`, turns freely, driven by an angular motor.
  kWheel = 3,
  /// Glues the bodies: rigid, or soft with linear_hertz / angular_hertz.
  kWeld = 4,
  /// Grab (mouse) joint: pulls body_b's anchor toward `target` (world) with
  /// a spring of `hertz` and `damping_ratio`, at most max_force. body_a is
  /// ignored (use any body; a static ground is usual).
  kGrab = 5,
};

/// Everything a joint is made from. create_joint() validates the fields
/// the type uses and refuses the definition, changing nothing, otherwise.
struct JointDef2D {
  JointType2D type = JointType2D::kRevolute;
  BodyId2D body_a;
  BodyId2D body_b;
  /// World points (m) at creation: the joint's anchor on each body. For a
  /// revolute, weld, prismatic or wheel joint give the same point twice.
  Vec2 anchor_a;
  Vec2 anchor_b;
  /// Prismatic and wheel: the direction of travel in world axes at
  /// creation (any length > 0; it is normalized and kept in body A).
  Vec2 axis{1_fx, Fx()};

  /// Distance: rest length (m, >= 0; a spring's rest length) and the
  /// range the distance is held in; max_length 0 means "length".
  Fx length = 1_fx;
  Fx min_length;
  Fx max_length;

  /// Revolute, prismatic and weld: the angle of B relative to A (rad, in
  /// [-pi, pi]) the joint holds as zero, counted from their angle at
  /// creation: a spring pulls toward it and limits count from it, so the
  /// joint angle at creation is minus this (Box2D's referenceAngle, for
  /// bodies created at the same angle). 0: the pose at creation.
  Fx reference_angle;

  /// Revolute: angle limits (rad, relative to the reference angle);
  /// prismatic and wheel: translation limits (m, along the axis).
  bool enable_limit = false;
  Fx lower;
  Fx upper;

  /// Revolute and wheel: angular speed (rad/s) and the largest torque
  /// (N m); prismatic: speed along the axis (m/s) and force (N).
  bool enable_motor = false;
  Fx motor_speed;
  Fx max_motor;

  /// Distance, prismatic, wheel (its suspension), grab: a spring (Hz > 0)
  /// with its damping ratio (>= 0). A wheel's suspension is always on.
  bool enable_spring = false;
  Fx hertz = 4_fx;
  Fx damping_ratio = 0.7_fx;

  /// Weld: stiffness of the linear and angular parts (Hz); 0 is rigid.
  Fx linear_hertz;
  Fx angular_hertz;

  /// Grab: where body_b's anchor is pulled (m, world) and the largest
  /// pulling force (N, > 0).
  Vec2 target;
  Fx max_force = 1000_fx;

  /// The joint breaks (stops acting; World2D::is_joint_broken) when the
  /// impulse it applies in one tick exceeds this (N s for its linear part,
  /// N m s for its angular part). 0: it never breaks.
  Fx break_impulse;
  /// Whether the two bodies still collide with each other.
  bool collide_connected = false;
};

/// A spring joint: a distance joint between two world points whose spring
/// pulls toward their current distance (override `length` to change it).
JointDef2D spring_joint(BodyId2D a, BodyId2D b, Vec2 anchor_a, Vec2 anchor_b, Fx hertz,
                        Fx damping_ratio);

}  // namespace rwd::sim2d
