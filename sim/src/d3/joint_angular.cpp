// SPDX-License-Identifier: MIT
// The angular part of a ball joint whose point is solved as a point joint
// (JointConstraint::angular, joint_solver.h): its cone-twist limit and its
// angular motor, each solved before the point in every pass (the point
// ends the pass holding) against the point held rigid, as the general
// path solves a joint's extra rows against its block (joint_block.h): a
// row's effective mass is the Schur complement of the point's 3 x 3, and
// its impulse comes with the linear impulse at the anchors that leaves
// the anchors' relative velocity as it was. So the joint's friction stops
// a limb about its joint, not about its centre of mass. Written for these
// rows alone (a turn about a world axis against a point), each costs a
// few dozen operations a pass, and the point joints around them run in
// the solver's lanes (joint_point_batches.h): this is the ragdoll's joint.
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

// What a unit turn impulse about `u` (-u to A, +u to B) does to the
// point rows' velocities: (I_A u) x r_A + (I_B u) x r_B.
Vec3 coupling(const JointConstraint& c, const SolverBody& a, const SolverBody& b, Vec3 u) {
  return cross(a.inv_inertia * u, c.frames.ra) + cross(b.inv_inertia * u, c.frames.rb);
}

// What a unit turn impulse about `u`, with the anchors' compensating
// linear impulse p = -K^-1 C u, does to the bodies' velocities.
TurnResponse turn_response(const JointConstraint& c, const SolverBody& a, const SolverBody& b,
                           Vec3 u) {
  const Vec3 ia = a.inv_inertia * u;
  const Vec3 ib = b.inv_inertia * u;
  const Vec3 p = -(c.angular_point_inv * (cross(ia, c.frames.ra) + cross(ib, c.frames.rb)));
  return {-(p * a.inv_mass), -(ia + a.inv_inertia * cross(c.frames.ra, p)), p * b.inv_mass,
          ib + b.inv_inertia * cross(c.frames.rb, p)};
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

// The limits where the bodies stand (frames f), each with its effective
// mass against the point.
void find_limits(const JointRecord& j, JointConstraint& c, const SolverBody& a, const SolverBody& b,
                 const JointFrames& f) {
  c.limit_count = static_cast<uint8_t>(joint_ops(j.type).limits(j, f, c.limits));
  for (int k = 0; k < c.limit_count; ++k) {
    const Vec3 u = c.limits[k].row.angular_b;
    const float own = dot(u, a.inv_inertia * u) + dot(u, b.inv_inertia * u);
    const Vec3 cu = coupling(c, a, b, u);
    const float schur = own - dot(cu, c.angular_point_inv * cu);
    c.limit_mass[k] = own > 0.0f && schur > kExtraShare * own ? 1.0f / schur : 0.0f;
    c.limit_response[k] = turn_response(c, a, b, u);
  }
}

void solve_part(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
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
  if ((j.flags & kJointLimit) == 0) return;
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
    const float lambda = -c.limit_mass[k] * rhs * t.mass_scale - impulse * t.impulse_scale;
    const float next = impulse + lambda > 0.0f ? impulse + lambda : 0.0f;
    const float delta = next - impulse;
    impulse = next;
    if (delta != 0.0f) apply_response(c.limit_response[k], a, b, delta);
  }
}

}  // namespace

bool has_angular_part(const JointRecord& j) {
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
    if ((j.flags & kJointMotor) != 0) {
      // The three turns' Schur complement against the point:
      // (I_A + I_B) - C^T K^-1 C, C's columns the turns' couplings.
      const Vec3 col[3] = {coupling(c, a, b, {1.0f, 0.0f, 0.0f}),
                           coupling(c, a, b, {0.0f, 1.0f, 0.0f}),
                           coupling(c, a, b, {0.0f, 0.0f, 1.0f})};
      const Mat3 own = a.inv_inertia + b.inv_inertia;
      const Vec3 own_col[3] = {own.c0, own.c1, own.c2};
      Vec3 s[3];
      for (int q = 0; q < 3; ++q) {
        const Vec3 y = c.angular_point_inv * col[q];
        s[q] = own_col[q] - Vec3{dot(col[0], y), dot(col[1], y), dot(col[2], y)};
      }
      c.angular_inv_mass = inverse_symmetric(Mat3{s[0], s[1], s[2]});
      c.motor_response[0] = turn_response(c, a, b, {1.0f, 0.0f, 0.0f});
      c.motor_response[1] = turn_response(c, a, b, {0.0f, 1.0f, 0.0f});
      c.motor_response[2] = turn_response(c, a, b, {0.0f, 0.0f, 1.0f});
    }
    c.limit_count = 0;
    if ((j.flags & kJointLimit) != 0) find_limits(j, c, a, b, c.frames);
  }
}

void warm_start_angular_parts(const WorldState& state, WorldScratch& scratch) {
  for (const uint32_t k : scratch.joint_angular) {
    const JointConstraint& c = scratch.joint_constraints[k];
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    // (Without a motor the impulse is zero and its responses unset:
    // has_angular_part.)
    if ((state.joints[c.record].flags & kJointMotor) != 0) apply_motor(c, a, b, c.motor_impulse);
    for (int q = 0; q < c.limit_count; ++q) {
      apply_response(c.limit_response[q], a, b, limit_impulse(c, c.limits[q].kind));
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
    solve_part(state.joints[c.record], c, a, b, use_bias, scratch.joint_frames_fresh);
  }
  bodies[0].linear_velocity = {};
  bodies[0].angular_velocity = {};
}

}  // namespace rwd::sim::d3
