// SPDX-License-Identifier: MIT
// The two joints that slide along an axis fixed in body A. Prismatic: no
// turning, a motor, a spring and limits along the axis. Wheel: turns
// freely about its anchor, a suspension spring along the axis, an angular
// motor, and limits on the travel.
#include "joint_math2d.h"

namespace rwd::sim2d::detail {

namespace {

// The axis and the lever arms of the axial and perpendicular rows, now.
struct SliderFrame2D {
  Anchors2D r;
  V2 d;  ///< B's anchor minus A's
  V2 axis;
  V2 perp;
  W a1 = 0;  ///< (d + ra) x axis
  W a2 = 0;  ///< rb x axis
  W s1 = 0;  ///< (d + ra) x perp
  W s2 = 0;  ///< rb x perp
  W translation = 0;
};

SliderFrame2D frame_now(const JointConstraint2D& c, const SolverBody2D& a, const SolverBody2D& b) {
  SliderFrame2D f;
  f.r = current_anchors(c, a, b);
  f.d = anchor_separation(c, a, b, f.r);
  f.axis = rotate(a.dq, c.axis_a);
  f.perp = vperp(f.axis);
  f.a1 = vcross(f.d + f.r.ra, f.axis);
  f.a2 = vcross(f.r.rb, f.axis);
  f.s1 = vcross(f.d + f.r.ra, f.perp);
  f.s2 = vcross(f.r.rb, f.perp);
  f.translation = vdot(f.axis, f.d);
  return f;
}

W axial_velocity(const SliderFrame2D& f, const SolverBody2D& a, const SolverBody2D& b) {
  return vdot(f.axis, b.v - a.v) + wmul(f.a2, b.w) - wmul(f.a1, a.w);
}

// `impulse` along the axis (and `perp_impulse` across it, `angular` about
// the anchors).
void apply_slider(SolverBody2D& a, SolverBody2D& b, const SliderFrame2D& f, W impulse,
                  W perp_impulse, W angular) {
  const V2 p = vscale(impulse, f.axis) + vscale(perp_impulse, f.perp);
  const W la = wmul(impulse, f.a1) + wmul(perp_impulse, f.s1) + angular;
  const W lb = wmul(impulse, f.a2) + wmul(perp_impulse, f.s2) + angular;
  a.v = vmul_sub(a.v, a.inv_mass, p);
  a.w -= wmul(a.inv_inertia, la);
  b.v = vmul_add(b.v, b.inv_mass, p);
  b.w += wmul(b.inv_inertia, lb);
}

// Spring toward zero travel, then the limits on the travel.
void solve_axial_rows(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                      SolverBody2D& b, const JointPass2D& pass) {
  if (j.flags & kJointSpring) {
    const SliderFrame2D f = frame_now(c, a, b);
    const W impulse = -wmul(wmul(c.axial_mass, c.spring.mass_scale),
                            axial_velocity(f, a, b) + wmul(c.spring.bias_rate, f.translation)) -
                      wmul(c.spring.impulse_scale, j.spring_impulse);
    j.spring_impulse += impulse;
    apply_slider(a, b, f, impulse, 0, 0);
  }
  if (j.flags & kJointLimit) {
    {
      const SliderFrame2D f = frame_now(c, a, b);
      const BiasTerms2D t = one_sided_bias(f.translation - j.lower, c.soft, pass);
      const W impulse = -wmul(wmul(c.axial_mass, t.mass_scale), axial_velocity(f, a, b) + t.bias) -
                        wmul(t.impulse_scale, j.lower_impulse);
      const W next = wmax(j.lower_impulse + impulse, 0);
      apply_slider(a, b, f, next - j.lower_impulse, 0, 0);
      j.lower_impulse = next;
    }
    {
      const SliderFrame2D f = frame_now(c, a, b);
      const BiasTerms2D t = one_sided_bias(j.upper - f.translation, c.soft, pass);
      const W impulse = -wmul(wmul(c.axial_mass, t.mass_scale), -axial_velocity(f, a, b) + t.bias) -
                        wmul(t.impulse_scale, j.upper_impulse);
      const W next = wmax(j.upper_impulse + impulse, 0);
      apply_slider(a, b, f, -(next - j.upper_impulse), 0, 0);
      j.upper_impulse = next;
    }
  }
}

}  // namespace

void prepare_slider(const JointRecord2D& /*j*/, JointConstraint2D& c, const SolverBody2D& a,
                    const SolverBody2D& b) {
  const V2 d = c.delta_center + (c.frame_b - c.frame_a);
  const W a1 = vcross(d + c.frame_a, c.axis_a);
  const W a2 = vcross(c.frame_b, c.axis_a);
  const W k = a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(a1, a1)) +
              wmul(b.inv_inertia, wmul(a2, a2));
  c.axial_mass = k > 0 ? winv(k) : 0;
}

