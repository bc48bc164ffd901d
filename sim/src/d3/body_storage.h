// SPDX-License-Identifier: MIT
#pragma once
// Body mass properties, bounds and the predicates every stage shares.
// What counts as a valid body is state_rules.h's business.
#include "d3/world_scratch.h"
#include "rewind/sim/body.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Mass, inverse mass and principal inverse inertia from density and shape
/// (its geometry in `store`); zero for static and kinematic bodies
/// (infinite mass).
BodyMass compute_mass(BodyKind kind, const Shape& shape, const GeometryStore& store, float density);
/// Tight world bounds of the shape at a pose (`axes` = mat3_from_quat of
/// its rotation).
Aabb shape_aabb(const Shape& shape, Vec3 position, const Mat3& axes);
Aabb shape_aabb(const Shape& shape, Vec3 position, Quat rotation);
/// The world-frame inverse inertia tensor (`axes` as above).
Mat3 world_inverse_inertia(const BodyMass& mass, const Mat3& axes);
Mat3 world_inverse_inertia(const BodyMass& mass, Quat rotation);

/// v without its components about the world axes `locks` names
/// (kLockRotation* bits): an angular velocity or impulse a locked body may
/// take.
inline Vec3 without_locked_axes(uint8_t locks, Vec3 v) {
  if ((locks & kLockRotationX) != 0) v.x = 0.0f;
  if ((locks & kLockRotationY) != 0) v.y = 0.0f;
  if ((locks & kLockRotationZ) != 0) v.z = 0.0f;
  return v;
}
/// A world inverse inertia with the rows and columns of the locked axes
/// cleared: no torque turns the body about them, and the solver's
/// effective masses account for that.
inline Mat3 lock_inverse_inertia(uint8_t locks, Mat3 m) {
  if (locks == 0) return m;
  m.c0 = without_locked_axes(locks, m.c0);
  m.c1 = without_locked_axes(locks, m.c1);
  m.c2 = without_locked_axes(locks, m.c2);
  if ((locks & kLockRotationX) != 0) m.c0 = {};
  if ((locks & kLockRotationY) != 0) m.c1 = {};
  if ((locks & kLockRotationZ) != 0) m.c2 = {};
  return m;
}

/// Starts a step's body frames: every frame of earlier steps goes stale.
inline void begin_body_axes(const WorldState& state, WorldScratch& scratch) {
  ++scratch.step_serial;
  scratch.axes.resize(state.infos.size());
  scratch.axes_step.resize(state.infos.size(), 0);
}
/// Records body i's frame for this step (its pose must not move until the
/// step's solve).
inline const Mat3& set_body_axes(WorldScratch& scratch, uint32_t i, Quat rotation) {
  scratch.axes[i] = mat3_from_quat(rotation);
  scratch.axes_step[i] = scratch.step_serial;
  return scratch.axes[i];
}
/// Body i's rotation matrix at the start of this step, computed once per
/// step and body (the broadphase, the narrowphase's pairs and the solver's
/// inertia share it, bit for bit what mat3_from_quat gives).
inline const Mat3& body_axes(const WorldState& state, WorldScratch& scratch, uint32_t i) {
  if (scratch.axes_step[i] == scratch.step_serial) return scratch.axes[i];
  return set_body_axes(scratch, i, state.sims[i].rotation);
}

inline bool is_live(const WorldState& s, BodyId id) {
  return id.generation != 0 && id.index < s.infos.size() && s.infos[id.index].alive != 0 &&
         s.infos[id.index].generation == id.generation;
}
/// Live and enabled: takes part in pairs, contacts, islands and queries
/// (asleep or awake).
inline bool is_simulated(const BodyInfo& info) {
  return info.alive != 0 && info.enabled != 0;
}
/// Awake and able to move: the bodies the step integrates and pairs.
/// (Disabled bodies are never awake.)
inline bool is_active(const BodyInfo& info) {
  return info.alive != 0 && info.awake != 0 && info.kind != BodyKind::kStatic;
}

}  // namespace rwd::sim::d3
