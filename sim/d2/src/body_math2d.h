// SPDX-License-Identifier: MIT
#pragma once
// Small conversions between a body record and what the API speaks of.
#include "rewind/sim2d/world2d_state.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// The rotation by `angle` radians, unit to the last bits.
Rot rotation_from_angle(Fx angle);

/// The body origin's transform (the shape's frame).
inline Xf origin_transform(const BodyRecord2D& body) {
  return {body.center - rotate(body.rotation, body.local_center), body.rotation};
}

/// Sets local_center, inv_mass and inv_inertia from the shape and density
/// (kg/m^2). Static and kinematic bodies get zero inverses and turn about
/// their origin (local_center zero); a locked rotation has zero inverse
/// inertia.
void set_mass_from_shape(BodyRecord2D& body, W density);

/// The body's mass in kg (0 when it has no finite mass).
W body_mass(const BodyRecord2D& body);

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
