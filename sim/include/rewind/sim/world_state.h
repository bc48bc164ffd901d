// SPDX-License-Identifier: MIT
#pragma once
// The persistent state of a World3D, as plain data. Everything a future step
// depends on lives here, in flat vectors of trivially copyable records
// addressed by body index; nothing here points anywhere. Saving is
// `snapshot = world.state()`, restoring is the reverse, and because vector
// copy-assignment reuses capacity, a reused snapshot does not allocate once it
// has grown to the world's size.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "rewind/sim/body.h"
#include "rewind/sim/joint.h"
#include "rewind/sim/math.h"
#include "rewind/sim/query.h"
#include "rewind/sim/scheduled_query.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world_config.h"

namespace rwd::sim {

/// Bookkeeping of one body slot: identity, shape, material and filtering.
/// Cold data: read by the broadphase and narrowphase, written only by the API.
struct BodyInfo {
  uint32_t generation = 0;  ///< of the live body, or of the last one in a dead slot
  uint8_t alive = 0;        ///< 1 when the slot holds a live body
  BodyKind kind = BodyKind::kStatic;
  uint8_t sensor = 0;  ///< 1: reports overlaps, never solved
  uint8_t awake = 0;   ///< 1: simulated this step (static bodies are never awake)
  /// 0: taken out of the simulation (left the world bounds, or the game
  /// disabled it): never awake, no contacts, not found by queries.
  uint8_t enabled = 1;
  Shape shape;
  Material material;
  uint32_t layer = 1;
  uint32_t mask = 0xFFFFFFFFu;
  uint64_t user_data = 0;
  float density = 0.0f;          ///< kg/m^3
  float linear_damping = 0.0f;   ///< 1/s
  float angular_damping = 0.0f;  ///< 1/s
  float gravity_scale = 1.0f;
  uint8_t lock_rotation = 0;  ///< kLockRotation* bits (body.h)
  uint8_t continuous = 0;     ///< 1: swept for time of impact after each step (BodyDef)
  /// kEvent* bits: the contact and sensor events it asks for (BodyDef).
  EventMask event_mask = kEventAll;
};

/// Hot simulation state of one body slot, written every step while awake.
struct BodySim {
  Vec3 position;  ///< metres, shape centre (= centre of mass)
  Quat rotation;
  Vec3 linear_velocity;     ///< m/s
  Vec3 angular_velocity;    ///< rad/s, world frame
  Vec3 force;               ///< N, accumulated for the next step only
  Vec3 torque;              ///< N m, world frame, accumulated for the next step only
  float sleep_time = 0.0f;  ///< seconds at rest (WorldConfig::sleep_threshold_mps)
  /// Where the body's current stretch of rest began: it stays at rest
  /// while no point of it strays more than sleep_threshold_mps x
  /// time_to_sleep_s / 2 from here, and a new stretch starts every
  /// time_to_sleep_s / 2 (WorldConfig).
  Vec3 sleep_position;  ///< metres
  Quat sleep_rotation;
};

/// Mass properties of one body slot, derived from shape, density and kind.
/// Stored (not recomputed per step) because they are read every substep.
struct BodyMass {
  float mass = 0.0f;       ///< kg; 0 for static and kinematic
  float inv_mass = 0.0f;   ///< 1/kg
  Vec3 inv_inertia_local;  ///< principal inverse inertia in the body frame, 1/(kg m^2)
  float extent = 0.0f;     ///< metres, largest distance from the centre to the surface
};

/// Maximum contact points in one manifold.
inline constexpr uint32_t kMaxManifoldPoints = 4;
/// Most contact records one body pair has (ContactRecord::part).
inline constexpr uint32_t kMaxContactParts = 4;

/// The persistent part of one contact point: its feature id, the impulses
/// it ended the last step with (warm start), and where it was when its
/// manifold was last computed (so the manifold can be carried forward while
/// the two bodies barely move relative to each other; see ContactRecord).
struct CachedContactPoint {
  uint32_t feature_id = 0;        ///< which features produced the point (see manifold.h)
  float normal_impulse = 0.0f;    ///< N*s per substep
  float tangent_impulse1 = 0.0f;  ///< N*s per substep, along the first tangent of the normal
  float tangent_impulse2 = 0.0f;  ///< N*s per substep, along the second tangent
  Vec3 local_a;                   ///< metres, the point on A's surface, in A's frame
  float separation = 0.0f;        ///< metres along the normal to B's surface then
};

/// One pair of bodies whose fat bounds overlapped last step (or one part of
/// it, see `part`). Records are kept sorted by (index_a, index_b, part) with
/// index_a < index_b. Generations make a
/// record of a destroyed body distinct from one of its slot's next occupant.
struct ContactRecord {
  uint32_t index_a = 0;
  uint32_t generation_a = 0;
  uint32_t index_b = 0;
  uint32_t generation_b = 0;
  uint8_t touching = 0;  ///< 1: manifold had points (solid) or shapes overlapped (sensor)
  uint8_t sensor = 0;    ///< 1: at least one body is a sensor
  uint8_t point_count = 0;
  /// Which of the pair's records this is, [0, kMaxContactParts): a solid
  /// pair with a compound has one per group of its children's contacts
  /// whose normals lie within 30 degrees of each other, deepest group
  /// first (parts 0, 1, ... in a row); every other pair has part 0 only.
  uint8_t part = 0;
  CachedContactPoint points[kMaxManifoldPoints];
  // The frame of the last computed manifold (meaningful when point_count >
  // 0): B's centre and rotation, and the normal, in A's body frame. While B
  // stays within a millimetre of this pose relative to A, the step moves the
  // points with B instead of colliding the shapes again.
  Vec3 frame_position;  ///< metres
  Quat frame_rotation;  ///< unit
  Vec3 frame_normal;    ///< unit, from A to B
};

/// JointRecord::flags bits.
enum : uint8_t {
  kJointLimit = 1u << 0,
  kJointMotor = 1u << 1,
  kJointSpring = 1u << 2,
  kJointDisableCollision = 1u << 3,
  kJointBroken = 1u << 4,  ///< exceeded break_impulse; inert from then on
};
/// JointRecord::index_a of a joint held to the world.
inline constexpr uint32_t kJointWorld = 0xFFFFFFFFu;

/// One joint slot: its bodies, its frames on each, its settings and the
/// impulses it ended the last tick with (applied again each substep: the
/// warm start). Anchors and frames are kept in the bodies' mass frames
/// (relative to the centre of mass, along the principal axes), the frames
/// the solver works in; the API converts from the authored frames.
struct JointRecord {
  uint32_t generation = 0;  ///< of the live joint, or of the last one in a dead slot
  uint8_t alive = 0;        ///< 1 when the slot holds a live joint
  JointType type = JointType::kBall;
  uint8_t flags = 0;  ///< kJoint* bits
  uint32_t index_a = kJointWorld;
  uint32_t generation_a = 0;
  uint32_t index_b = 0;
  uint32_t generation_b = 0;
  Vec3 local_anchor_a;  ///< m, in A's mass frame (world frame for the world)
  Vec3 local_anchor_b;  ///< m, in B's mass frame
  /// The joint's frame on each body (its x axis is the hinge, slide or
  /// twist axis). At creation both are the same world frame, or B's is
  /// swung onto B's axis by the shortest arc, so angles count from there.
  Quat frame_a;
  Quat frame_b;
  // Settings (JointDef, in the same units).
  float lower = 0.0f;
  float upper = 0.0f;
  float cone_angle = 0.0f;
  float twist_lower = 0.0f;
  float twist_upper = 0.0f;
  float min_length = 0.0f;
  float max_length = 0.0f;
  float length = 0.0f;
  float motor_speed = 0.0f;
  Vec3 motor_velocity;
  float max_motor = 0.0f;  ///< N m or N by type
  float hertz = 0.0f;
  float damping_ratio = 0.0f;
  float spring_target = 0.0f;
  Quat spring_rotation;  ///< ball: B's mass frame in A's mass frame
  float linear_hertz = 0.0f;
  float angular_hertz = 0.0f;
  Vec3 target;  ///< m, world
  float max_force = 0.0f;
  float break_impulse = 0.0f;
  // Impulses of the last substep (N s, N m s), world frame.
  Vec3 linear_impulse;         ///< point or perpendicular rows
  Vec3 angular_impulse;        ///< orientation rows (hinge, weld, prismatic)
  Vec3 motor_impulse;          ///< ball motor (3 rows), else x: the motor row
  Vec3 spring_impulse;         ///< ball orientation spring (3 rows), else x: the spring row
  float axial_impulse = 0.0f;  ///< distance: the rigid row
  float lower_impulse = 0.0f;  ///< lower limit (hinge, prismatic, twist, min length)
  float upper_impulse = 0.0f;  ///< upper limit (same, max length)
  float cone_impulse = 0.0f;   ///< ball: the swing cone
};

/// A query scheduled to run inside the step (World3D::schedule_raycast,
/// schedule_overlap), as given, on the canonical grid. Rays use `ray`;
/// overlaps use `shape`, `position` and `rotation` (the shape's authored
/// frame, rotation unit).
struct ScheduledQueryRecord {
  uint64_t ticket = 0;  ///< QueryTicket::id
  uint64_t user_tag = 0;
  ScheduledQueryKind kind = ScheduledQueryKind::kRaycast;
  QueryPhase phase = QueryPhase::kPrePhysics;
  uint8_t repeat = 0;  ///< 1: every step until cancelled (QueryRepeat::kEveryStep)
  QueryFilter filter;
  Ray ray;
  Shape shape;
  Vec3 position;
  Quat rotation;
};

/// All persistent state of a World3D.
struct WorldState {
  WorldConfig config;
  uint64_t step_count = 0;
  uint32_t live_count = 0;
  std::vector<BodyInfo> infos;   ///< one per slot, live or dead
  std::vector<BodySim> sims;     ///< one per slot
  std::vector<BodyMass> masses;  ///< one per slot
  /// Dead slot indices, sorted descending so back() is the lowest free slot.
  std::vector<uint32_t> free_slots;
  /// Contact cache sorted by (index_a, index_b, part); source of warm starting,
  /// contact events (previous touching pairs) and sleeping contacts.
  std::vector<ContactRecord> contacts;
  /// Joint slots, live or dead, by JointId::index; solved in this order.
  std::vector<JointRecord> joints;
  uint32_t live_joints = 0;
  /// Scheduled queries in scheduling order (ascending tickets). They are
  /// state, one-shot ones included: a snapshot taken between scheduling
  /// and stepping steps the same after a restore.
  std::vector<ScheduledQueryRecord> queries;
  /// The last QueryTicket::id handed out (0: none ever).
  uint64_t last_query_ticket = 0;
  /// Derived, neither hashed nor encoded: the last step found no body
  /// awake and only resting pairs in the contact cache, and reported
  /// nothing, and no body has been woken, made, destroyed, moved or
  /// switched since. A step of such a world changes nothing but the step
  /// count, so it is skipped (World3D::step). Anything that wakes a body
  /// (d3::wake_body) or edits the world clears it; a restore clears it.
  bool at_rest = false;
};

static_assert(std::is_trivially_copyable_v<BodyInfo>);
static_assert(std::is_trivially_copyable_v<BodySim>);
static_assert(std::is_trivially_copyable_v<BodyMass>);
static_assert(std::is_trivially_copyable_v<ContactRecord>);
static_assert(std::is_trivially_copyable_v<JointRecord>);
static_assert(std::is_trivially_copyable_v<ScheduledQueryRecord>);
static_assert(std::is_copy_assignable_v<WorldState>);

}  // namespace rwd::sim
