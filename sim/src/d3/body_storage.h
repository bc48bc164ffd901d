// SPDX-License-Identifier: MIT
#pragma once
// Body validation, mass properties and bounds.
#include "d3/world_scratch.h"
#include "rewind/sim/body.h"
#include "rewind/sim/status.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Largest accepted |position| component, metres.
inline constexpr float kMaxCoordinate = 1e5f;
/// Largest accepted radius or half extent, metres.
inline constexpr float kMaxShapeSize = 1000.0f;
/// Largest accepted speed, m/s or rad/s, for bodies created or set.
inline constexpr float kMaxSpeed = 1e4f;

Status validate_shape(const Shape& shape);
Status validate_body_def(const BodyDef& def);
/// Mass, inverse mass and principal inverse inertia from density and shape;
/// zero for static and kinematic bodies (infinite mass).
BodyMass compute_mass(BodyKind kind, const Shape& shape, float density);
/// Tight world bounds of the shape at a pose.
Aabb shape_aabb(const Shape& shape, Vec3 position, Quat rotation);
/// The world-frame inverse inertia tensor.
Mat3 world_inverse_inertia(const BodyMass& mass, Quat rotation);

inline bool is_live(const WorldState& s, BodyId id) {
  return id.generation != 0 && id.index < s.infos.size() && s.infos[id.index].alive != 0 &&
         s.infos[id.index].generation == id.generation;
}
/// Awake and able to move: the bodies the step integrates and pairs.
inline bool is_active(const BodyInfo& info) {
  return info.alive != 0 && info.awake != 0 && info.kind != BodyKind::kStatic;
}

}  // namespace rwd::sim::d3
