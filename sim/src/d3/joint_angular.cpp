// SPDX-License-Identifier: MIT
// The angular part of a joint whose point is solved as a point joint
// (JointConstraint::angular, joint_solver.h): a ball joint's cone-twist
// limit and angular motor, or a hinge's two turns off its axis (its
// structure beside the point) and the spring, motor and limits about the
// axis. Each row is solved before the point in every pass (the point ends
// the pass holding) against the point held rigid, as the general path
// solves a joint's extra rows against its block (joint_block.h): a row's
// effective mass is the Schur complement of the point's 3 x 3, and its
// impulse comes with the linear impulse at the anchors that leaves the
// anchors' relative velocity as it was. So the joint's friction stops a
// limb about its joint, not about its centre of mass. Written for these
// rows alone (a turn about a world axis against a point), each costs a
// few dozen operations a pass. This file is the scalar path, for the
// joints that found no colour; the rest run in the lanes of their points'
// batches with the same maths (joint_angular_batches.h). This is the
// ragdoll's joint.
//
// Unlike the general path, a limit already reached does not join the
// point in one block: it stays a row against the point, the point solved
// after it.
#include <cmath>

#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// An extra row the point already holds has no Schur complement left
// (what is left is rounding): it is left out, as joint_block.cpp does.
constexpr float kExtraShare = 1e-5f;

// A unit turn impulse about `u` (-u to A, +u to B) against the point:
// what it does to each body's angular velocity alone (I u), to the point
// rows' velocities (C u = (I_A u) x r_A + (I_B u) x r_B), and K^-1 C u,
// the anchors' compensating impulse with its sign turned.
struct Turn {
  Vec3 u;
  Vec3 ia;
  Vec3 ib;
  Vec3 c;
  Vec3 y;
};

Turn make_turn(const JointConstraint& c, const SolverBody& a, const SolverBody& b, Vec3 u) {
  Turn t;
  t.u = u;
  t.ia = a.inv_inertia * u;
  t.ib = b.inv_inertia * u;
  t.c = cross(t.ia, c.frames.ra) + cross(t.ib, c.frames.rb);
  t.y = c.angular_point_inv * t.c;
  return t;
}

// Entry (t, s) of the turns' Schur complement against the point.
float schur(const Turn& t, const Turn& s) {
  return dot(t.u, s.ia) + dot(t.u, s.ib) - dot(t.c, s.y);
}

// The inverse effective mass of a lone turn: 1 / its Schur complement, or
// 0 when the point holds it.
float turn_mass(const Turn& t) {
  const float own = dot(t.u, t.ia) + dot(t.u, t.ib);
  const float s = own - dot(t.c, t.y);
  return own > 0.0f && s > kExtraShare * own ? 1.0f / s : 0.0f;
}

// What the turn's unit impulse, with the anchors' impulse p = -K^-1 C u,
// does to the bodies' velocities.
TurnResponse turn_response(const JointConstraint& c, const SolverBody& a, const SolverBody& b,
                           const Turn& t) {
  const Vec3 p = -t.y;
  return {-(p * a.inv_mass), -(t.ia + a.inv_inertia * cross(c.frames.ra, p)), p * b.inv_mass,
          t.ib + b.inv_inertia * cross(c.frames.rb, p)};
}

void apply_response(const TurnResponse& r, SolverBody& a, SolverBody& b, float delta) {
  a.linear_velocity += r.va * delta;
  a.angular_velocity += r.wa * delta;
  b.linear_velocity += r.vb * delta;
  b.angular_velocity += r.wb * delta;
}

// A turn impulse d about the world axes (the motor's rows).
void apply_motor(const JointConstraint& c, SolverBody& a, SolverBody& b, Vec3 d) {
  apply_response(c.motor_response[0], a, b, d.x);
  apply_response(c.motor_response[1], a, b, d.y);
  apply_response(c.motor_response[2], a, b, d.z);
}

// Limit k's effective mass against the point and its response, made
// when a pass first needs them after the refresh (most limits of a pile
// stand open through most substeps). They depend only on the refresh's
// rows and the tick's inertia, so when they are made does not matter.
void ready_limit(JointConstraint& c, const SolverBody& a, const SolverBody& b, int k) {
  if ((c.limit_ready & (1u << k)) != 0) return;
  c.limit_ready = static_cast<uint8_t>(c.limit_ready | (1u << k));
  const Turn t = make_turn(c, a, b, c.limits[k].row.angular_b);
  c.limit_mass[k] = turn_mass(t);
  c.limit_response[k] = turn_response(c, a, b, t);
}

