// SPDX-License-Identifier: MIT
// Distance joint: rigid at `length` when min == max and no spring; a rope
// or slack range [min_length, max_length] otherwise, with an optional
// spring toward `length` inside it.
#include "joint_math2d.h"

namespace rwd::sim2d::detail {

namespace {

struct Axis2D {
  V2 unit;
  W length = 0;
};

Axis2D current_axis(const JointConstraint2D& c, const SolverBody2D& a, const SolverBody2D& b,
                    const Anchors2D& r) {
  const UnitLength ul = vnormalize(anchor_separation(c, a, b, r));
  return {ul.unit, ul.length};
}

bool is_rigid(const JointRecord2D& j) {
  return j.min_length == j.max_length && !(j.flags & kJointSpring);
}

}  // namespace

void prepare_distance(const JointRecord2D& /*j*/, JointConstraint2D& c, const SolverBody2D& a,
                      const SolverBody2D& b) {
  const Anchors2D r{c.frame_a, c.frame_b};
  const V2 axis = vnormalize(c.delta_center + (r.rb - r.ra)).unit;
  const W cra = vcross(r.ra, axis);
  const W crb = vcross(r.rb, axis);
  const W k = a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(cra, cra)) +
              wmul(b.inv_inertia, wmul(crb, crb));
  c.axial_mass = k > 0 ? winv(k) : 0;
}

void warm_start_distance(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                         SolverBody2D& b) {
  const Anchors2D r = current_anchors(c, a, b);
  const Axis2D axis = current_axis(c, a, b, r);
  const W impulse = j.axial_impulse + j.spring_impulse + j.lower_impulse - j.upper_impulse;
  apply_linear(a, b, r, vscale(impulse, axis.unit));
}

void solve_distance(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                    const JointPass2D& pass) {
  const Anchors2D r = current_anchors(c, a, b);
  const Axis2D axis = current_axis(c, a, b, r);
  auto axial_velocity = [&] { return vdot(anchor_velocity(a, b, r), axis.unit); };

  if (is_rigid(j)) {
    const W error = axis.length - j.length;
    BiasTerms2D t;
    if (pass.use_bias) t = {wmul(c.soft.bias_rate, error), c.soft.mass_scale, c.soft.impulse_scale};
    const W impulse = -wmul(wmul(c.axial_mass, t.mass_scale), axial_velocity() + t.bias) -
                      wmul(t.impulse_scale, j.axial_impulse);
    j.axial_impulse += impulse;
    apply_linear(a, b, r, vscale(impulse, axis.unit));
    return;
  }
  if (j.flags & kJointSpring) {
    const W error = axis.length - j.length;
    const W impulse = -wmul(wmul(c.axial_mass, c.spring.mass_scale),
                            axial_velocity() + wmul(c.spring.bias_rate, error)) -
                      wmul(c.spring.impulse_scale, j.spring_impulse);
    j.spring_impulse += impulse;
    apply_linear(a, b, r, vscale(impulse, axis.unit));
  }
  // The range: the anchors never come closer than min_length nor part
  // farther than max_length (a rope when min_length is 0).
  {
    const BiasTerms2D t = one_sided_bias(axis.length - j.min_length, c.soft, pass);
    const W impulse = -wmul(wmul(c.axial_mass, t.mass_scale), axial_velocity() + t.bias) -
                      wmul(t.impulse_scale, j.lower_impulse);
    const W next = wmax(j.lower_impulse + impulse, 0);
    const W applied = next - j.lower_impulse;
    j.lower_impulse = next;
    apply_linear(a, b, r, vscale(applied, axis.unit));
  }
  {
    const BiasTerms2D t = one_sided_bias(j.max_length - axis.length, c.soft, pass);
    const W impulse = -wmul(wmul(c.axial_mass, t.mass_scale), -axial_velocity() + t.bias) -
                      wmul(t.impulse_scale, j.upper_impulse);
    const W next = wmax(j.upper_impulse + impulse, 0);
    const W applied = next - j.upper_impulse;
    j.upper_impulse = next;
    apply_linear(a, b, r, vscale(-applied, axis.unit));
  }
}

}  // namespace rwd::sim2d::detail
