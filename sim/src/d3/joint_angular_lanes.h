// SPDX-License-Identifier: MIT
#pragma once
// The batched angular parts' passes (joint_angular_batches.h), lane by
// lane: joint_angular.cpp's maths written once for kLanes lanes, on the
// bodies a point batch's pass has gathered. Internal linkage, like
// joint_lanes.h; included by joint_point_batches.cpp alone.
#include "d3/joint_angular_batches.h"
#include "d3/joint_lanes.h"
#include "d3/joint_solver.h"
#include "d3/lane_atan2.h"

namespace rwd::sim::d3 {
namespace {

// What a point batch's refresh found for its lanes' points: lever arms,
// inverse masses and inertias, the inertia times [r]x (columns: the
// angular velocity of a unit impulse along each world axis at the anchor),
// and the point's inverse effective mass (xx, xy, xz, yy, yz, zz).
struct PointLanes {
  V3<F> ra, rb;
  F ma, mb;
  LaneInertia<F> ia, ib;
  V3<F> ta[3], tb[3];
  F k[6];
};

inline V3<F> sym_times(const F (&k)[6], const V3<F>& v) {
  return {k[0] * v.x + k[1] * v.y + k[2] * v.z, k[1] * v.x + k[3] * v.y + k[4] * v.z,
          k[2] * v.x + k[4] * v.y + k[5] * v.z};
}

inline V3<F> columns_times(const V3<F> (&t)[3], const V3<F>& v) {
  return t[0] * v.x + t[1] * v.y + t[2] * v.z;
}

inline V3<F> neg3(const V3<F>& v) {
  const F zero = splat(0.0f);
  return {zero - v.x, zero - v.y, zero - v.z};
}

inline F ld(const float (&f)[kLanes]) {
  return load(f);
}

inline MaskW on(const float (&f)[kLanes]) {
  return load(f) > splat(0.0f);
}

inline V3<F> sel3(MaskW m, const V3<F>& a, const V3<F>& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

// q * r of math.h, lane by lane.
inline LaneQuat quat_mul(const LaneQuat& a, const LaneQuat& b) {
  return {
      a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
      a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

inline LaneQuat ld_quat(const float (&f)[4][kLanes]) {
  return {load(f[0]), load(f[1]), load(f[2]), load(f[3])};
}

// The frame's x, y, z axes in the world (rotate(q, e_k), math.h's
// formula with the zeros of e_k left out: the same rounding).
inline V3<F> axis_x(const LaneQuat& q) {
  const F two = splat(2.0f);
  // t = 2 (u x e_x) = (0, 2 z, -2 y); e_x + w t + u x t.
  const F ty = two * q.z;
  const F tz = splat(0.0f) - two * q.y;
  return {splat(1.0f) + (q.y * tz - q.z * ty), q.w * ty + (splat(0.0f) - q.x * tz),
          q.w * tz + q.x * ty};
}
inline V3<F> axis_y(const LaneQuat& q) {
  const F two = splat(2.0f);
  // t = 2 (u x e_y) = (-2 z, 0, 2 x).
  const F tx = splat(0.0f) - two * q.z;
  const F tz = two * q.x;
  return {q.w * tx + q.y * tz, splat(1.0f) + (q.z * tx - q.x * tz),
          q.w * tz + (splat(0.0f) - q.y * tx)};
}
inline V3<F> axis_z(const LaneQuat& q) {
  const F two = splat(2.0f);
  // t = 2 (u x e_z) = (2 y, -2 x, 0).
  const F tx = two * q.y;
  const F ty = splat(0.0f) - two * q.x;
  return {q.w * tx + (splat(0.0f) - q.z * ty), q.w * ty + q.z * tx,
          splat(1.0f) + (q.x * ty - q.y * tx)};
}

// det_atan2 lane by lane (lane_atan2.h), and twist_angle (joint_math.h)
// of conjugate(fa) * fb: bit for bit the one-float functions.
inline F atan2_lanes(F y, F x) {
  return det_atan2_lanes(y, x);
}

inline F twist_lanes(const LaneQuat& fa, const LaneQuat& fb) {
  const F zero = splat(0.0f);
  const LaneQuat rel = quat_mul({zero - fa.x, zero - fa.y, zero - fa.z, fa.w}, fb);
  // (det_atan2 of two zeros is zero: twist_angle's own test for them
  // gives the same.)
  F angle = splat(2.0f) * det_atan2_lanes(rel.x, rel.w);
  angle = select(angle > splat(kPi), angle - splat(2.0f * kPi), angle);
  return select(angle < splat(-kPi), angle + splat(2.0f * kPi), angle);
}

// A unit turn impulse about u against the point (joint_angular.cpp's Turn).
struct LaneTurn {
  V3<F> u, ia, ib, c, y;
};

inline LaneTurn make_turn(const PointLanes& pt, const V3<F>& u, const V3<F>& ia, const V3<F>& ib) {
  LaneTurn t;
  t.u = u;
  t.ia = ia;
  t.ib = ib;
  t.c = cross3(t.ia, pt.ra) + cross3(t.ib, pt.rb);
  t.y = sym_times(pt.k, t.c);
  return t;
}

inline LaneTurn make_turn(const PointLanes& pt, const V3<F>& u) {
  return make_turn(pt, u, mul(pt.ia, u), mul(pt.ib, u));
}

inline F schur(const LaneTurn& t, const LaneTurn& s) {
  return (dot3(t.u, s.ia) + dot3(t.u, s.ib)) - dot3(t.c, s.y);
}

// An extra row the point already holds is left out (kExtraShare,
// joint_angular.cpp).
constexpr float kLaneExtraShare = 1e-5f;

inline MaskW kept_turn(const LaneTurn& t, F s) {
  const F own = dot3(t.u, t.ia) + dot3(t.u, t.ib);
  return (own > splat(0.0f)) & (s > splat(kLaneExtraShare) * own);
}

inline F turn_mass(const LaneTurn& t) {
  const F s = schur(t, t);
  const MaskW keep = kept_turn(t, s);
  return select(keep, splat(1.0f) / select(keep, s, splat(1.0f)), splat(0.0f));
}

// The turn's unit impulse with the anchors' p = -K^-1 C u: A's and B's
// velocities (turn_response, joint_angular.cpp).
inline void turn_response(const PointLanes& pt, const LaneTurn& t, LaneResponse& out) {
  const V3<F> p = neg3(t.y);
  const V3<F> va = neg3(p * pt.ma);
  const V3<F> wa = neg3(t.ia + columns_times(pt.ta, p));
  const V3<F> vb = p * pt.mb;
  const V3<F> wb = t.ib + columns_times(pt.tb, p);
  const V3<F> all[4] = {va, wa, vb, wb};
  for (int q = 0; q < 4; ++q) {
    store(out.r[3 * q], all[q].x);
    store(out.r[3 * q + 1], all[q].y);
    store(out.r[3 * q + 2], all[q].z);
  }
}

// The bodies' velocities moved by a response times delta.
inline void apply_response(const LaneResponse& r, LaneBodies<F>& a, LaneBodies<F>& b, F delta) {
  a.v = a.v + V3<F>{load(r.r[0]), load(r.r[1]), load(r.r[2])} * delta;
  a.w = a.w + V3<F>{load(r.r[3]), load(r.r[4]), load(r.r[5])} * delta;
  b.v = b.v + V3<F>{load(r.r[6]), load(r.r[7]), load(r.r[8])} * delta;
  b.w = b.w + V3<F>{load(r.r[9]), load(r.r[10]), load(r.r[11])} * delta;
}

// The positions moved by a response times delta (the hinge's projection).
inline void sum_response(const LaneResponse& r, F x, V3<F>& va, V3<F>& wa, V3<F>& vb, V3<F>& wb) {
  va = va + V3<F>{load(r.r[0]), load(r.r[1]), load(r.r[2])} * x;
  wa = wa + V3<F>{load(r.r[3]), load(r.r[4]), load(r.r[5])} * x;
  vb = vb + V3<F>{load(r.r[6]), load(r.r[7]), load(r.r[8])} * x;
  wb = wb + V3<F>{load(r.r[9]), load(r.r[10]), load(r.r[11])} * x;
}

inline V3<F> rel_w(const LaneBodies<F>& a, const LaneBodies<F>& b) {
  return b.w - a.w;
}

// limit_terms (joint_solver.h) lane by lane: speculative while open, the
// structure's soft step once crossed (with the bias), rigid without.
struct LaneTerms {
  F bias, mass_scale, impulse_scale;
};
inline LaneTerms limit_terms_lanes(const JointSoftness& soft, F gap, F h, bool use_bias) {
  const MaskW open = gap > splat(0.0f);
  const F one = splat(1.0f);
  const F zero = splat(0.0f);
  const F spec = gap / h;
  if (use_bias) {
    return {select(open, spec, splat(soft.bias_rate) * gap),
            select(open, one, splat(soft.mass_scale)),
            select(open, zero, splat(soft.impulse_scale))};
  }
  return {select(open, spec, zero), one, zero};
}

// One limit row (solve_limits, joint_angular.cpp): `sign` -1 for a row
// that is the negation of the response's turn.
inline void solve_limit_lanes(const JointSoftness& soft, F h, bool use_bias, MaskW active,
                              const V3<F>& row, F gap, F mass, const LaneResponse& r, bool negated,
                              float (&impulse)[kLanes], LaneBodies<F>& a, LaneBodies<F>& b) {
  const F zero = splat(0.0f);
  const F imp = load(impulse);
  const LaneTerms t = limit_terms_lanes(soft, gap, h, use_bias);
  const F rhs = dot3(row, rel_w(a, b)) + t.bias;
  // Open, holding nothing and not closing within the substep: untouched.
  const MaskW idle = (imp == zero) & (rhs >= zero);
  const F lambda = (zero - mass) * rhs * t.mass_scale - imp * t.impulse_scale;
  const F sum = imp + lambda;
  F next = select(sum > zero, sum, zero);
  next = select(idle, imp, next);
  next = select(active, next, imp);
  const F delta = next - imp;
  store(impulse, next);
  apply_response(r, a, b, negated ? zero - delta : delta);
}

// ---- ball joints ----

inline void refresh_ball_lanes(BallPartBatch& p, const PointLanes& pt, const LaneQuat& qa,
                               const LaneQuat& qb) {
  const LaneQuat fa = quat_mul(qa, ld_quat(p.frame_a));
  const LaneQuat fb = quat_mul(qb, ld_quat(p.frame_b));
  const F zero = splat(0.0f);
  const F one = splat(1.0f);
  if (p.any_limit) {
    // cone_twist (joint_ball.cpp).
    const V3<F> xa = axis_x(fa);
    const V3<F> xb = axis_x(fb);
    const V3<F> n = cross3(xa, xb);
    const F s = sqrt(dot3(n, n));
    const MaskW swing = s > splat(1e-6f);
    const F inv_s = one / select(swing, s, one);
    const V3<F> swing_axis = sel3(swing, n * inv_s, V3<F>{zero, zero, zero});
    const F angle = select(swing, atan2_lanes(s, dot3(xa, xb)), zero);
    const V3<F> sum = xa + xb;
    const F len = sqrt(dot3(sum, sum));
    const MaskW twisted = len > splat(1e-12f);
    const F inv_len = one / select(twisted, len, one);
    const V3<F> twist_axis = sel3(twisted, sum * inv_len, V3<F>{zero, zero, zero});
    const F twist = twist_lanes(fa, fb);
    const MaskW limited = on(p.limit_on);
    const F cone_angle = ld(p.cone_angle);
    const MaskW cone = limited & swing & (splat(kPi) > cone_angle);
    const MaskW range = limited & twisted;
    const V3<F> cone_row = neg3(swing_axis);
    st3(p.cone_row, cone_row);
    st3(p.twist_row, twist_axis);
    store(p.slot_on[0], select(cone, one, zero));
    store(p.slot_on[1], select(range, one, zero));
    store(p.slot_on[2], select(range, one, zero));
    store(p.gap[0], cone_angle - angle);
    store(p.gap[1], twist - ld(p.twist_lower));
    store(p.gap[2], ld(p.twist_upper) - twist);
    const LaneTurn tc = make_turn(pt, cone_row);
    const LaneTurn tt = make_turn(pt, twist_axis);
    store(p.cone_mass, turn_mass(tc));
    store(p.twist_mass, turn_mass(tt));
    turn_response(pt, tc, p.cone_response);
    turn_response(pt, tt, p.twist_response);
  }
  if (p.any_motor) {
    // The three turns about the world axes, their Schur complement
    // against the point inverted (inverse_symmetric, joint_math.h).
    const V3<F> e[3] = {{one, zero, zero}, {zero, one, zero}, {zero, zero, one}};
    const V3<F> ca[3] = {pt.ia.c0, pt.ia.c1, pt.ia.c2};
    const V3<F> cb[3] = {pt.ib.c0, pt.ib.c1, pt.ib.c2};
    LaneTurn t[3];
    for (int q = 0; q < 3; ++q) {
      t[q] = make_turn(pt, e[q], ca[q], cb[q]);
      turn_response(pt, t[q], p.motor_response[q]);
    }
    // Column q is (schur(t_0, t_q), schur(t_1, t_q), schur(t_2, t_q)):
    // symmetric but for rounding, inverted whole as the scalar path does.
    V3<F> k[3];
    for (int q = 0; q < 3; ++q) k[q] = {schur(t[0], t[q]), schur(t[1], t[q]), schur(t[2], t[q])};
    // A world axis both bodies are locked about stays zero.
    const MaskW zx = k[0].x == zero;
    const MaskW zy = k[1].y == zero;
    const MaskW zz = k[2].z == zero;
    const MaskW z[3] = {zx, zy, zz};
    const auto zero_where = [&](V3<F> v, MaskW mx, MaskW my, MaskW mz) {
      return V3<F>{select(mx, zero, v.x), select(my, zero, v.y), select(mz, zero, v.z)};
    };
    k[0] = sel3(zx, V3<F>{one, zero, zero}, k[0]);
    k[1] = sel3(zy, V3<F>{zero, one, zero}, k[1]);
    k[2] = sel3(zz, V3<F>{zero, zero, one}, k[2]);
    k[0] = zero_where(k[0], zx, zy | zx, zz | zx);
    k[1] = zero_where(k[1], zx | zy, zy, zz | zy);
    k[2] = zero_where(k[2], zx | zz, zy | zz, zz);
    const V3<F> r0 = cross3(k[1], k[2]);
    const F det = dot3(k[0], r0);
    const MaskW regular = (det > splat(1e-30f)) | (det < splat(-1e-30f));
    const F inv = select(regular, one / select(regular, det, one), zero);
    V3<F> m[3] = {r0 * inv, cross3(k[2], k[0]) * inv, cross3(k[0], k[1]) * inv};
    for (int q = 0; q < 3; ++q) {
      // Column q and row q of a locked axis are zero.
      m[q] = sel3(z[q], V3<F>{zero, zero, zero}, m[q]);
      m[q] = zero_where(m[q], zx, zy, zz);
      store(p.motor_inv[3 * q], m[q].x);
      store(p.motor_inv[3 * q + 1], m[q].y);
      store(p.motor_inv[3 * q + 2], m[q].z);
    }
  }
}

inline void apply_motor_lanes(const BallPartBatch& p, LaneBodies<F>& a, LaneBodies<F>& b,
                              const V3<F>& d) {
  apply_response(p.motor_response[0], a, b, d.x);
  apply_response(p.motor_response[1], a, b, d.y);
  apply_response(p.motor_response[2], a, b, d.z);
}

inline void warm_start_ball_lanes(const BallPartBatch& p, LaneBodies<F>& a, LaneBodies<F>& b) {
  const F zero = splat(0.0f);
  // (Without a motor a lane's motor impulse is zero: has_angular_part.)
  if (p.any_motor) apply_motor_lanes(p, a, b, ld3(p.motor_impulse));
  if (!p.any_limit) return;
  const F cone = select(on(p.slot_on[0]), load(p.limit_impulse[0]), zero);
  const F lower = select(on(p.slot_on[1]), load(p.limit_impulse[1]), zero);
  const F upper = select(on(p.slot_on[2]), load(p.limit_impulse[2]), zero);
  apply_response(p.cone_response, a, b, cone);
  apply_response(p.twist_response, a, b, lower - upper);
}

inline void solve_ball_lanes(BallPartBatch& p, const JointSoftness& soft, F h, bool use_bias,
                             bool at_refresh, MaskW changes, LaneBodies<F>& a, LaneBodies<F>& b) {
  if (p.any_motor) {
    const V3<F> cdot = rel_w(a, b) - ld3(p.motor_velocity);
    const V3<F> old = ld3(p.motor_impulse);
    const V3<F> m0{load(p.motor_inv[0]), load(p.motor_inv[1]), load(p.motor_inv[2])};
    const V3<F> m1{load(p.motor_inv[3]), load(p.motor_inv[4]), load(p.motor_inv[5])};
    const V3<F> m2{load(p.motor_inv[6]), load(p.motor_inv[7]), load(p.motor_inv[8])};
    V3<F> next = old - (m0 * cdot.x + m1 * cdot.y + m2 * cdot.z);
    const F max = ld(p.max_motor);
    const F len_sq = dot3(next, next);
    const MaskW over = len_sq > max * max;
    const F scale = max / sqrt(select(over, len_sq, splat(1.0f)));
    next = sel3(over, next * scale, next);
    next = sel3(on(p.motor_on) & changes, next, old);
    st3(p.motor_impulse, next);
    apply_motor_lanes(p, a, b, next - old);
  }
  if (!p.any_limit) return;
  const V3<F> cone_row = ld3(p.cone_row);
  const V3<F> twist_row = ld3(p.twist_row);
  F gap[3] = {load(p.gap[0]), load(p.gap[1]), load(p.gap[2])};
  if (!at_refresh) {
    // Each gap moved by the rows' velocity over the substep.
    const V3<F> w = rel_w(a, b);
    const F tw = dot3(twist_row, w);
    gap[0] = gap[0] + h * dot3(cone_row, w);
    gap[1] = gap[1] + h * tw;
    gap[2] = gap[2] + h * (splat(0.0f) - tw);
  }
  const F twist_mass = ld(p.twist_mass);
  solve_limit_lanes(soft, h, use_bias, on(p.slot_on[0]) & changes, cone_row, gap[0],
                    ld(p.cone_mass), p.cone_response, false, p.limit_impulse[0], a, b);
  solve_limit_lanes(soft, h, use_bias, on(p.slot_on[1]) & changes, twist_row, gap[1], twist_mass,
                    p.twist_response, false, p.limit_impulse[1], a, b);
  solve_limit_lanes(soft, h, use_bias, on(p.slot_on[2]) & changes, neg3(twist_row), gap[2],
                    twist_mass, p.twist_response, true, p.limit_impulse[2], a, b);
}

// ---- hinges ----

inline void refresh_hinge_lanes(HingePartBatch& p, const PointLanes& pt, const LaneQuat& qa,
                                const LaneQuat& qb) {
  const LaneQuat fa = quat_mul(qa, ld_quat(p.frame_a));
  const LaneQuat fb = quat_mul(qb, ld_quat(p.frame_b));
  const V3<F> xa = axis_x(fa);
  st3(p.axis, xa);
  store(p.angle, twist_lanes(fa, fb));
  const V3<F> ax[2] = {axis_y(fa), axis_z(fa)};
  const V3<F> tilt = cross3(xa, axis_x(fb));
  const LaneTurn t0 = make_turn(pt, ax[0]);
  const LaneTurn t1 = make_turn(pt, ax[1]);
  const LaneTurn tx = make_turn(pt, xa);
  const V3<F> impulse = ld3(p.angular_impulse);
  for (int k = 0; k < 2; ++k) {
    store(p.align_axis[k][0], ax[k].x);
    store(p.align_axis[k][1], ax[k].y);
    store(p.align_axis[k][2], ax[k].z);
    store(p.align_error[k], dot3(tilt, ax[k]));
    store(p.align_impulse[k], dot3(impulse, ax[k]));
  }
  turn_response(pt, t0, p.align_response[0]);
  turn_response(pt, t1, p.align_response[1]);
  // The 2 x 2 inverted, leaving out a turn the point holds.
  const F zero = splat(0.0f);
  const F one = splat(1.0f);
  F s00 = schur(t0, t0);
  F s11 = schur(t1, t1);
  F s01 = schur(t0, t1);
  const MaskW keep0 = kept_turn(t0, s00);
  const MaskW keep1 = kept_turn(t1, s11);
  s00 = select(keep0, s00, one);
  s11 = select(keep1, s11, one);
  s01 = select(keep0 & keep1, s01, zero);
  const F det = s00 * s11 - s01 * s01;
  const MaskW positive = det > zero;
  const F inv_det = select(positive, one / select(positive, det, one), zero);
  store(p.align_inv[0], select(keep0, s11 * inv_det, zero));
  store(p.align_inv[1], select(keep0 & keep1, (zero - s01) * inv_det, zero));
  store(p.align_inv[2], select(keep1, s00 * inv_det, zero));
  store(p.axial_mass, turn_mass(tx));
  turn_response(pt, tx, p.axial_response);
}

inline void warm_start_hinge_lanes(const HingePartBatch& p, LaneBodies<F>& a, LaneBodies<F>& b) {
  const F zero = splat(0.0f);
  const MaskW limited = on(p.limit_on);
  const F lower = select(limited, load(p.limit_impulse[0]), zero);
  const F upper = select(limited, load(p.limit_impulse[1]), zero);
  apply_response(p.axial_response, a, b, ld(p.motor_impulse) + ld(p.spring_impulse));
  apply_response(p.align_response[0], a, b, load(p.align_impulse[0]));
  apply_response(p.align_response[1], a, b, load(p.align_impulse[1]));
  apply_response(p.axial_response, a, b, lower - upper);
}

inline F wrap_lanes(F angle) {
  const F pi = splat(kPi);
  const F two_pi = splat(2.0f * kPi);
  return select(angle > pi, angle - two_pi, select(angle < splat(-kPi), angle + two_pi, angle));
}

inline void solve_hinge_lanes(HingePartBatch& p, const JointSoftness& soft, F h, bool use_bias,
                              bool at_refresh, MaskW changes, LaneBodies<F>& a, LaneBodies<F>& b) {
  const F zero = splat(0.0f);
  const V3<F> axis = ld3(p.axis);
  const F mass = ld(p.axial_mass);
  const F angle0 = ld(p.angle);
  const F angle = at_refresh ? angle0 : angle0 + h * dot3(axis, rel_w(a, b));
  {
    // The spring (soft in every pass).
    const F error = wrap_lanes(angle - ld(p.spring_target));
    const F rhs = dot3(axis, rel_w(a, b)) + load(p.spring_soft[0]) * error;
    const F old = ld(p.spring_impulse);
    const F lambda = (zero - mass) * rhs * load(p.spring_soft[1]) - old * load(p.spring_soft[2]);
    const MaskW act = on(p.spring_on) & changes;
    store(p.spring_impulse, select(act, old + lambda, old));
    apply_response(p.axial_response, a, b, select(act, lambda, zero));
  }
  {
    // The motor, its impulse held within its torque times the substep.
    const F rhs = dot3(axis, rel_w(a, b)) - ld(p.motor_speed);
    const F max = ld(p.max_motor);
    const F old = ld(p.motor_impulse);
    F next = old - mass * rhs;
    next = select(next > max, max, select(next < zero - max, zero - max, next));
    next = select(on(p.motor_on) & changes, next, old);
    store(p.motor_impulse, next);
    apply_response(p.axial_response, a, b, next - old);
  }
  {
    // The limits about the axis (their gaps moved by the axis's velocity
    // over the substep after the move).
    const MaskW limited = on(p.limit_on) & changes;
    F gap_lower = angle0 - ld(p.lower);
    F gap_upper = ld(p.upper) - angle0;
    if (!at_refresh) {
      const F moved = h * dot3(axis, rel_w(a, b));
      gap_lower = gap_lower + moved;
      gap_upper = gap_upper + (zero - moved);
    }
    solve_limit_lanes(soft, h, use_bias, limited, axis, gap_lower, mass, p.axial_response, false,
                      p.limit_impulse[0], a, b);
    solve_limit_lanes(soft, h, use_bias, limited, neg3(axis), gap_upper, mass, p.axial_response,
                      true, p.limit_impulse[1], a, b);
  }
  // The two turns off the axis together: soft toward the refresh's
  // misalignment with the bias, rigid without.
  const V3<F> w = rel_w(a, b);
  F rhs[2];
  for (int k = 0; k < 2; ++k) {
    const V3<F> ax = ld3(p.align_axis[k]);
    rhs[k] = dot3(ax, w);
    if (use_bias) rhs[k] = rhs[k] + splat(soft.bias_rate) * load(p.align_error[k]);
  }
  const F i0 = load(p.align_inv[0]);
  const F i1 = load(p.align_inv[1]);
  const F i2 = load(p.align_inv[2]);
  const F x0 = i0 * rhs[0] + i1 * rhs[1];
  const F x1 = i1 * rhs[0] + i2 * rhs[1];
  const F mass_scale = splat(use_bias ? soft.mass_scale : 1.0f);
  const F impulse_scale = splat(use_bias ? soft.impulse_scale : 0.0f);
  const F old0 = load(p.align_impulse[0]);
  const F old1 = load(p.align_impulse[1]);
  const F l0 = (zero - x0) * mass_scale - old0 * impulse_scale;
  const F l1 = (zero - x1) * mass_scale - old1 * impulse_scale;
  store(p.align_impulse[0], select(changes, old0 + l0, old0));
  store(p.align_impulse[1], select(changes, old1 + l1, old1));
  apply_response(p.align_response[0], a, b, l0);
  apply_response(p.align_response[1], a, b, l1);
}

inline F clamp_lanes(F v) {
  const F limit = splat(kMaxProjection);
  const F neg_limit = splat(-kMaxProjection);
  return select(v > limit, limit, select(v < neg_limit, neg_limit, v));
}

// The hinge's axes brought back into line, and a crossed limit back
// within its range (project_angular_parts), on the lanes' positions.
inline void project_hinge_lanes(const HingePartBatch& p, MaskW movable_a, MaskW movable_b,
                                LanePositions& pa, LanePositions& pb) {
  const F zero = splat(0.0f);
  const LaneQuat fa = quat_mul(pa.q, ld_quat(p.frame_a));
  const LaneQuat fb = quat_mul(pb.q, ld_quat(p.frame_b));
  const V3<F> tilt = cross3(axis_x(fa), axis_x(fb));
  const F e0 = clamp_lanes(dot3(tilt, ld3(p.align_axis[0])));
  const F e1 = clamp_lanes(dot3(tilt, ld3(p.align_axis[1])));
  const F i0 = load(p.align_inv[0]);
  const F i1 = load(p.align_inv[1]);
  const F i2 = load(p.align_inv[2]);
  const F x0 = zero - (i0 * e0 + i1 * e1);
  const F x1 = zero - (i1 * e0 + i2 * e1);
  F x2 = zero;
  const MaskW limited = on(p.limit_on);
  if (lane_bits(limited) != 0) {
    const F angle = twist_lanes(fa, fb);
    const F mass = ld(p.axial_mass);
    const F lower = ld(p.lower);
    const F upper = ld(p.upper);
    x2 = select(angle < lower, (zero - mass) * clamp_lanes(angle - lower), x2);
    x2 = select(angle > upper, (zero - mass) * clamp_lanes(angle - upper), x2);
    x2 = select(limited, x2, zero);
  }
  V3<F> va{zero, zero, zero};
  V3<F> wa = va;
  V3<F> vb = va;
  V3<F> wb = va;
  sum_response(p.align_response[0], x0, va, wa, vb, wb);
  sum_response(p.align_response[1], x1, va, wa, vb, wb);
  sum_response(p.axial_response, x2, va, wa, vb, wb);
  // A body that cannot move stays where it is (and is never written back).
  const LaneQuat qa = integrate_lanes(pa.q, wa);
  const LaneQuat qb = integrate_lanes(pb.q, wb);
  pa.p = sel3(movable_a, pa.p + va, pa.p);
  pb.p = sel3(movable_b, pb.p + vb, pb.p);
  pa.q = {select(movable_a, qa.x, pa.q.x), select(movable_a, qa.y, pa.q.y),
          select(movable_a, qa.z, pa.q.z), select(movable_a, qa.w, pa.q.w)};
  pb.q = {select(movable_b, qb.x, pb.q.x), select(movable_b, qb.y, pb.q.y),
          select(movable_b, qb.z, pb.q.z), select(movable_b, qb.w, pb.q.w)};
}

}  // namespace
}  // namespace rwd::sim::d3