void warm_start_slider(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                       SolverBody2D& b) {
  const SliderFrame2D f = frame_now(c, a, b);
  const W axial = j.spring_impulse + j.lower_impulse - j.upper_impulse +
                  (j.type == JointType2D::kPrismatic ? j.motor_impulse : 0);
  if (j.type == JointType2D::kPrismatic) {
    // linear_impulse holds (across the axis, about the anchors).
    apply_slider(a, b, f, axial, j.linear_impulse.x, j.linear_impulse.y);
  } else {
    apply_slider(a, b, f, axial, j.axial_impulse, 0);
    apply_angular(a, b, j.motor_impulse);
  }
}

void solve_prismatic(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                     const JointPass2D& pass) {
  if (j.flags & kJointMotor) {
    const SliderFrame2D f = frame_now(c, a, b);
    const W max_impulse = wmul(pass.h, j.max_motor);
    const W next =
        wclamp(j.motor_impulse + wmul(c.axial_mass, j.motor_speed - axial_velocity(f, a, b)),
               -max_impulse, max_impulse);
    apply_slider(a, b, f, next - j.motor_impulse, 0, 0);
    j.motor_impulse = next;
  }
  solve_axial_rows(j, c, a, b, pass);

  // Across the axis and about the anchors: two rows solved together.
  const SliderFrame2D f = frame_now(c, a, b);
  const V2 cdot{vdot(f.perp, b.v - a.v) + wmul(f.s2, b.w) - wmul(f.s1, a.w), b.w - a.w};
  V2 bias;
  W mass_scale = kWOne;
  W impulse_scale = 0;
  if (pass.use_bias) {
    bias = vscale(c.soft.bias_rate, V2{vdot(f.perp, f.d), joint_angle(c, a, b)});
    mass_scale = c.soft.mass_scale;
    impulse_scale = c.soft.impulse_scale;
  }
  const W k11 = a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(f.s1, f.s1)) +
                wmul(b.inv_inertia, wmul(f.s2, f.s2));
  const W k12 = wmul(a.inv_inertia, f.s1) + wmul(b.inv_inertia, f.s2);
  W k22 = a.inv_inertia + b.inv_inertia;
  if (k22 == 0) k22 = kWOne;  // neither body turns: the angle row is moot
  const V2 x = solve22(k11, k12, k22, cdot + bias);
  const V2 impulse = -vscale(mass_scale, x) - vscale(impulse_scale, j.linear_impulse);
  j.linear_impulse += impulse;
  apply_slider(a, b, f, 0, impulse.x, impulse.y);
}

void solve_wheel(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                 const JointPass2D& pass) {
  if ((j.flags & kJointMotor) && c.angular_mass > 0) {
    const W max_impulse = wmul(pass.h, j.max_motor);
    const W next = wclamp(j.motor_impulse - wmul(c.angular_mass, b.w - a.w - j.motor_speed),
                          -max_impulse, max_impulse);
    apply_angular(a, b, next - j.motor_impulse);
    j.motor_impulse = next;
  }
  solve_axial_rows(j, c, a, b, pass);

  // The wheel's centre stays on the axis.
  const SliderFrame2D f = frame_now(c, a, b);
  const W cdot = vdot(f.perp, b.v - a.v) + wmul(f.s2, b.w) - wmul(f.s1, a.w);
  BiasTerms2D t;
  if (pass.use_bias) {
    t = {wmul(c.soft.bias_rate, vdot(f.perp, f.d)), c.soft.mass_scale, c.soft.impulse_scale};
  }
  const W k = a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(f.s1, f.s1)) +
              wmul(b.inv_inertia, wmul(f.s2, f.s2));
  const W perp_mass = k > 0 ? winv(k) : 0;
  const W impulse =
      -wmul(wmul(perp_mass, t.mass_scale), cdot + t.bias) - wmul(t.impulse_scale, j.axial_impulse);
  j.axial_impulse += impulse;
  apply_slider(a, b, f, 0, impulse, 0);
}

}  // namespace rwd::sim2d::detail