// A hinge at the refresh: its axis and angle, the two turns off the axis
// with their misalignment and their 2 x 2 Schur complement against the
// point (inverted; a turn the point holds is left out), and the
// responses of all three turns. (Its limits are rows about the axis.)
void refresh_hinge(JointConstraint& c, const SolverBody& a, const SolverBody& b) {
  const JointFrames& f = c.frames;
  const Vec3 xa = rotate(f.fa, kAxisX);
  c.hinge_axis = xa;
  c.hinge_angle = twist_angle(conjugate(f.fa) * f.fb);
  c.align_axis[0] = rotate(f.fa, kAxisY);
  c.align_axis[1] = rotate(f.fa, kAxisZ);
  const Vec3 tilt = cross(xa, rotate(f.fb, kAxisX));
  const Turn t0 = make_turn(c, a, b, c.align_axis[0]);
  const Turn t1 = make_turn(c, a, b, c.align_axis[1]);
  const Turn tx = make_turn(c, a, b, xa);
  const Turn* align[2] = {&t0, &t1};
  for (int k = 0; k < 2; ++k) {
    c.align_error[k] = dot(tilt, c.align_axis[k]);
    c.align_response[k] = turn_response(c, a, b, *align[k]);
    c.align_impulse[k] = dot(c.angular_impulse, c.align_axis[k]);
  }
  // The 2 x 2 inverted, leaving out a turn the point holds.
  const float own0 = dot(t0.u, t0.ia) + dot(t0.u, t0.ib);
  const float own1 = dot(t1.u, t1.ia) + dot(t1.u, t1.ib);
  float s00 = schur(t0, t0);
  float s11 = schur(t1, t1);
  float s01 = schur(t0, t1);
  const bool keep0 = own0 > 0.0f && s00 > kExtraShare * own0;
  const bool keep1 = own1 > 0.0f && s11 > kExtraShare * own1;
  if (!keep0) s00 = 1.0f, s01 = 0.0f;
  if (!keep1) s11 = 1.0f, s01 = 0.0f;
  const float det = s00 * s11 - s01 * s01;
  const float inv_det = det > 0.0f ? 1.0f / det : 0.0f;
  c.align_inv[0] = keep0 ? s11 * inv_det : 0.0f;
  c.align_inv[1] = keep0 && keep1 ? -s01 * inv_det : 0.0f;
  c.align_inv[2] = keep1 ? s00 * inv_det : 0.0f;
  c.axial_mass = turn_mass(tx);
  c.axial_response = turn_response(c, a, b, tx);
}

// The limits, each a one-sided row against the point.
void solve_limits(JointConstraint& c, SolverBody& a, SolverBody& b, bool use_bias, bool at_refresh);

// The hinge's rows about its axis: spring, motor, limits; then the two
// turns off it (its structure beside the point).
void solve_hinge(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                 bool use_bias, bool at_refresh) {
  const Vec3 axis = c.hinge_axis;
  // After the move the angle has turned by the axis's relative velocity
  // over the substep (see solve_limits).
  const float angle =
      at_refresh ? c.hinge_angle : c.hinge_angle + c.h * dot(axis, relative_angular_velocity(a, b));
  if ((j.flags & kJointSpring) != 0) {
    const RowTerms t = spring_terms(c.spring_soft, wrap_angle(angle - j.spring_target));
    const float rhs = dot(axis, relative_angular_velocity(a, b)) + t.bias;
    const float lambda = -c.axial_mass * rhs * t.mass_scale - c.spring_impulse.x * t.impulse_scale;
    c.spring_impulse.x += lambda;
    apply_response(c.axial_response, a, b, lambda);
  }
  if ((j.flags & kJointMotor) != 0) {
    const float rhs = dot(axis, relative_angular_velocity(a, b)) - j.motor_speed;
    const float max = j.max_motor * c.h;
    const float old = c.motor_impulse.x;
    float next = old - c.axial_mass * rhs;
    next = next > max ? max : (next < -max ? -max : next);
    c.motor_impulse.x = next;
    apply_response(c.axial_response, a, b, next - old);
  }
  if ((j.flags & kJointLimit) != 0) solve_limits(c, a, b, use_bias, at_refresh);
  // The two turns off the axis, together: soft toward the refresh's
  // misalignment with the bias, rigid without.
  const Vec3 w = relative_angular_velocity(a, b);
  float rhs[2];
  for (int k = 0; k < 2; ++k) {
    rhs[k] = dot(c.align_axis[k], w) + (use_bias ? c.soft.bias_rate * c.align_error[k] : 0.0f);
  }
  const float x0 = c.align_inv[0] * rhs[0] + c.align_inv[1] * rhs[1];
  const float x1 = c.align_inv[1] * rhs[0] + c.align_inv[2] * rhs[1];
  const float mass_scale = use_bias ? c.soft.mass_scale : 1.0f;
  const float impulse_scale = use_bias ? c.soft.impulse_scale : 0.0f;
  const float l0 = -x0 * mass_scale - c.align_impulse[0] * impulse_scale;
  const float l1 = -x1 * mass_scale - c.align_impulse[1] * impulse_scale;
  c.align_impulse[0] += l0;
  c.align_impulse[1] += l1;
  apply_response(c.align_response[0], a, b, l0);
  apply_response(c.align_response[1], a, b, l1);
  c.angular_impulse = c.align_axis[0] * c.align_impulse[0] + c.align_axis[1] * c.align_impulse[1];
}

