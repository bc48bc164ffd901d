// SPDX-License-Identifier: MIT
#pragma once
// Small pieces every joint type shares.
#include "joint_solver2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// The anchors now: the step's frames turned by each body's rotation so far.
struct Anchors2D {
  V2 ra;
  V2 rb;
};
inline Anchors2D current_anchors(const JointConstraint2D& c, const SolverBody2D& a,
                                 const SolverBody2D& b) {
  return {rotate(a.dq, c.frame_a), rotate(b.dq, c.frame_b)};
}

/// B's anchor minus A's, now.
inline V2 anchor_separation(const JointConstraint2D& c, const SolverBody2D& a,
                            const SolverBody2D& b, const Anchors2D& r) {
  return (b.dp - a.dp) + c.delta_center + (r.rb - r.ra);
}

/// Velocity of B's anchor relative to A's.
inline V2 anchor_velocity(const SolverBody2D& a, const SolverBody2D& b, const Anchors2D& r) {
  return (b.v + vcross_sv(b.w, r.rb)) - (a.v + vcross_sv(a.w, r.ra));
}

/// Applies `impulse` at the anchors: -impulse to A, +impulse to B.
inline void apply_linear(SolverBody2D& a, SolverBody2D& b, const Anchors2D& r, V2 impulse) {
  a.v = vmul_sub(a.v, a.inv_mass, impulse);
  a.w -= wmul(a.inv_inertia, vcross(r.ra, impulse));
  b.v = vmul_add(b.v, b.inv_mass, impulse);
  b.w += wmul(b.inv_inertia, vcross(r.rb, impulse));
}

inline void apply_angular(SolverBody2D& a, SolverBody2D& b, W impulse) {
  a.w -= wmul(a.inv_inertia, impulse);
  b.w += wmul(b.inv_inertia, impulse);
}

/// The angle of a rotation, radians in [-pi, pi], to 2^-29 (the fixed
/// library's CORDIC at its working precision).
W angle_of(Rot q);

/// B's angle minus A's now, minus the reference: the step's start value
/// plus what the bodies turned since.
inline W joint_angle(const JointConstraint2D& c, const SolverBody2D& a, const SolverBody2D& b) {
  return c.delta_angle + angle_of(rinv_mul(a.dq, b.dq));
}

/// x with K x = v for the symmetric 2x2 K = [k11 k12; k12 k22]; zero when
/// K is singular.
V2 solve22(W k11, W k12, W k22, V2 v);

/// The point constraint's effective-mass matrix terms for anchors ra, rb.
struct PointMass2D {
  W k11 = 0;
  W k12 = 0;
  W k22 = 0;
};
PointMass2D point_mass(const SolverBody2D& a, const SolverBody2D& b, const Anchors2D& r);

/// The soft or speculative terms of a one-sided constraint with position
/// error `c` (>= 0 satisfied).
struct BiasTerms2D {
  W bias = 0;
  W mass_scale = kWOne;
  W impulse_scale = 0;
};
inline BiasTerms2D one_sided_bias(W c, const Softness2D& soft, const JointPass2D& pass) {
  if (c > 0) return {wmul(c, pass.inv_h), kWOne, 0};  // speculative
  if (pass.use_bias) return {wmul(soft.bias_rate, c), soft.mass_scale, soft.impulse_scale};
  return {};
}

/// One-sided row along an angle: lower limit when `sign` is +1 (B turns
/// past A), upper when -1. Returns the impulse applied.
W solve_angle_limit(W c, W sign, W& accumulated, W axial_mass, const Softness2D& soft,
                    SolverBody2D& a, SolverBody2D& b, const JointPass2D& pass);

}  // namespace rwd::sim2d::detail
