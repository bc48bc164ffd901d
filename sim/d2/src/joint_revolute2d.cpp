// SPDX-License-Identifier: MIT
// Revolute joint: a shared point, with an optional angular spring toward
// the angle at creation, a motor and angle limits.
#include "joint_math2d.h"

namespace rwd::sim2d::detail {

void prepare_revolute(JointConstraint2D& c, const SolverBody2D& a, const SolverBody2D& b) {
  const PointMass2D k = point_mass(a, b, {c.frame_a, c.frame_b});
  const W det = wmul(k.k11, k.k22) - wmul(k.k12, k.k12);
  if (det == 0) return;  // nothing can move the point: every row's impulse is zero
  c.point_inv_k11 = wdiv(k.k22, det);
  c.point_inv_k12 = wdiv(-k.k12, det);
  c.point_inv_k22 = wdiv(k.k11, det);
}

void warm_start_revolute(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                         SolverBody2D& b) {
  const Anchors2D r = current_anchors(c, a, b);
  apply_linear(a, b, r, j.linear_impulse);
  apply_angular(a, b, j.spring_impulse + j.motor_impulse + j.lower_impulse - j.upper_impulse);
}

void solve_revolute(JointRecord2D& j, JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                    const JointPass2D& pass) {
  const bool turns = c.angular_mass > 0;
  // The angle moves only when positions do, between passes: the spring and
  // the limits share one evaluation, and passes between the same two
  // position integrations share it too.
  if (turns && (j.flags & (kJointSpring | kJointLimit)) && c.angle_positions != pass.positions) {
    c.angle = joint_angle(c, a, b);
    c.angle_positions = pass.positions;
  }
  const W angle = c.angle;
  if ((j.flags & kJointSpring) && turns) {
    const W impulse = -wmul(wmul(c.angular_mass, c.spring.mass_scale),
                            b.w - a.w + wmul(c.spring.bias_rate, angle)) -
                      wmul(c.spring.impulse_scale, j.spring_impulse);
    j.spring_impulse += impulse;
    apply_angular(a, b, impulse);
  }
  if ((j.flags & kJointMotor) && turns) {
    const W max_impulse = wmul(pass.h, j.max_motor);
    const W next = wclamp(j.motor_impulse - wmul(c.angular_mass, b.w - a.w - j.motor_speed),
                          -max_impulse, max_impulse);
    const W applied = next - j.motor_impulse;
    j.motor_impulse = next;
    apply_angular(a, b, applied);
  }
  if ((j.flags & kJointLimit) && turns) {
    solve_angle_limit(angle - j.lower, kWOne, j.lower_impulse, c.angular_mass, c.soft, a, b, pass);
    solve_angle_limit(j.upper - angle, -kWOne, j.upper_impulse, c.angular_mass, c.soft, a, b, pass);
  }
  // The point, last: it matters most.
  const Anchors2D r = current_anchors(c, a, b);
  const V2 cdot = anchor_velocity(a, b, r);
  if (!pass.use_bias) {
    // Relaxing: mass scale one (the product by kWOne is exact), no bias and
    // no impulse term.
    const V2 impulse = -V2{wmul_add(c.point_inv_k11, cdot.x, c.point_inv_k12, cdot.y),
                           wmul_add(c.point_inv_k12, cdot.x, c.point_inv_k22, cdot.y)};
    j.linear_impulse += impulse;
    apply_linear(a, b, r, impulse);
    return;
  }
  const V2 e = cdot + vscale(c.soft.bias_rate, anchor_separation(c, a, b, r));
  const V2 x = {wmul_add(c.point_inv_k11, e.x, c.point_inv_k12, e.y),
                wmul_add(c.point_inv_k12, e.x, c.point_inv_k22, e.y)};
  const V2 impulse = -vscale(c.soft.mass_scale, x) - vscale(c.soft.impulse_scale, j.linear_impulse);
  j.linear_impulse += impulse;
  apply_linear(a, b, r, impulse);
}

}  // namespace rwd::sim2d::detail
