// SPDX-License-Identifier: MIT
// The soft step (DESIGN 6): substeps of integrate velocities, warm start,
// solve, integrate positions and relax; then restitution and storing the
// impulses for the next step's warm start.
#include "body_mass2d.h"
#include "body_math2d.h"
#include "contact_solver2d.h"
#include "joint_solver2d.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

// Each moving body's solver state, and what a substep's integration adds
// to it: the same every substep of a step, so worked out once here from the
// body record instead of read from it every substep.
void load_bodies(const World2DState& state, StepScratch2D& scratch, W h) {
  const V2 gravity = v_from(state.config.gravity);
  scratch.bodies.resize(state.bodies.size());
  scratch.moving.clear();
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    const BodyRecord2D& body = state.bodies[i];
    SolverBody2D& sb = scratch.bodies[i];
    sb = {};
    // A sleeping body is as immovable as a static one this step.
    if (!is_moving(body)) continue;
    sb.v = body.velocity;
    sb.w = body.angular_velocity;
    sb.inv_mass = body.inv_mass;
    sb.inv_inertia = body.inv_inertia;
    BodyMotion2D m;
    m.body = i;
    // Gravity, forces and damping, for dynamic bodies. Damping divides by
    // (1 + h c), which never reverses a velocity however large c.
    m.dynamic = body.kind == BodyKind2D::kDynamic;
    if (m.dynamic) {
      const W g = w_from(body.gravity_scale);
      m.dv = vmul_add(vscale(wmul(h, g), gravity), wmul(h, body.inv_mass), body.force);
      m.dw = wmul(wmul(h, body.inv_inertia), body.torque);
      if (body.linear_damping > Fx()) {
        m.linear_keep = winv(kWOne + wmul(h, w_from(body.linear_damping)));
      }
      if (body.angular_damping > Fx()) {
        m.angular_keep = winv(kWOne + wmul(h, w_from(body.angular_damping)));
      }
    }
    scratch.moving.push_back(m);
  }
}

// Gravity, forces and damping for one substep of dynamic bodies.
void integrate_velocities(const World2DState& state, StepScratch2D& scratch, W h) {
  // At most a quarter turn per substep: beyond that the rotation update
  // (first order, renormalized) loses its meaning.
  const W max_w = wmul(kWPi / 4, winv(h));
  for (const BodyMotion2D& m : scratch.moving) {
    if (!m.dynamic) continue;
    SolverBody2D& sb = scratch.bodies[m.body];
    V2 v = sb.v;
    W w = sb.w;
    if (m.linear_keep != kWOne) v = vscale(m.linear_keep, v);
    if (m.angular_keep != kWOne) w = wmul(m.angular_keep, w);
    sb.v = clamp_speed(v + m.dv, state.config);
    sb.w = wclamp(w + m.dw, -max_w, max_w);
  }
}

// Kinematic bodies move too: they carry what they touch. Velocities are
// capped again first: a solve can exceed what integration allowed, and the
// cap is what keeps every sum inside the integer range.
void integrate_positions(const World2DState& state, StepScratch2D& scratch, W h) {
  const W max_w = wmul(kWPi / 4, winv(h));
  for (const BodyMotion2D& m : scratch.moving) {
    SolverBody2D& sb = scratch.bodies[m.body];
    sb.v = clamp_speed(sb.v, state.config);
    sb.w = wclamp(sb.w, -max_w, max_w);
    sb.dp += vscale(h, sb.v);
    if (sb.w != 0) sb.dq = integrate_rotation(sb.dq, wmul(h, sb.w));
  }
}

void write_back(World2DState& state, const StepScratch2D& scratch) {
  for (size_t i = 0; i < state.bodies.size(); ++i) {
    BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyLive)) continue;
    body.force = {};
    body.torque = 0;
    if (!is_moving(body)) continue;
    const SolverBody2D& sb = scratch.bodies[i];
    body.center += sb.dp;
    if (!(sb.dq == Rot{})) body.rotation = renormalize(rmul(sb.dq, body.rotation));
    // The relax pass and restitution run after the last cap: cap again, so
    // every state a step leaves is one deserialize() accepts.
    body.velocity = clamp_speed(sb.v, state.config);
    body.angular_velocity = sb.w;
  }
}

}  // namespace

void solve_step(World2DState& state, StepScratch2D& scratch, StepStats2D& stats) {
  const World2DConfig& config = state.config;
  const int substeps = config.substeps;
  const W h = w_ratio(1, int64_t{config.tick_hz} * substeps);
  const W inv_h = w_int(int64_t{config.tick_hz} * substeps);
  const W push_max = w_from(config.contact_push_max);

  load_bodies(state, scratch, h);
  prepare_joints(state, scratch, h);
  prepare_contacts(state, scratch, h);
  JointPass2D biased{h, inv_h, true};
  JointPass2D relax{h, inv_h, false};
  // Joints before contacts in every stage: contacts, solved last, win
  // where the two disagree, so joined bodies do not sink into the ground.
  for (int i = 0; i < substeps; ++i) {
    integrate_velocities(state, scratch, h);
    warm_start_joints(state, scratch);
    warm_start_contacts(scratch);
    biased.positions = static_cast<uint32_t>(i);
    solve_joints(state, scratch, biased);
    solve_contacts(scratch, inv_h, push_max, true);
    integrate_positions(state, scratch, h);
    relax.positions = static_cast<uint32_t>(i) + 1;
    for (int r = 0; r < config.relax_iterations; ++r) {
      solve_joints(state, scratch, relax);
      solve_contacts(scratch, inv_h, push_max, false);
    }
  }
  apply_restitution(scratch, w_from(config.restitution_threshold));
  store_impulses(state, scratch);
  break_joints(state, substeps);
  write_back(state, scratch);

  stats.touching_contacts = static_cast<uint32_t>(scratch.constraints.size());
  uint32_t points = 0;
  for (const ContactConstraint2D& c : scratch.constraints) points += static_cast<uint32_t>(c.count);
  stats.contact_points = points;
  stats.solver_iterations = static_cast<uint32_t>(substeps * (1 + config.relax_iterations));
}

}  // namespace rwd::sim2d::detail
