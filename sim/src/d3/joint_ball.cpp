// SPDX-License-Identifier: MIT
// The ball joint: the anchors coincide (its structure: three point rows).
// Optionally a cone-twist joint (the swing of B's twist axis from A's
// within a cone, the twist about them within a range), an angular motor
// and an orientation spring, each solved against the point rows held
// rigid, softest first (spring, motor, limits); the structure ends the
// pass.
#include <cmath>

#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// Where the cone and twist limits stand: the swing angle and the axis it
// grows about, the twist angle and the axis it grows about.
struct ConeTwist {
  bool has_swing = false;
  Vec3 swing_axis;  ///< unit; the swing grows about it
  float swing = 0.0f;
  Vec3 twist_axis;  ///< unit, or zero when the axes are opposed
  float twist = 0.0f;
};

ConeTwist cone_twist(const JointFrames& f) {
  ConeTwist ct;
  const Vec3 xa = rotate(f.fa, kAxisX);
  const Vec3 xb = rotate(f.fb, kAxisX);
  const Vec3 n = cross(xa, xb);
  const float s = length(n);
  if (s > 1e-6f) {
    ct.has_swing = true;
    ct.swing_axis = n * (1.0f / s);
    ct.swing = det_atan2(s, dot(xa, xb));
  }
  ct.twist_axis = normalize_or_zero(xa + xb);
  ct.twist = twist_angle(conjugate(f.fa) * f.fb);
  return ct;
}

bool limited(const JointRecord& j) {
  return (j.flags & kJointLimit) != 0;
}

int ball_rows(const JointRecord&, const JointFrames& f, JointRow* out) {
  return point_rows(f, out);
}

Vec3 no_angular_error(const JointRecord&, const JointFrames&) {
  return {};
}

void warm_start_ball(const JointRecord&, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  apply_angular(a, b, c.motor_impulse + c.spring_impulse);
}

// The cone (the swing of B's axis from A's) and the twist range.
int ball_limits(const JointRecord& j, const JointFrames& f, LimitRow* out) {
  if (!limited(j)) return 0;
  const ConeTwist ct = cone_twist(f);
  int n = 0;
  if (ct.has_swing && j.cone_angle < kPi) {
    out[n++] = {angular_jacobian(-ct.swing_axis), j.cone_angle - ct.swing, kRowCone};
  }
  if (!(ct.twist_axis == Vec3{})) {
    out[n++] = {angular_jacobian(ct.twist_axis), ct.twist - j.twist_lower, kRowLower};
    out[n++] = {angular_jacobian(-ct.twist_axis), j.twist_upper - ct.twist, kRowUpper};
  }
  return n;
}

float get(Vec3 v, int i) {
  return component(v, i);
}

void ball_extras(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                 const JointFrames& f, bool, const ExtraBase& base) {
  const bool spring = (j.flags & kJointSpring) != 0;
  const bool motor = (j.flags & kJointMotor) != 0;
  if (spring || motor) {
    // Both drive the three relative angular velocities.
    // Against a tree the base is the tree's factor, which each substep
    // refactors (the tree keeps the group between refactorizations);
    // against the joint's own block it changes only when the block is
    // refreshed.
    ExtraGroup in_tree;
    const bool alone = base.scratch == nullptr;
    if (!alone || !c.orientation_ready) {
      JointRow rows[3];
      orientation_rows(rows);
      (alone ? c.orientation : in_tree).prepare(base, rows, 3, a, b, kKeptAxis);
      c.orientation_ready = alone;
    }
    const ExtraGroup& group = alone ? c.orientation : in_tree;
    if (spring) {
      // The rotation from where B should be (A's rotation times the
      // target) to where it is, in the world.
      const Vec3 error = rotation_vector(f.qb * conjugate(f.qa * j.spring_rotation));
      const JointSoftness& s = c.spring_soft;
      float cdot[3];
      group.velocity(a, b, cdot);
      float rhs[3];
      for (int k = 0; k < 3; ++k) rhs[k] = cdot[k] + get(error, k) * s.bias_rate;
      float x[3];
      group.solve(rhs, x);
      float delta[3];
      for (int k = 0; k < 3; ++k) {
        delta[k] = -x[k] * s.mass_scale - get(c.spring_impulse, k) * s.impulse_scale;
      }
      c.spring_impulse += Vec3{delta[0], delta[1], delta[2]};
      group.apply(base, a, b, delta);
    }
    if (motor) {
      float cdot[3];
      group.velocity(a, b, cdot);
      float rhs[3];
      for (int k = 0; k < 3; ++k) rhs[k] = cdot[k] - get(j.motor_velocity, k);
      float x[3];
      group.solve(rhs, x);
      const Vec3 old = c.motor_impulse;
      Vec3 next = old - Vec3{x[0], x[1], x[2]};
      const float max = j.max_motor * c.h;
      const float len_sq = length_squared(next);
      if (len_sq > max * max) next = next * (max / std::sqrt(len_sq));
      c.motor_impulse = next;
      const Vec3 d = next - old;
      const float delta[3] = {d.x, d.y, d.z};
      group.apply(base, a, b, delta);
    }
  }
}

}  // namespace

const JointOps kBallOps = {nullptr,     ball_rows,       no_angular_error, ball_limits,
                           ball_extras, warm_start_ball, nullptr};

}  // namespace rwd::sim::d3