void solve_ball(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                bool use_bias, bool at_refresh) {
  if ((j.flags & kJointMotor) != 0) {
    // Toward the target relative angular velocity, the accumulated
    // impulse held within the motor's torque times the substep.
    const Vec3 cdot = relative_angular_velocity(a, b) - j.motor_velocity;
    const Vec3 old = c.motor_impulse;
    Vec3 next = old - c.angular_inv_mass * cdot;
    const float max = j.max_motor * c.h;
    const float len_sq = length_squared(next);
    if (len_sq > max * max) next = next * (max / std::sqrt(len_sq));
    c.motor_impulse = next;
    apply_motor(c, a, b, next - old);
  }
  if ((j.flags & kJointLimit) != 0) solve_limits(c, a, b, use_bias, at_refresh);
}

void solve_limits(JointConstraint& c, SolverBody& a, SolverBody& b, bool use_bias,
                  bool at_refresh) {
  // After the substep's move the rows are the refresh's (a substep
  // behind, as the general path's block is in its relax) and each gap has
  // moved by the rows' velocity over the substep: the velocity the bodies
  // just moved with, as the relax finds it. (Working the limits out anew
  // where the bodies stand cost a third of a ragdoll pile's joints.)
  float moved[kMaxLimitRows] = {};
  if (!at_refresh) {
    const Vec3 w = relative_angular_velocity(a, b);
    for (int k = 0; k < c.limit_count; ++k) moved[k] = c.h * dot(c.limits[k].row.angular_b, w);
  }
  for (int k = 0; k < c.limit_count; ++k) {
    const LimitRow& l = c.limits[k];
    float& impulse = limit_impulse(c, l.kind);
    const RowTerms t = limit_terms(c.soft, l.gap + moved[k], c.h, use_bias);
    const float rhs = dot(l.row.angular_b, relative_angular_velocity(a, b)) + t.bias;
    // Open, holding nothing and not closing within the substep.
    if (impulse == 0.0f && rhs >= 0.0f) continue;
    ready_limit(c, a, b, k);
    const float lambda = -c.limit_mass[k] * rhs * t.mass_scale - impulse * t.impulse_scale;
    const float next = impulse + lambda > 0.0f ? impulse + lambda : 0.0f;
    const float delta = next - impulse;
    impulse = next;
    if (delta != 0.0f) apply_response(c.limit_response[k], a, b, delta);
  }
}

}  // namespace

bool has_angular_part(const JointRecord& j) {
  if (j.type == JointType::kHinge) return true;
  return j.type == JointType::kBall && (j.flags & kJointSpring) == 0 &&
         (j.flags & (kJointLimit | kJointMotor)) != 0 &&
         ((j.flags & kJointMotor) != 0 || j.motor_impulse == Vec3{});
}

void refresh_angular_parts(const WorldState& state, WorldScratch& scratch) {
  for (const uint32_t k : scratch.joint_angular) {
    JointConstraint& c = scratch.joint_constraints[k];
    const JointRecord& j = state.joints[c.record];
    const SolverBody& a = scratch.solver_bodies[c.body_a];
    const SolverBody& b = scratch.solver_bodies[c.body_b];
    c.frames = joint_frames(c, a, b);
    c.angular_point_inv = inverse_symmetric(point_mass_matrix(
        a.inv_mass, a.inv_inertia, c.frames.ra, b.inv_mass, b.inv_inertia, c.frames.rb));
    c.limit_count = 0;
    c.limit_ready = 0;
    if ((j.flags & kJointLimit) != 0) {
      c.limit_count = static_cast<uint8_t>(joint_ops(j.type).limits(j, c.frames, c.limits));
    }
    c.hinge = j.type == JointType::kHinge;
    if (c.hinge) {
      refresh_hinge(c, a, b);
      continue;
    }
    if ((j.flags & kJointMotor) != 0) {
      // The three turns about the world axes, their Schur complement
      // against the point ((I_A + I_B) - C^T K^-1 C) inverted.
      const Turn t[3] = {make_turn(c, a, b, kAxisX), make_turn(c, a, b, kAxisY),
                         make_turn(c, a, b, kAxisZ)};
      Vec3 col[3];
      for (int q = 0; q < 3; ++q) {
        col[q] = {schur(t[0], t[q]), schur(t[1], t[q]), schur(t[2], t[q])};
        c.motor_response[q] = turn_response(c, a, b, t[q]);
      }
      c.angular_inv_mass = inverse_symmetric(Mat3{col[0], col[1], col[2]});
    }
  }
}

