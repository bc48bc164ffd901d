// SPDX-License-Identifier: MIT
#pragma once
// Body mass properties, bounds and the predicates every stage shares.
// What counts as a valid body is state_rules.h's business.
#include "d3/world_scratch.h"
#include "rewind/sim/body.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

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
