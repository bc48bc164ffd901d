// SPDX-License-Identifier: MIT
#include "contact_solver2d.h"

#include "body_mass2d.h"
#include "body_math2d.h"

namespace rwd::sim2d::detail {

Softness2D make_softness(W hertz, W zeta, W h) {
  if (hertz == 0) return {0, kWOne, 0};
  const W omega = wmul(2 * kWPi, hertz);
  const W a1 = 2 * zeta + wmul(h, omega);
  const W a2 = wmul(wmul(h, omega), a1);
  const W a3 = winv(kWOne + a2);
  return {wdiv(omega, a1), wmul(a2, a3), a3};
}

namespace {

W inverse_or_zero(W k) {
  return k > 0 ? winv(k) : 0;
}

/// a0 b0 + a1 b1 + a2 b2 + a3 b3, rounded once.
W wdot4(W a0, W b0, W a1, W b1, W a2, W b2, W a3, W b3) {
  const I128 sum = static_cast<I128>(a0) * b0 + static_cast<I128>(a1) * b1 +
                   static_cast<I128>(a2) * b2 + static_cast<I128>(a3) * b3;
  return static_cast<W>((sum + kWHalf) >> kWFrac);
}

/// a0 b0 + a1 b1 + a2 b2, rounded once.
W wdot3(W a0, W b0, W a1, W b1, W a2, W b2) {
  const I128 sum =
      static_cast<I128>(a0) * b0 + static_cast<I128>(a1) * b1 + static_cast<I128>(a2) * b2;
  return static_cast<W>((sum + kWHalf) >> kWFrac);
}

// Velocity of B's anchor relative to A's.
V2 relative_velocity(const SolverBody2D& a, V2 ra, const SolverBody2D& b, V2 rb) {
  return (b.v + vcross_sv(b.w, rb)) - (a.v + vcross_sv(a.w, ra));
}

/// The tangent t = n turned a quarter clockwise, and so A's and B's
/// velocity per unit of tangent impulse.
V2 tangent_of(V2 v) {
  return vperp_cw(v);
}

/// B's anchor's speed relative to A's along the normal.
W normal_speed(const ContactConstraint2D& c, const ContactConstraintPoint2D& cp,
               const SolverBody2D& a, const SolverBody2D& b) {
  return wdot4(b.v.x - a.v.x, c.normal.x, b.v.y - a.v.y, c.normal.y, b.w, cp.rn_b, -a.w, cp.rn_a);
}

/// B's anchor's speed relative to A's along the tangent.
W tangent_speed(const ContactConstraint2D& c, const ContactConstraintPoint2D& cp,
                const SolverBody2D& a, const SolverBody2D& b) {
  const V2 t = tangent_of(c.normal);
  return wdot4(b.v.x - a.v.x, t.x, b.v.y - a.v.y, t.y, b.w, cp.rt_b, -a.w, cp.rt_a);
}

void push_normal(const ContactConstraint2D& c, const ContactConstraintPoint2D& cp, SolverBody2D& a,
                 SolverBody2D& b, W impulse) {
  a.v -= vscale(impulse, c.move_a);
  a.w -= wmul(impulse, cp.spin_n_a);
  b.v += vscale(impulse, c.move_b);
  b.w += wmul(impulse, cp.spin_n_b);
}

void push_tangent(const ContactConstraint2D& c, const ContactConstraintPoint2D& cp, SolverBody2D& a,
                  SolverBody2D& b, W impulse) {
  a.v -= vscale(impulse, tangent_of(c.move_a));
  a.w -= wmul(impulse, cp.spin_t_a);
  b.v += vscale(impulse, tangent_of(c.move_b));
  b.w += wmul(impulse, cp.spin_t_b);
}

// One contact's constraint, appended to scratch.constraints.
void prepare_contact(const World2DState& state, StepScratch2D& scratch, uint32_t ci,
                     const Softness2D& soft, const Softness2D& static_soft) {
  const ContactRecord2D& contact = state.contacts[ci];
  if (contact.flags & kContactSensor) return;
  if (!is_moving(state.bodies[contact.a]) && !is_moving(state.bodies[contact.b])) return;
  const BodyRecord2D& body_a = state.bodies[contact.a];
  const BodyRecord2D& body_b = state.bodies[contact.b];
  const SolverBody2D& a = scratch.bodies[contact.a];
  const SolverBody2D& b = scratch.bodies[contact.b];
  ContactConstraint2D& c = scratch.constraints.emplace_back();
  c.a = contact.a;
  c.b = contact.b;
  c.contact = ci;
  c.normal = contact.normal;
  c.move_a = vscale(a.inv_mass, contact.normal);
  c.move_b = vscale(b.inv_mass, contact.normal);
  // sqrt(f f) is f: most pairs share a material, and the root is the
  // costliest operation of the preparation.
  const Fx fa = body_a.material.friction;
  const Fx fb = body_b.material.friction;
  c.friction = fa == fb ? w_from(fa) : wsqrt(wmul(w_from(fa), w_from(fb)));
  c.restitution = wmax(w_from(body_a.material.restitution), w_from(body_b.material.restitution));
  c.rolling_resistance =
      wmax(w_from(body_a.material.rolling_resistance), w_from(body_b.material.rolling_resistance));
  c.rolling_mass = inverse_or_zero(a.inv_inertia + b.inv_inertia);
  c.rolling_impulse = contact.rolling_impulse;
  c.softness = (a.inv_mass == 0 || b.inv_mass == 0) ? static_soft : soft;
  c.count = contact.count;
  const V2 n = contact.normal;
  const V2 t = tangent_of(n);
  const W m = a.inv_mass + b.inv_mass;
  for (int i = 0; i < contact.count; ++i) {
    const ContactPoint2D& p = contact.points[i];
    ContactConstraintPoint2D& cp = c.points[i];
    const V2 ra = p.anchor_a;
    const V2 rb = p.anchor_b;
    cp.rn_a = vcross(ra, n);
    cp.rn_b = vcross(rb, n);
    cp.rt_a = vcross(ra, t);
    cp.rt_b = vcross(rb, t);
    cp.rd_a = vdot(ra, n);
    cp.rd_b = vdot(rb, n);
    cp.spin_n_a = wmul(a.inv_inertia, cp.rn_a);
    cp.spin_n_b = wmul(b.inv_inertia, cp.rn_b);
    cp.spin_t_a = wmul(a.inv_inertia, cp.rt_a);
    cp.spin_t_b = wmul(b.inv_inertia, cp.rt_b);
    cp.adjusted_separation = p.separation - (cp.rd_b - cp.rd_a);
    cp.normal_impulse = p.normal_impulse;
    cp.tangent_impulse = p.tangent_impulse;
    // The normal row's effective mass; for two points, K's diagonal.
    const W k = m + wmul(a.inv_inertia, wmul(cp.rn_a, cp.rn_a)) +
                wmul(b.inv_inertia, wmul(cp.rn_b, cp.rn_b));
    if (i == 0) c.k11 = k;
    if (i == 1) c.k22 = k;
    cp.normal_mass = inverse_or_zero(k);
    cp.tangent_mass = inverse_or_zero(m + wmul(a.inv_inertia, wmul(cp.rt_a, cp.rt_a)) +
                                      wmul(b.inv_inertia, wmul(cp.rt_b, cp.rt_b)));
    cp.relative_velocity = vdot(n, relative_velocity(a, ra, b, rb));
  }
  if (c.count == 2) {
    const ContactConstraintPoint2D& p1 = c.points[0];
    const ContactConstraintPoint2D& p2 = c.points[1];
    c.k12 = m + wmul(a.inv_inertia, wmul(p1.rn_a, p2.rn_a)) +
            wmul(b.inv_inertia, wmul(p1.rn_b, p2.rn_b));
    // Two points nearly on top of each other make K nearly singular: the
    // block is used only while k11^2 < 1000 det (one after the other
    // otherwise), as the sequential rows are then just as good.
    const W det = wmul(c.k11, c.k22) - wmul(c.k12, c.k12);
    c.block = det > 0 && wmul(c.k11, c.k11) < 1000 * det;
    if (c.block) {
      c.inv_k11 = wdiv(c.k22, det);
      c.inv_k12 = wdiv(-c.k12, det);
      c.inv_k22 = wdiv(c.k11, det);
    }
  }
  if (c.rolling_resistance > 0 && c.count > 0) {
    // The resisting torque is the coefficient times the normal force times
    // the lever from the centre of mass to the contact.
    // The lever of the bodies that turn: a static ground's "arm" from its
    // own origin means nothing.
    const ContactPoint2D& p = contact.points[0];
    const W lever = wmax(a.inv_inertia > 0 ? vlength(p.anchor_a) : 0,
                         b.inv_inertia > 0 ? vlength(p.anchor_b) : 0);
    c.rolling_resistance = wmul(c.rolling_resistance, lever);
  }
}

}  // namespace

void prepare_contacts(const World2DState& state, StepScratch2D& scratch, W h) {
  const World2DConfig& config = state.config;
  const W substep_hz = winv(h);
  const W hertz = wmin(w_from(config.contact_hertz), substep_hz / 4);
  const W zeta = w_from(config.contact_damping_ratio);
  const Softness2D soft = make_softness(hertz, zeta, h);
  const Softness2D static_soft = make_softness(2 * hertz, zeta, h);

  // The order built here is the order every pass solves in. Contacts are
  // kept by pair (a, b), so one Gauss-Seidel sweep in pair order corrects
  // each body from its lowest-numbered neighbour to its highest. Bodies are
  // numbered as they are made, and a structure is usually made in space
  // order, so every frame of a card house is corrected from the same side
  // first; with one solve and one relax pass a substep, what that one-sided
  // sweep leaves in the velocities at an impact (a frame landing on its
  // feet, a flat card on two apexes) is the same in every frame and racks
  // the house over. The sweep is split in two interleaved halves instead,
  // pairs of two even or two odd bodies first, then the mixed ones, each in
  // pair order. Box2D's card house (5 frames at the base, 2 mm cards) at
  // default settings, over 99 variants of card thickness and lean: stands
  // in 98 (was 1), with 6 frames 86 (was 0), mirrored 95 and 99 (was 40
  // and 1), built top row first 67 and 34 (was 0 and 0); Box2D v3 itself
  // stands in 90 and 72. The suite's domino row (the ground, then the
  // dominoes in a row) keeps every body's order, so it falls as before.
  // Rejected: the mixed pairs first (78 and 24); a hashed order (the last
  // domino tips 3 to 4 s later and the row is not at rest in 15 s); greedy
  // graph colouring in pair order (keeps the sweep: 4 and 0) or from the
  // last pair (the dominoes again); a second relax pass (half as much
  // solving again, and built top row first still 68 and 41).
  auto& constraints = scratch.constraints;
  constraints.clear();
  for (const uint32_t parity : {0u, 1u}) {
    for (uint32_t ci = 0; ci < state.contacts.size(); ++ci) {
      const ContactRecord2D& contact = state.contacts[ci];
      if (((contact.a ^ contact.b) & 1u) != parity) continue;
      prepare_contact(state, scratch, ci, soft, static_soft);
    }
  }
}

void warm_start_contacts(StepScratch2D& scratch) {
  for (ContactConstraint2D& c : scratch.constraints) {
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    const V2 ta = tangent_of(c.move_a);
    const V2 tb = tangent_of(c.move_b);
    for (int i = 0; i < c.count; ++i) {
      const ContactConstraintPoint2D& cp = c.points[i];
      const W pn = cp.normal_impulse;
      const W pt = cp.tangent_impulse;
      a.v.x -= wmul_add(pn, c.move_a.x, pt, ta.x);
      a.v.y -= wmul_add(pn, c.move_a.y, pt, ta.y);
      a.w -= wmul_add(pn, cp.spin_n_a, pt, cp.spin_t_a);
      b.v.x += wmul_add(pn, c.move_b.x, pt, tb.x);
      b.v.y += wmul_add(pn, c.move_b.y, pt, tb.y);
      b.w += wmul_add(pn, cp.spin_n_b, pt, cp.spin_t_b);
    }
    a.w -= wmul(a.inv_inertia, c.rolling_impulse);
    b.w += wmul(b.inv_inertia, c.rolling_impulse);
  }
}

namespace {

// The soft or speculative terms of one point's normal row this pass.
struct NormalTerms2D {
  W bias = 0;
  W mass_scale = kWOne;
  W impulse_scale = 0;
  bool soft = false;  ///< the soft push-out applies (overlapping, biased pass)
};

NormalTerms2D normal_terms(const ContactConstraint2D& c, const ContactConstraintPoint2D& cp, V2 dp,
                           const SolverBody2D& a, const SolverBody2D& b, W inv_h, W push_max,
                           bool use_bias) {
  // The separation now, from how far each body moved (dp: B's move less
  // A's) and turned since the step began (the manifold is not recomputed
  // between substeps).
  const I128 moved = static_cast<I128>(dp.x) * c.normal.x + static_cast<I128>(dp.y) * c.normal.y +
                     static_cast<I128>(b.dq.c) * cp.rd_b + static_cast<I128>(b.dq.s) * cp.rn_b -
                     static_cast<I128>(a.dq.c) * cp.rd_a - static_cast<I128>(a.dq.s) * cp.rn_a;
  const W s = static_cast<W>((moved + kWHalf) >> kWFrac) + cp.adjusted_separation;
  if (s > 0) return {wmul(s, inv_h), kWOne, 0, false};  // speculative: arrive touching
  if (use_bias) {
    return {wmax(wmul(c.softness.bias_rate, s), -push_max), c.softness.mass_scale,
            c.softness.impulse_scale, true};
  }
  return {};
}

// Both points of a manifold at once (the 2x2 linear complementarity
// problem, by enumerating which points push), so neither undoes the other
// through the rotation they share: a box lands flat without a first
// sideways twitch, and a push-out leaves no velocity behind. The soft
// terms enter as K / mass_scale and a relaxed accumulated impulse, exactly
// as the one-point rows use them; both sides are multiplied by the mass
// scale, so each case is products with K, its inverse or the rows'
// masses, and no division. Returns false, changing nothing, when no case
// fits (then the points are solved one after the other).
bool solve_normal_block(ContactConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                        const NormalTerms2D& t1, const NormalTerms2D& t2) {
  ContactConstraintPoint2D& p1 = c.points[0];
  ContactConstraintPoint2D& p2 = c.points[1];
  const W ms = t1.mass_scale;
  // The relaxed accumulated impulses, and the rows' residuals times the
  // mass scale: q = ms (v + bias) - K a.
  // Outside the soft push-out the impulse scale is zero (both rows agree).
  const W a1 =
      t1.soft ? p1.normal_impulse - wmul(t1.impulse_scale, p1.normal_impulse) : p1.normal_impulse;
  const W a2 =
      t2.soft ? p2.normal_impulse - wmul(t2.impulse_scale, p2.normal_impulse) : p2.normal_impulse;
  const W r1 = normal_speed(c, p1, a, b) + t1.bias;
  const W r2 = normal_speed(c, p2, a, b) + t2.bias;
  const W q1 = wdot3(ms, r1, -c.k11, a1, -c.k12, a2);
  const W q2 = wdot3(ms, r2, -c.k12, a1, -c.k22, a2);
  // Both push: x = -K^-1 q.
  W x1 = -wmul_add(c.inv_k11, q1, c.inv_k12, q2);
  W x2 = -wmul_add(c.inv_k12, q1, c.inv_k22, q2);
  bool found = x1 >= 0 && x2 >= 0;
  if (!found && p1.normal_mass > 0) {  // only the first
    x1 = -wmul(q1, p1.normal_mass);
    x2 = 0;
    found = x1 >= 0 && wmul(c.k12, x1) + q2 >= 0;
  }
  if (!found && p2.normal_mass > 0) {  // only the second
    x1 = 0;
    x2 = -wmul(q2, p2.normal_mass);
    found = x2 >= 0 && wmul(c.k12, x2) + q1 >= 0;
  }
  if (!found) {  // neither
    x1 = 0;
    x2 = 0;
    found = q1 >= 0 && q2 >= 0;
  }
  if (!found) return false;
  const W d1 = x1 - p1.normal_impulse;
  const W d2 = x2 - p2.normal_impulse;
  p1.normal_impulse = x1;
  p2.normal_impulse = x2;
  p1.max_normal_impulse = wmax(p1.max_normal_impulse, d1);
  p2.max_normal_impulse = wmax(p2.max_normal_impulse, d2);
  // Both pushes at once: one rounding per velocity component.
  a.v.x -= wmul(d1 + d2, c.move_a.x);
  a.v.y -= wmul(d1 + d2, c.move_a.y);
  a.w -= wmul_add(d1, p1.spin_n_a, d2, p2.spin_n_a);
  b.v.x += wmul(d1 + d2, c.move_b.x);
  b.v.y += wmul(d1 + d2, c.move_b.y);
  b.w += wmul_add(d1, p1.spin_n_b, d2, p2.spin_n_b);
  return true;
}

}  // namespace

void solve_contacts(StepScratch2D& scratch, W inv_h, W push_max, bool use_bias) {
  for (ContactConstraint2D& c : scratch.constraints) {
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    const V2 dp = b.dp - a.dp;
    NormalTerms2D terms[2];
    for (int i = 0; i < c.count; ++i) {
      terms[i] = normal_terms(c, c.points[i], dp, a, b, inv_h, push_max, use_bias);
    }
    // The block needs one mass scale for both rows: both soft or both not.
    const bool block = c.count == 2 && c.block && terms[0].soft == terms[1].soft &&
                       solve_normal_block(c, a, b, terms[0], terms[1]);
    if (!block) {
      for (int i = 0; i < c.count; ++i) {
        ContactConstraintPoint2D& cp = c.points[i];
        const NormalTerms2D& t = terms[i];
        const W vn = normal_speed(c, cp, a, b);
        // Outside the soft push-out the mass scale is one and the impulse
        // scale zero (normal_terms), whose products are exact: skipped.
        const W impulse = t.soft ? -wmul(wmul(cp.normal_mass, t.mass_scale), vn + t.bias) -
                                       wmul(t.impulse_scale, cp.normal_impulse)
                                 : -wmul(cp.normal_mass, vn + t.bias);
        const W accumulated = wmax(cp.normal_impulse + impulse, 0);
        const W applied = accumulated - cp.normal_impulse;
        cp.normal_impulse = accumulated;
        cp.max_normal_impulse = wmax(cp.max_normal_impulse, applied);
        push_normal(c, cp, a, b, applied);
      }
    }
    W total_normal_impulse = 0;
    for (int i = 0; i < c.count; ++i) total_normal_impulse += c.points[i].normal_impulse;

    for (int i = 0; i < c.count; ++i) {
      ContactConstraintPoint2D& cp = c.points[i];
      const W vt = tangent_speed(c, cp, a, b);
      const W max_friction = wmul(c.friction, cp.normal_impulse);
      const W accumulated =
          wclamp(cp.tangent_impulse - wmul(cp.tangent_mass, vt), -max_friction, max_friction);
      const W applied = accumulated - cp.tangent_impulse;
      cp.tangent_impulse = accumulated;
      push_tangent(c, cp, a, b, applied);
    }

    if (c.rolling_resistance > 0) {
      const W max_lambda = wmul(c.rolling_resistance, total_normal_impulse);
      const W accumulated =
          wclamp(c.rolling_impulse - wmul(c.rolling_mass, b.w - a.w), -max_lambda, max_lambda);
      const W applied = accumulated - c.rolling_impulse;
      c.rolling_impulse = accumulated;
      a.w -= wmul(a.inv_inertia, applied);
      b.w += wmul(b.inv_inertia, applied);
    }
  }
}

void apply_restitution(StepScratch2D& scratch, W threshold) {
  for (ContactConstraint2D& c : scratch.constraints) {
    if (c.restitution == 0) continue;
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    for (int i = 0; i < c.count; ++i) {
      ContactConstraintPoint2D& cp = c.points[i];
      // Only points that were approaching fast and that pushed this step.
      if (cp.relative_velocity > -threshold || cp.max_normal_impulse == 0) continue;
      const W vn = normal_speed(c, cp, a, b);
      const W impulse = -wmul(cp.normal_mass, vn + wmul(c.restitution, cp.relative_velocity));
      const W accumulated = wmax(cp.normal_impulse + impulse, 0);
      const W applied = accumulated - cp.normal_impulse;
      cp.normal_impulse = accumulated;
      cp.max_normal_impulse = wmax(cp.max_normal_impulse, applied);
      push_normal(c, cp, a, b, applied);
    }
  }
}

void store_impulses(World2DState& state, const StepScratch2D& scratch) {
  for (const ContactConstraint2D& c : scratch.constraints) {
    ContactRecord2D& contact = state.contacts[c.contact];
    for (int i = 0; i < c.count; ++i) {
      contact.points[i].normal_impulse = c.points[i].normal_impulse;
      contact.points[i].tangent_impulse = c.points[i].tangent_impulse;
    }
    contact.rolling_impulse = c.rolling_impulse;
  }
}

}  // namespace rwd::sim2d::detail
