// SPDX-License-Identifier: MIT
#include "d3/angular_momentum.h"

#include <cmath>

namespace rwd::sim::d3 {

// The gyroscopic term. The solver holds the inertia tensor fixed at the
// tick's starting orientation, so its angular velocity belongs to that
// orientation: the world angular momentum is L = I(q0) w. A free body keeps
// L while its inertia turns with it, so the velocity it ends the tick with
// is I(q1)^-1 L: this is what makes a box spun about its intermediate axis
// tumble (the Dzhanibekov effect) instead of spinning forever.
//
// The orientation q1 came from the tick's starting velocity, an explicit
// step that on its own pumps energy into a tumbling body (an explicit torque
// w x Iw does the same; an implicit one, as in Bullet, drains it). The
// gyroscopic term does no work, so the body-frame momentum is moved along the
// sphere |L| = const back onto the energy ellipsoid L.I^-1.L = 2E of the
// tick's start (two Newton steps), and the orientation is turned by the same
// small body-frame rotation, so the world momentum stays exactly L. Both
// invariants then hold to rounding.

Spin carry_angular_momentum(const BodyMass& mass, Quat q0, Quat q1, Vec3 w) {
  const Vec3 inv = mass.inv_inertia_local;
  // Equal principal moments (spheres, cubes): the inertia tensor does not
  // change as the body turns, so neither does w.
  if (inv.x == inv.y && inv.y == inv.z) return {w, q1};
  const Vec3 inertia{1.0f / inv.x, 1.0f / inv.y, 1.0f / inv.z};
  const Vec3 l_world = rotate(q0, mul_elements(inertia, inv_rotate(q0, w)));
  const float two_energy = dot(w, l_world);
  const float l_sq = length_squared(l_world);
  const Vec3 carried = inv_rotate(q1, l_world);  // body frame at the tick's end
  if (!(l_sq > 0.0f) || !(two_energy > 0.0f)) return {rotate(q1, mul_elements(inv, carried)), q1};
  Vec3 l = carried;
  for (int i = 0; i < 2; ++i) {
    const Vec3 g = mul_elements(inv, l);  // the body-frame w; L.I^-1.L has gradient 2g
    const float error = dot(l, g) - two_energy;
    // The gradient's part tangent to the momentum sphere.
    const Vec3 t = g - l * (dot(g, l) / length_squared(l));
    const float slope = 2.0f * dot(g, t);
    if (!(slope > 1e-12f * two_energy)) break;  // on a principal axis: nothing to correct
    Vec3 next = l - t * (error / slope);
    next = next * std::sqrt(l_sq / length_squared(next));
    if (!is_finite(next)) break;
    l = next;
  }
  // The body-frame rotation r taking l to `carried`: q1 r maps l to L.
  const Vec3 axis = cross(l, carried);
  const Quat r = normalize(Quat{axis.x, axis.y, axis.z, l_sq + dot(l, carried)});
  const Quat q = normalize(q1 * r);
  if (!is_finite(q)) return {rotate(q1, mul_elements(inv, carried)), q1};
  return {rotate(q, mul_elements(inv, l)), q};
}

}  // namespace rwd::sim::d3
