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

float axial_impulse(const JointConstraint& c) {
  return c.motor_impulse.x + c.spring_impulse.x;
}

int prismatic_rows(const JointRecord&, const JointFrames& f, JointRow* out) {
  const Vec3 arm_a = f.ra + f.d;
  out[0] = linear_jacobian(rotate(f.fa, kAxisY), arm_a, f.rb);
  out[1] = linear_jacobian(rotate(f.fa, kAxisZ), arm_a, f.rb);
  orientation_rows(out + 2);
  return 5;
}

Vec3 prismatic_turn(const JointRecord&, const JointFrames& f) {
  return orientation_error(f);
}

void warm_start_prismatic(const JointRecord&, const JointConstraint& c, SolverBody& a,
                          SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 xa = rotate(f.fa, kAxisX);
  apply_linear(a, b, f.ra + f.d, f.rb, xa * axial_impulse(c));
}

// The translation range.
int prismatic_limits(const JointRecord& j, const JointFrames& f, LimitRow* out) {
  if ((j.flags & kJointLimit) == 0) return 0;
  const Vec3 xa = rotate(f.fa, kAxisX);
  const Vec3 arm_a = f.ra + f.d;
  const float translation = dot(f.d, xa);
  out[0] = {linear_jacobian(xa, arm_a, f.rb), translation - j.lower, kRowLower};
  out[1] = {linear_jacobian(-xa, arm_a, f.rb), j.upper - translation, kRowUpper};
  return 2;
}

void prismatic_extras(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                      const JointFrames& f, bool, const ExtraBase& base) {
  const Vec3 xa = rotate(f.fa, kAxisX);
  const Vec3 arm_a = f.ra + f.d;
  const float translation = dot(f.d, xa);
  const JointRow slide = linear_jacobian(xa, arm_a, f.rb);
  if ((j.flags & kJointSpring) != 0) {
    solve_extra_row(base, a, b, slide, spring_terms(c.spring_soft, translation - j.spring_target),
                    0.0f, -kUnbounded, kUnbounded, c.spring_impulse.x, kKeptAxis);
  }
  if ((j.flags & kJointMotor) != 0) {
    const float max = j.max_motor * c.h;
    solve_extra_row(base, a, b, slide, RowTerms{}, j.motor_speed, -max, max, c.motor_impulse.x,
                    kKeptAxis);
  }
}

}  // namespace

const JointOps kPrismaticOps = {nullptr,          prismatic_rows,   prismatic_turn,
                                prismatic_limits, prismatic_extras, warm_start_prismatic,
                                nullptr};

}  // namespace rwd::sim::d3
