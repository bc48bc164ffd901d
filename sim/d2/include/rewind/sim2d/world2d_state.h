// SPDX-License-Identifier: MIT
#pragma once
// Everything a 2D world is: flat arrays of trivially copyable records (no
// pointers), so save() and restore() are bulk copies and a restored world
// steps on bit for bit. The layout is the world's own business; games save
// and restore it whole and never read it.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "rewind/sim2d/body2d.h"
#include "rewind/sim2d/detail/wmath.h"
#include "rewind/sim2d/joint2d.h"
#include "rewind/sim2d/shape2d.h"
#include "rewind/sim2d/world2d_config.h"

namespace rwd::sim2d {

/// BodyRecord2D::flags bits.
inline constexpr uint8_t kBodyEnabled = 1;  ///< simulated (not disabled by bounds or the game)
inline constexpr uint8_t kBodySensor = 2;
inline constexpr uint8_t kBodyLockRotation = 4;
inline constexpr uint8_t kBodyLive = 8;  ///< the slot holds a body
/// Simulated this step; a dynamic body without it sleeps (costs nothing,
/// keeps its contacts) until something touching it moves or the game
/// changes it.
inline constexpr uint8_t kBodyAwake = 16;
/// Swept against static and kinematic shapes after each step (BodyDef2D::continuous).
inline constexpr uint8_t kBodyContinuous = 32;
/// A solid body whose contacts are reported as trigger contacts (BodyDef2D::trigger).
inline constexpr uint8_t kBodyTrigger = 64;

/// One body slot. A free slot has no kBodyLive flag, keeps the generation of
/// its last body and is zero otherwise.
struct BodyRecord2D {
  uint32_t generation = 0;
  BodyKind2D kind = BodyKind2D::kStatic;
  uint8_t flags = 0;
  uint32_t layer = 0;
  uint32_t mask = 0;
  uint64_t user_data = 0;
  Shape2D shape;
  detail::V2 center;               ///< centre of mass, world, m
  detail::Rot rotation;            ///< body frame to world
  detail::V2 local_center;         ///< centre of mass in the body frame, m
  detail::V2 velocity;             ///< m/s of the centre of mass
  detail::W angular_velocity = 0;  ///< rad/s
  detail::V2 force;                ///< N, cleared by each step
  detail::W torque = 0;            ///< N m, cleared by each step
  detail::W inv_mass = 0;          ///< 1/kg; 0 for static and kinematic bodies
  detail::W inv_inertia = 0;       ///< 1/(kg m^2) about the centre of mass
  detail::W sleep_time = 0;        ///< s the body has been slow enough to sleep
  Fx z;
  Fx linear_damping;
  Fx angular_damping;
  Fx gravity_scale;
  Material2D material;
};

/// One touching (or speculatively close) pair's contact point.
struct ContactPoint2D {
  detail::V2 anchor_a;            ///< from A's centre of mass, world axes, m
  detail::V2 anchor_b;            ///< from B's centre of mass
  detail::W separation = 0;       ///< m, negative when overlapping
  detail::W normal_impulse = 0;   ///< N s, warm start of the next step
  detail::W tangent_impulse = 0;  ///< N s
  uint16_t id = 0;                ///< feature key (manifold2.h)
};

/// ContactRecord2D::flags bits.
inline constexpr uint8_t kContactSensor = 1;  ///< a sensor pair: reported, never solved
/// Touching (contact_event2d.h) as of the last step.
inline constexpr uint8_t kContactTouching = 2;
/// A pair with a trigger: solved like any, reported with the trigger flag.
inline constexpr uint8_t kContactTrigger = 4;

/// A pair of bodies whose bounds overlap, with the manifold of the last
/// step. a < b (body indices); the array is sorted by (a, b).
struct ContactRecord2D {
  uint32_t a = 0;
  uint32_t b = 0;
  detail::V2 normal;  ///< unit, from a to b
  ContactPoint2D points[2];
  uint8_t count = 0;
  uint8_t flags = 0;
  detail::W rolling_impulse = 0;  ///< N m s, warm start of rolling resistance
};

/// A touching pair whose contact ended outside a step (a body destroyed,
/// disabled or stopped at the bounds): its exit event is reported by the
/// next step.
struct PendingExit2D {
  uint32_t a = 0;
  uint32_t generation_a = 0;
  uint32_t b = 0;
  uint32_t generation_b = 0;
  uint8_t sensor = 0;  ///< bit 0: a sensor pair; bit 1: a trigger pair
};

/// JointRecord2D::flags bits.
inline constexpr uint8_t kJointLive = 1;
inline constexpr uint8_t kJointBroken = 2;
inline constexpr uint8_t kJointCollideConnected = 4;
inline constexpr uint8_t kJointLimit = 8;
inline constexpr uint8_t kJointMotor = 16;
inline constexpr uint8_t kJointSpring = 32;

/// One joint slot: its definition in the body frames and, after the
/// parameters, the impulses that warm start the next step. A free slot
/// has no kJointLive flag, keeps its generation and is zero otherwise.
struct JointRecord2D {
  uint32_t generation = 0;
  JointType2D type = JointType2D::kDistance;
  uint8_t flags = 0;
  uint32_t a = 0;  ///< body indices
  uint32_t b = 0;
  detail::V2 local_anchor_a;  ///< from each body's origin, body frame
  detail::V2 local_anchor_b;
  detail::V2 local_axis_a;        ///< unit, in A's frame (prismatic, wheel)
  detail::W reference_angle = 0;  ///< B's angle minus A's at creation
  detail::W length = 0;
  detail::W min_length = 0;
  detail::W max_length = 0;
  detail::W lower = 0;
  detail::W upper = 0;
  detail::W motor_speed = 0;
  detail::W max_motor = 0;
  detail::W hertz = 0;
  detail::W damping_ratio = 0;
  detail::W linear_hertz = 0;
  detail::W angular_hertz = 0;
  detail::W max_force = 0;
  detail::W break_impulse = 0;
  detail::V2 target;
  // Accumulated impulses of the last substep (warm starting).
  detail::V2 linear_impulse;
  detail::W angular_impulse = 0;
  detail::W axial_impulse = 0;  ///< distance and prismatic rigid part, wheel perpendicular
  detail::W spring_impulse = 0;
  detail::W motor_impulse = 0;
  detail::W lower_impulse = 0;
  detail::W upper_impulse = 0;
};

/// The whole state of a World2D.
struct World2DState {
  World2DConfig config;
  uint64_t step_count = 0;
  uint32_t live_bodies = 0;
  std::vector<BodyRecord2D> bodies;  ///< by slot index
  std::vector<ContactRecord2D> contacts;
  std::vector<PendingExit2D> pending_exits;  ///< in the order they ended
  uint32_t live_joints = 0;
  std::vector<JointRecord2D> joints;  ///< by slot index
};

static_assert(std::is_trivially_copyable_v<BodyRecord2D>);
static_assert(std::is_trivially_copyable_v<ContactRecord2D>);
static_assert(std::is_trivially_copyable_v<PendingExit2D>);
static_assert(std::is_trivially_copyable_v<JointRecord2D>);

}  // namespace rwd::sim2d
