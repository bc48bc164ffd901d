// SPDX-License-Identifier: MIT
// Weld joint: the bodies keep their relative pose, rigidly or through a
// linear and an angular spring.
#include "joint_math2d.h"

namespace rwd::sim2d::detail {

void warm_start_weld(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                     SolverBody2D& b) {
  const Anchors2D r = current_anchors(c, a, b);
  apply_linear(a, b, r, j.linear_impulse);
  apply_angular(a, b, j.angular_impulse);
}

void solve_weld(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                const JointPass2D& pass) {
  // A soft weld is a spring in every pass; a rigid one pushes its error
  // out only in the biased pass.
  {
    BiasTerms2D t;
    if (pass.use_bias || j.angular_hertz > 0) {
      t = {wmul(c.angular_spring.bias_rate, joint_angle(c, a, b)), c.angular_spring.mass_scale,
           c.angular_spring.impulse_scale};
    }
    const W impulse = -wmul(wmul(c.angular_mass, t.mass_scale), b.w - a.w + t.bias) -
                      wmul(t.impulse_scale, j.angular_impulse);
    j.angular_impulse += impulse;
    apply_angular(a, b, impulse);
  }
  const Anchors2D r = current_anchors(c, a, b);
  V2 bias;
  W mass_scale = kWOne;
  W impulse_scale = 0;
  if (pass.use_bias || j.linear_hertz > 0) {
    bias = vscale(c.spring.bias_rate, anchor_separation(c, a, b, r));
    mass_scale = c.spring.mass_scale;
    impulse_scale = c.spring.impulse_scale;
  }
  const PointMass2D k = point_mass(a, b, r);
  const V2 x = solve22(k.k11, k.k12, k.k22, anchor_velocity(a, b, r) + bias);
  const V2 impulse = -vscale(mass_scale, x) - vscale(impulse_scale, j.linear_impulse);
  j.linear_impulse += impulse;
  apply_linear(a, b, r, impulse);
}

}  // namespace rwd::sim2d::detail
