// SPDX-License-Identifier: MIT
// Grab (mouse) joint: a soft spring pulls body B's anchor toward a world
// target, never harder than max_force; a weak angular damper keeps the
// grabbed body from whirling about the grab point.
#include "joint_math2d.h"

namespace rwd::sim2d::detail {

void warm_start_grab(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& b) {
  const V2 rb = rotate(b.dq, c.frame_b);
  b.v = vmul_add(b.v, b.inv_mass, j.linear_impulse);
  b.w += wmul(b.inv_inertia, vcross(rb, j.linear_impulse) + j.angular_impulse);
}

void solve_grab(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& b,
                const JointPass2D& pass) {
  {
    const W impulse = -wmul(wmul(c.angular_mass, c.angular_spring.mass_scale), b.w) -
                      wmul(c.angular_spring.impulse_scale, j.angular_impulse);
    j.angular_impulse += impulse;
    b.w += wmul(b.inv_inertia, impulse);
  }
  const V2 rb = rotate(b.dq, c.frame_b);
  const V2 cdot = b.v + vcross_sv(b.w, rb);
  const V2 separation = b.dp + rb + c.delta_center;
  const V2 bias = vscale(c.spring.bias_rate, separation);
  const W k11 = b.inv_mass + wmul(b.inv_inertia, wmul(rb.y, rb.y));
  const W k12 = -wmul(b.inv_inertia, wmul(rb.x, rb.y));
  const W k22 = b.inv_mass + wmul(b.inv_inertia, wmul(rb.x, rb.x));
  const V2 x = solve22(k11, k12, k22, cdot + bias);
  const V2 old = j.linear_impulse;
  V2 next = old - vscale(c.spring.mass_scale, x) - vscale(c.spring.impulse_scale, old);
  // No more than max_force: the accumulated impulse is scaled back onto
  // the circle of max_force * h.
  const W max_impulse = wmul(pass.h, j.max_force);
  const W length = vlength(next);
  if (length > max_impulse) next = vscale(wdiv(max_impulse, length), next);
  j.linear_impulse = next;
  const V2 applied = next - old;
  b.v = vmul_add(b.v, b.inv_mass, applied);
  b.w += wmul(b.inv_inertia, vcross(rb, applied));
}

}  // namespace rwd::sim2d::detail
