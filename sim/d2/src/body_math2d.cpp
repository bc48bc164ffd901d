// SPDX-License-Identifier: MIT
#include "body_math2d.h"

#include "rewind/fixed/trig.h"

namespace rwd::sim2d::detail {

Rot rotation_from_angle(Fx angle) {
  const fixed::SinCos sc = fixed::sin_cos(angle);
  // CORDIC gives each component to an ulp of Q16.16; two Newton steps bring
  // the pair to unit length in Q32.32.
  return renormalize({w_from(sc.cos), w_from(sc.sin)});
}

Status check_mass_range(const MassData2& mass, bool lock_rotation) {
  auto invalid = [](const char* message) {
    return Status::Error(ErrorCode::kInvalidArgument, message);
  };
  if (mass.mass < kMinBodyMass2D.raw()) {
    return invalid("the body's mass (shape area x density) is below 2^-30 kg (kMinBodyMass2D)");
  }
  if (mass.mass > kMaxBodyMass2D.raw()) {
    return invalid("the body's mass (shape area x density) is above 2^20 kg (kMaxBodyMass2D)");
  }
  if (lock_rotation) return Status::Ok();
  if (mass.inertia < kMinBodyInertia2D.raw()) {
    return invalid(
        "the body's rotational inertia is below 2^-30 kg m^2 (kMinBodyInertia2D): "
        "lock its rotation or make it denser");
  }
  if (mass.inertia > kMaxBodyInertia2D.raw()) {
    return invalid(
        "the body's rotational inertia is above 2^28 kg m^2 (kMaxBodyInertia2D): "
        "lock its rotation or make it lighter or smaller");
  }
  return Status::Ok();
}

void set_mass(BodyRecord2D& body, const MassData2& mass) {
  body.local_center = {};
  body.inv_mass = 0;
  body.inv_inertia = 0;
  // Static and kinematic bodies turn about their origin, whatever their
  // shape: a kinematic wall of a tumbler, authored off-centre, turns about
  // the tumbler's axis.
  if (body.kind != BodyKind2D::kDynamic) return;
  body.local_center = mass.center;
  // check_mass_range() keeps both in the int64 range and their inverses too.
  body.inv_mass = winv(static_cast<W>(mass.mass));
  if (!(body.flags & kBodyLockRotation)) body.inv_inertia = winv(static_cast<W>(mass.inertia));
}

W body_mass(const BodyRecord2D& body) {
  return body.inv_mass > 0 ? winv(body.inv_mass) : 0;
}

W body_inertia(const BodyRecord2D& body) {
  return body.inv_inertia > 0 ? winv(body.inv_inertia) : 0;
}

}  // namespace rwd::sim2d::detail
