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

// Velocity of B's anchor relative to A's.
V2 relative_velocity(const SolverBody2D& a, V2 ra, const SolverBody2D& b, V2 rb) {
  return (b.v + vcross_sv(b.w, rb)) - (a.v + vcross_sv(a.w, ra));
}

void apply(SolverBody2D& a, V2 ra, SolverBody2D& b, V2 rb, V2 impulse) {
  a.v = vmul_sub(a.v, a.inv_mass, impulse);
  a.w -= wmul(a.inv_inertia, vcross(ra, impulse));
  b.v = vmul_add(b.v, b.inv_mass, impulse);
  b.w += wmul(b.inv_inertia, vcross(rb, impulse));
}

}  // namespace

void prepare_contacts(const World2DState& state, StepScratch2D& scratch, W h) {
  const World2DConfig& config = state.config;
  const W substep_hz = winv(h);
  const W hertz = wmin(w_from(config.contact_hertz), substep_hz / 4);
  const W zeta = w_from(config.contact_damping_ratio);
  const Softness2D soft = make_softness(hertz, zeta, h);
  const Softness2D static_soft = make_softness(2 * hertz, zeta, h);

  auto& constraints = scratch.constraints;
  constraints.clear();
  for (uint32_t ci = 0; ci < state.contacts.size(); ++ci) {
    const ContactRecord2D& contact = state.contacts[ci];
    if (contact.flags & kContactSensor) continue;
    if (!is_moving(state.bodies[contact.a]) && !is_moving(state.bodies[contact.b])) continue;
    const BodyRecord2D& body_a = state.bodies[contact.a];
    const BodyRecord2D& body_b = state.bodies[contact.b];
    const SolverBody2D& a = scratch.bodies[contact.a];
    const SolverBody2D& b = scratch.bodies[contact.b];
    ContactConstraint2D c;
    c.a = contact.a;
    c.b = contact.b;
    c.contact = ci;
    c.normal = contact.normal;
    c.friction = wsqrt(wmul(w_from(body_a.material.friction), w_from(body_b.material.friction)));
    c.restitution = wmax(w_from(body_a.material.restitution), w_from(body_b.material.restitution));
    c.rolling_resistance = wmax(w_from(body_a.material.rolling_resistance),
                                w_from(body_b.material.rolling_resistance));
    c.rolling_mass = inverse_or_zero(a.inv_inertia + b.inv_inertia);
    c.rolling_impulse = contact.rolling_impulse;
    c.softness = (a.inv_mass == 0 || b.inv_mass == 0) ? static_soft : soft;
    c.count = contact.count;
    const V2 n = contact.normal;
    const V2 t = vperp_cw(n);
    for (int i = 0; i < contact.count; ++i) {
      const ContactPoint2D& p = contact.points[i];
      ContactConstraintPoint2D& cp = c.points[i];
      cp.ra = p.anchor_a;
      cp.rb = p.anchor_b;
      cp.adjusted_separation = p.separation - vdot(cp.rb - cp.ra, n);
      cp.normal_impulse = p.normal_impulse;
      cp.tangent_impulse = p.tangent_impulse;
      const W rna = vcross(cp.ra, n);
      const W rnb = vcross(cp.rb, n);
      cp.normal_mass =
          inverse_or_zero(a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(rna, rna)) +
                          wmul(b.inv_inertia, wmul(rnb, rnb)));
      const W rta = vcross(cp.ra, t);
      const W rtb = vcross(cp.rb, t);
      cp.tangent_mass =
          inverse_or_zero(a.inv_mass + b.inv_mass + wmul(a.inv_inertia, wmul(rta, rta)) +
                          wmul(b.inv_inertia, wmul(rtb, rtb)));
      cp.relative_velocity = vdot(n, relative_velocity(a, cp.ra, b, cp.rb));
    }
    if (c.rolling_resistance > 0 && c.count > 0) {
      // The resisting torque is the coefficient times the normal force times
      // the lever from the centre of mass to the contact.
      const W lever = wmax(vlength(c.points[0].ra), vlength(c.points[0].rb));
      c.rolling_resistance = wmul(c.rolling_resistance, lever);
    }
    constraints.push_back(c);
  }
}

void warm_start_contacts(StepScratch2D& scratch) {
  for (ContactConstraint2D& c : scratch.constraints) {
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    const V2 t = vperp_cw(c.normal);
    for (int i = 0; i < c.count; ++i) {
      const ContactConstraintPoint2D& cp = c.points[i];
      const V2 impulse = vscale(cp.normal_impulse, c.normal) + vscale(cp.tangent_impulse, t);
      apply(a, cp.ra, b, cp.rb, impulse);
    }
    a.w -= wmul(a.inv_inertia, c.rolling_impulse);
    b.w += wmul(b.inv_inertia, c.rolling_impulse);
  }
}

void solve_contacts(StepScratch2D& scratch, W inv_h, W push_max, bool use_bias) {
  for (ContactConstraint2D& c : scratch.constraints) {
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    const V2 n = c.normal;
    W total_normal_impulse = 0;
    for (int i = 0; i < c.count; ++i) {
      ContactConstraintPoint2D& cp = c.points[i];
      // The separation now, from how far each body moved and turned since
      // the step began (the manifold is not recomputed between substeps).
      const V2 d = (b.dp - a.dp) + (rotate(b.dq, cp.rb) - rotate(a.dq, cp.ra));
      const W s = vdot(d, n) + cp.adjusted_separation;
      W bias = 0;
      W mass_scale = kWOne;
      W impulse_scale = 0;
      if (s > 0) {
        bias = wmul(s, inv_h);  // speculative: arrive exactly touching
      } else if (use_bias) {
        bias = wmax(wmul(c.softness.bias_rate, s), -push_max);
        mass_scale = c.softness.mass_scale;
        impulse_scale = c.softness.impulse_scale;
      }
      const W vn = vdot(relative_velocity(a, cp.ra, b, cp.rb), n);
      const W impulse = -wmul(wmul(cp.normal_mass, mass_scale), vn + bias) -
                        wmul(impulse_scale, cp.normal_impulse);
      const W accumulated = wmax(cp.normal_impulse + impulse, 0);
      const W applied = accumulated - cp.normal_impulse;
      cp.normal_impulse = accumulated;
      cp.max_normal_impulse = wmax(cp.max_normal_impulse, applied);
      total_normal_impulse += accumulated;
      apply(a, cp.ra, b, cp.rb, vscale(applied, n));
    }

    const V2 t = vperp_cw(n);
    for (int i = 0; i < c.count; ++i) {
      ContactConstraintPoint2D& cp = c.points[i];
      const W vt = vdot(relative_velocity(a, cp.ra, b, cp.rb), t);
      const W max_friction = wmul(c.friction, cp.normal_impulse);
      const W accumulated =
          wclamp(cp.tangent_impulse - wmul(cp.tangent_mass, vt), -max_friction, max_friction);
      const W applied = accumulated - cp.tangent_impulse;
      cp.tangent_impulse = accumulated;
      apply(a, cp.ra, b, cp.rb, vscale(applied, t));
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
      const W vn = vdot(relative_velocity(a, cp.ra, b, cp.rb), c.normal);
      const W impulse = -wmul(cp.normal_mass, vn + wmul(c.restitution, cp.relative_velocity));
      const W accumulated = wmax(cp.normal_impulse + impulse, 0);
      const W applied = accumulated - cp.normal_impulse;
      cp.normal_impulse = accumulated;
      cp.max_normal_impulse = wmax(cp.max_normal_impulse, applied);
      apply(a, cp.ra, b, cp.rb, vscale(applied, c.normal));
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
