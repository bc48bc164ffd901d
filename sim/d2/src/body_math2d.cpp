// SPDX-License-Identifier: MIT
#include "body_math2d.h"

#include "body_mass2d.h"
#include "rewind/fixed/trig.h"

namespace rwd::sim2d::detail {

Rot rotation_from_angle(Fx angle) {
  const fixed::SinCos sc = fixed::sin_cos(angle);
  // CORDIC gives each component to an ulp of Q16.16; two Newton steps bring
  // the pair to unit length in Q32.32.
  return renormalize({w_from(sc.cos), w_from(sc.sin)});
}

void set_mass_from_shape(BodyRecord2D& body, W density) {
  body.local_center = {};
  body.inv_mass = 0;
  body.inv_inertia = 0;
  // Static and kinematic bodies turn about their origin, whatever their
  // shape: a kinematic wall of a tumbler, authored off-centre, turns about
  // the tumbler's axis.
  if (body.kind != BodyKind2D::kDynamic) return;
  const MassData2 mass = compute_mass(body.shape, density);
  body.local_center = mass.center;
  body.inv_mass = mass.mass > 0 ? winv(mass.mass) : 0;
  if (!(body.flags & kBodyLockRotation) && mass.inertia > 0) body.inv_inertia = winv(mass.inertia);
}

W body_mass(const BodyRecord2D& body) {
  return body.inv_mass > 0 ? winv(body.inv_mass) : 0;
}

}  // namespace rwd::sim2d::detail