void warm_start_angular_parts(const WorldState& state, WorldScratch& scratch) {
  for (const uint32_t k : scratch.joint_angular) {
    JointConstraint& c = scratch.joint_constraints[k];
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    if (state.joints[c.record].type == JointType::kHinge) {
      apply_response(c.axial_response, a, b, c.motor_impulse.x + c.spring_impulse.x);
      apply_response(c.align_response[0], a, b, c.align_impulse[0]);
      apply_response(c.align_response[1], a, b, c.align_impulse[1]);
    } else if ((state.joints[c.record].flags & kJointMotor) != 0) {
      // (Without a motor the impulse is zero and its responses unset:
      // has_angular_part.)
      apply_motor(c, a, b, c.motor_impulse);
    }
    for (int q = 0; q < c.limit_count; ++q) {
      const float impulse = limit_impulse(c, c.limits[q].kind);
      if (impulse == 0.0f) continue;
      ready_limit(c, a, b, q);
      apply_response(c.limit_response[q], a, b, impulse);
    }
  }
}

void solve_angular_parts(const WorldState& state, WorldScratch& scratch, bool use_bias,
                         bool contacted_only) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for (const uint32_t k : scratch.joint_angular) {
    JointConstraint& c = scratch.joint_constraints[k];
    SolverBody& a = bodies[c.body_a];
    SolverBody& b = bodies[c.body_b];
    if (contacted_only && !a.contacted && !b.contacted) continue;
    const JointRecord& j = state.joints[c.record];
    if (j.type == JointType::kHinge) {
      solve_hinge(j, c, a, b, use_bias, scratch.joint_frames_fresh);
    } else {
      solve_ball(j, c, a, b, use_bias, scratch.joint_frames_fresh);
    }
  }
  bodies[0].linear_velocity = {};
  bodies[0].angular_velocity = {};
}

void project_angular_parts(const WorldState& state, WorldScratch& scratch) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for (const uint32_t k : scratch.joint_angular) {
    JointConstraint& c = scratch.joint_constraints[k];
    if (!c.hinge) continue;
    SolverBody& a = bodies[c.body_a];
    SolverBody& b = bodies[c.body_b];
    // The hinge's axes brought back into line (its point after, with the
    // points), by the same responses as its impulses, clamped.
    const JointFrames f = joint_frames(c, a, b);
    const Vec3 tilt = cross(rotate(f.fa, kAxisX), rotate(f.fb, kAxisX));
    const float e0 = clamp_projection(dot(tilt, c.align_axis[0]));
    const float e1 = clamp_projection(dot(tilt, c.align_axis[1]));
    const float x0 = -(c.align_inv[0] * e0 + c.align_inv[1] * e1);
    const float x1 = -(c.align_inv[1] * e0 + c.align_inv[2] * e1);
    // A limit crossed is brought back too, about the axis.
    float x2 = 0.0f;
    const JointRecord& j = state.joints[c.record];
    if ((j.flags & kJointLimit) != 0) {
      const float angle = twist_angle(conjugate(f.fa) * f.fb);
      if (angle < j.lower) x2 = -c.axial_mass * clamp_projection(angle - j.lower);
      if (angle > j.upper) x2 = -c.axial_mass * clamp_projection(angle - j.upper);
    }
    const TurnResponse& r0 = c.align_response[0];
    const TurnResponse& r1 = c.align_response[1];
    const TurnResponse& r2 = c.axial_response;
    if (a.inv_mass > 0.0f) {
      a.delta_position += r0.va * x0 + r1.va * x1 + r2.va * x2;
      a.delta_rotation =
          integrate_rotation(a.delta_rotation, r0.wa * x0 + r1.wa * x1 + r2.wa * x2, 1.0f);
    }
    if (b.inv_mass > 0.0f) {
      b.delta_position += r0.vb * x0 + r1.vb * x1 + r2.vb * x2;
      b.delta_rotation =
          integrate_rotation(b.delta_rotation, r0.wb * x0 + r1.wb * x1 + r2.wb * x2, 1.0f);
    }
  }
}

}  // namespace rwd::sim::d3
