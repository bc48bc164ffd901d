// SPDX-License-Identifier: MIT
// The hinge: the anchors coincide and B's axis stays on A's, leaving one
// turning axis. The block is five rows: the point, and the two turns
// about the axes perpendicular to A's hinge axis. Its angle (relative to
// the pose at creation) may be pulled by a spring, driven by a motor and
// limited, each row solved about the axis against the block held rigid,
// so a door hung from its edge stops at its limit about the hinge line.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

constexpr Vec3 kAxisX{1.0f, 0.0f, 0.0f};
constexpr Vec3 kAxisY{0.0f, 1.0f, 0.0f};
constexpr Vec3 kAxisZ{0.0f, 0.0f, 1.0f};

float wrap_angle(float angle) {
  if (angle > kPi) return angle - 2.0f * kPi;
  if (angle < -kPi) return angle + 2.0f * kPi;
  return angle;
}

// The impulse about the hinge axis: spring, motor and limits.
float axial_impulse(const JointConstraint& c) {
  return c.motor_impulse.x + c.spring_impulse.x + c.lower_impulse - c.upper_impulse;
}

void prepare_hinge(const JointRecord&, JointConstraint& c, const SolverBody&, const SolverBody&) {
  // The stored perpendicular impulse, onto the plane the axis now spans.
  const Vec3 axis = rotate(c.frame_a, kAxisX);
  c.angular_impulse -= axis * dot(c.angular_impulse, axis);
}

void warm_start_hinge(const JointRecord&, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  apply_linear(a, b, f.ra, f.rb, c.linear_impulse);
  apply_angular(a, b, c.angular_impulse + rotate(f.fa, kAxisX) * axial_impulse(c));
}

void solve_hinge(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                 bool use_bias) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 xa = rotate(f.fa, kAxisX);
  const Vec3 ya = rotate(f.fa, kAxisY);
  const Vec3 za = rotate(f.fa, kAxisZ);
  RowBlock block;
  add_point_rows(block, f);
  block.add(angular_jacobian(ya));
  block.add(angular_jacobian(za));
  block.factor(a, b);
  float acc[5] = {c.linear_impulse.x, c.linear_impulse.y, c.linear_impulse.z,
                  dot(c.angular_impulse, ya), dot(c.angular_impulse, za)};
  const float angle = twist_angle(conjugate(f.fa) * f.fb);
  const JointRow turn = angular_jacobian(xa);
  if ((j.flags & kJointSpring) != 0) {
    solve_extra_row(block, a, b, turn,
                    spring_terms(c.spring_soft, wrap_angle(angle - j.spring_target)), 0.0f,
                    -kUnbounded, kUnbounded, c.spring_impulse.x, acc);
  }
  if ((j.flags & kJointMotor) != 0) {
    const float max = j.max_motor * c.h;
    solve_extra_row(block, a, b, turn, RowTerms{}, j.motor_speed, -max, max, c.motor_impulse.x,
                    acc);
  }
  if ((j.flags & kJointLimit) != 0) {
    solve_extra_row(block, a, b, turn, limit_terms(c.soft, angle - j.lower, c.h, use_bias), 0.0f,
                    0.0f, kUnbounded, c.lower_impulse, acc);
    solve_extra_row(block, a, b, angular_jacobian(-xa),
                    limit_terms(c.soft, j.upper - angle, c.h, use_bias), 0.0f, 0.0f, kUnbounded,
                    c.upper_impulse, acc);
  }
  // The axes' misalignment: the rotation taking A's axis to B's.
  const Vec3 tilt = cross(xa, rotate(f.fb, kAxisX));
  const float rate = c.soft.bias_rate;
  const float bias[5] = {f.d.x * rate, f.d.y * rate, f.d.z * rate, dot(tilt, ya) * rate,
                         dot(tilt, za) * rate};
  solve_block(block, a, b, bias, c.soft, use_bias, acc);
  c.linear_impulse = {acc[0], acc[1], acc[2]};
  c.angular_impulse = ya * acc[3] + za * acc[4];
}

}  // namespace

const JointOps kHingeOps = {prepare_hinge, warm_start_hinge, solve_hinge};

}  // namespace rwd::sim::d3
