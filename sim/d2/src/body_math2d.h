// SPDX-License-Identifier: MIT
#pragma once
// Small conversions between a body record and what the API speaks of.
#include "body_mass2d.h"
#include "rewind/core/status.h"
#include "rewind/sim2d/world2d_state.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// The rotation by `angle` radians, unit to the last bits.
Rot rotation_from_angle(Fx angle);

/// The body origin's transform (the shape's frame).
inline Xf origin_transform(const BodyRecord2D& body) {
  return {body.center - rotate(body.rotation, body.local_center), body.rotation};
}

/// kInvalidArgument naming the limit when a dynamic body of this mass and
/// inertia is outside the range body2d.h documents (kMinBodyMass2D ..
/// kMaxBodyMass2D, kMinBodyInertia2D .. kMaxBodyInertia2D); the inertia is
/// not checked for a body that never turns.
Status check_mass_range(const MassData2& mass, bool lock_rotation);

/// Sets local_center, inv_mass and inv_inertia from `mass` (the body's
/// shape at its density; check_mass_range() passed). Static and kinematic
/// bodies get zero inverses and turn about their origin (local_center
/// zero); a locked rotation has zero inverse inertia.
void set_mass(BodyRecord2D& body, const MassData2& mass);

/// The body's mass in kg (0 when it has no finite mass): the inverse of
/// the inverse mass the solver uses.
W body_mass(const BodyRecord2D& body);
/// Its rotational inertia about the centre of mass in kg m^2 (0 when it
/// never turns), likewise from the inverse.
W body_inertia(const BodyRecord2D& body);

}  // namespace rwd::sim2d::detail

namespace rwd::sim2d::detail {

/// Whether the body moves this step: an awake dynamic body, or a
/// kinematic one with a velocity. Pairs without a moving body are not
/// collided (their contacts are kept as they were).
inline bool is_moving(const BodyRecord2D& body) {
  if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled)) return false;
  if (body.kind == BodyKind2D::kDynamic) return (body.flags & kBodyAwake) != 0;
  return body.kind == BodyKind2D::kKinematic &&
         (body.velocity.x != 0 || body.velocity.y != 0 || body.angular_velocity != 0);
}

/// Wakes a dynamic body (no-op for others): it is simulated again from
/// this step and counts its time to sleep from zero.
inline void wake(BodyRecord2D& body) {
  if (body.kind != BodyKind2D::kDynamic) return;
  body.flags |= kBodyAwake;
  body.sleep_time = 0;
}

/// v with each component limited to the world's max_linear_speed.
inline V2 clamp_speed(V2 v, const World2DConfig& config) {
  const W cap = w_from(config.max_linear_speed);
  return {wclamp(v.x, -cap, cap), wclamp(v.y, -cap, cap)};
}

}  // namespace rwd::sim2d::detail
