// SPDX-License-Identifier: MIT
#pragma once
// The one rule for valid 3D state. Everything that puts a value into
// WorldState goes through here:
//   - the API (create_body, setters) refuses values the rule refuses;
//   - deserialize() refuses snapshots holding a value the rule refuses;
//   - the step settles every body it moved back under the rule (speeds
//     clamped, non-finite results discarded, bodies that left the world
//     bounds disabled), so no state the step reaches is one a snapshot
//     reader would refuse.
// A change to one of these limits changes all three at once.
#include <cmath>
#include <cstdint>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/sim/body.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/query.h"
#include "rewind/sim/world_config.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Largest |component| of the world bounds, metres.
inline constexpr float kMaxCoordinate = 1e5f;
/// Largest accepted radius or half extent, metres.
inline constexpr float kMaxShapeSize = 1000.0f;
/// Largest speed a body may hold, m/s (linear) or rad/s (angular).
inline constexpr float kMaxSpeed = 1e4f;
/// Largest force accumulated for one step, N.
inline constexpr float kMaxForce = 1e12f;
/// Largest torque accumulated for one step, N m.
inline constexpr float kMaxTorque = 1e12f;
/// Largest deviation of |q|^2 from 1 in a stored rotation.
inline constexpr float kRotationTolerance = 1e-3f;

/// Relative slack on the substep limit, so that a 60 Hz tick cut in four
/// counts as 1/240 s whatever the rounding of either.
inline constexpr float kSubstepTolerance = 1.0001f;
/// One substep's length, seconds.
inline float substep_seconds(const WorldConfig& c) {
  return c.tick_seconds / static_cast<float>(c.substeps);
}
/// Range and finiteness of every config field, bounds included, and the
/// substep's length.
Status check_config(const WorldConfig& config);
/// Size of a shape, and the geometry it refers to (in `store`).
Status check_shape(const Shape& shape, const GeometryStore& store);
/// A body definition as create_body() receives it (before quantization).
Status check_body_def(const WorldConfig& config, const GeometryStore& store, const BodyDef& def);
/// Mass properties of a body: finite and positive for dynamic bodies.
Status check_mass(BodyKind kind, const BodyMass& mass);
/// A stored body: identity flags, shape, material, pose inside the world
/// bounds, speeds, accumulated force, sleep timer, and the flags' mutual
/// consistency (static and disabled bodies never awake nor moving).
Status check_body(const WorldConfig& config, const GeometryStore& store, const BodyInfo& info,
                  const BodySim& sim);

/// A contact cache record against the body slots it names and the record
/// before it (null for the first): ordered pair of existing slots, sorted
/// after `previous`, at most kMaxManifoldPoints finite impulses, sensors
/// without points, points and manifold frame in range (unit rotation and
/// normal). Records may name a body destroyed or disabled since the
/// last step: the next step ends them with exit events.
Status check_contact(const std::vector<BodyInfo>& infos, const ContactRecord& record,
                     const ContactRecord* previous);

/// A stored joint against the body slots: a known type and flags, live
/// bodies of the generations it names (a destroyed body's joints go with
/// it), two different bodies (or the world and a body), unit frames, and
/// every setting within the range create_joint() accepts.
Status check_joint(const WorldConfig& config, const std::vector<BodyInfo>& infos,
                   const JointRecord& joint);

/// Largest ray length and |component| of a scheduled query's position,
/// metres (far past any world's bounds).
inline constexpr float kMaxQueryDistance = 1e6f;
/// A ray as a scheduled query takes it: finite, a direction that
/// normalizes to a unit vector, max_distance in [0, kMaxQueryDistance].
Status check_query_ray(const Ray& ray);
/// A scheduled overlap's pose: position within kMaxQueryDistance, rotation
/// finite and not zero.
Status check_query_pose(Vec3 position, Quat rotation);
/// A stored scheduled query against the store and the tickets handed out:
/// a ticket in (previous's, last_ticket], known kind and phase, a valid ray
/// or a valid shape at a valid pose with a unit rotation.
Status check_query(const GeometryStore& store, const ScheduledQueryRecord& query,
                   uint64_t last_ticket, const ScheduledQueryRecord* previous);

/// Largest |anchor| or joint length, metres.
inline constexpr float kMaxJointReach = 1e4f;

/// True when `p` lies inside the config's bounds (faces included).
bool inside_bounds(const WorldConfig& config, Vec3 p);
/// `v` scaled down to length `max` when it is longer; zero when not finite.
Vec3 clamp_length(Vec3 v, float max);
/// Whether w is zero about every world axis `locks` (kLockRotation* bits)
/// names.
inline bool angular_velocity_respects_locks(uint8_t locks, Vec3 w) {
  return ((locks & kLockRotationX) == 0 || w.x == 0.0f) &&
         ((locks & kLockRotationY) == 0 || w.y == 0.0f) &&
         ((locks & kLockRotationZ) == 0 || w.z == 0.0f);
}

/// A shape size (radius, half extent, half height): finite, in
/// (0, kMaxShapeSize] metres.
inline bool in_shape_size_range(float v) {
  return std::isfinite(v) && v > 0.0f && v <= kMaxShapeSize;
}

/// A solver impulse as it may be cached: non-finite values become zero.
inline float settle_impulse(float impulse) {
  return std::isfinite(impulse) ? impulse : 0.0f;
}

/// Brings a body the step has just moved back under the rule. `before` is
/// its state at the start of the step. Non-finite poses fall back to
/// `before`'s, speeds are clamped to kMaxSpeed, and a body whose centre left
/// the world bounds is clamped onto them and disabled. Returns true when
/// the body was disabled (the caller reports it).
bool settle_body(const WorldConfig& config, const BodySim& before, BodyInfo& info, BodySim& sim);

/// Takes a live body out of the simulation where it stands: not awake,
/// not moving, no pending force. Its contacts end on the next step.
void disable_body(BodyInfo& info, BodySim& sim);

}  // namespace rwd::sim::d3
