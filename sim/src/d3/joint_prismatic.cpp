// SPDX-License-Identifier: MIT
// The prismatic joint: B slides along A's axis and does not turn relative
// to A. The block is five rows: the two across the axis that keep anchor
// B on the line through anchor A (A's lever arm reaches anchor B, since
// the axis turns with A) and the three of the orientation. Along the axis,
// measured from anchor A to anchor B: a spring, a motor and limits, each
// solved against the block held rigid.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

constexpr Vec3 kAxisX{1.0f, 0.0f, 0.0f};
constexpr Vec3 kAxisY{0.0f, 1.0f, 0.0f};
constexpr Vec3 kAxisZ{0.0f, 0.0f, 1.0f};

float axial_impulse(const JointConstraint& c) {
  return c.motor_impulse.x + c.spring_impulse.x + c.lower_impulse - c.upper_impulse;
}

void prepare_prismatic(const JointRecord&, JointConstraint& c, const SolverBody&,
                       const SolverBody&) {
  const Vec3 axis = rotate(c.frame_a, kAxisX);
  c.linear_impulse -= axis * dot(c.linear_impulse, axis);
}

void warm_start_prismatic(const JointRecord&, const JointConstraint& c, SolverBody& a,
                          SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 xa = rotate(f.fa, kAxisX);
  apply_linear(a, b, f.ra + f.d, f.rb, c.linear_impulse + xa * axial_impulse(c));
  apply_angular(a, b, c.angular_impulse);
}

void solve_prismatic(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                     bool use_bias) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 xa = rotate(f.fa, kAxisX);
  const Vec3 ya = rotate(f.fa, kAxisY);
  const Vec3 za = rotate(f.fa, kAxisZ);
  const Vec3 arm_a = f.ra + f.d;
  RowBlock block;
  block.add(linear_jacobian(ya, arm_a, f.rb));
  block.add(linear_jacobian(za, arm_a, f.rb));
  add_orientation_rows(block);
  block.factor(a, b);
  float acc[5] = {dot(c.linear_impulse, ya), dot(c.linear_impulse, za), c.angular_impulse.x,
                  c.angular_impulse.y, c.angular_impulse.z};
  const float translation = dot(f.d, xa);
  const JointRow slide = linear_jacobian(xa, arm_a, f.rb);
  if ((j.flags & kJointSpring) != 0) {
    solve_extra_row(block, a, b, slide, spring_terms(c.spring_soft, translation - j.spring_target),
                    0.0f, -kUnbounded, kUnbounded, c.spring_impulse.x, acc);
  }
  if ((j.flags & kJointMotor) != 0) {
    const float max = j.max_motor * c.h;
    solve_extra_row(block, a, b, slide, RowTerms{}, j.motor_speed, -max, max, c.motor_impulse.x,
                    acc);
  }
  if ((j.flags & kJointLimit) != 0) {
    solve_extra_row(block, a, b, slide, limit_terms(c.soft, translation - j.lower, c.h, use_bias),
                    0.0f, 0.0f, kUnbounded, c.lower_impulse, acc);
    solve_extra_row(block, a, b, linear_jacobian(-xa, arm_a, f.rb),
                    limit_terms(c.soft, j.upper - translation, c.h, use_bias), 0.0f, 0.0f,
                    kUnbounded, c.upper_impulse, acc);
  }
  const Vec3 turn = orientation_error(f);
  const float rate = c.soft.bias_rate;
  const float bias[5] = {dot(f.d, ya) * rate, dot(f.d, za) * rate, turn.x * rate, turn.y * rate,
                         turn.z * rate};
  solve_block(block, a, b, bias, c.soft, use_bias, acc);
  c.linear_impulse = ya * acc[0] + za * acc[1];
  c.angular_impulse = {acc[2], acc[3], acc[4]};
}

}  // namespace

const JointOps kPrismaticOps = {prepare_prismatic, warm_start_prismatic, solve_prismatic};

}  // namespace rwd::sim::d3
