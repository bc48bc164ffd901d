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

// The impulse about the hinge axis of its spring and motor.
float axial_impulse(const JointConstraint& c) {
  return c.motor_impulse.x + c.spring_impulse.x;
}

int hinge_rows(const JointRecord&, const JointFrames& f, JointRow* out) {
  point_rows(f, out);
  out[3] = angular_jacobian(rotate(f.fa, kAxisY));
  out[4] = angular_jacobian(rotate(f.fa, kAxisZ));
  return 5;
}

// The axes' misalignment: the rotation taking A's axis to B's.
Vec3 hinge_tilt(const JointRecord&, const JointFrames& f) {
  return cross(rotate(f.fa, kAxisX), rotate(f.fb, kAxisX));
}

// (The warm start follows the rows' refresh: the frames it kept hold.)
void warm_start_hinge(const JointRecord&, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  apply_angular(a, b, rotate(c.frames.fa, kAxisX) * axial_impulse(c));
}

// The angle range.
int hinge_limits(const JointRecord& j, const JointFrames& f, LimitRow* out) {
  if ((j.flags & kJointLimit) == 0) return 0;
  const Vec3 xa = rotate(f.fa, kAxisX);
  const float angle = twist_angle(conjugate(f.fa) * f.fb);
  out[0] = {angular_jacobian(xa), angle - j.lower, kRowLower};
  out[1] = {angular_jacobian(-xa), j.upper - angle, kRowUpper};
  return 2;
}

void hinge_extras(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                  const JointFrames& f, bool, const ExtraBase& base) {
  const Vec3 xa = rotate(f.fa, kAxisX);
  const float angle = twist_angle(conjugate(f.fa) * f.fb);
  const JointRow turn = angular_jacobian(xa);
  if ((j.flags & kJointSpring) != 0) {
    solve_extra_row(base, a, b, turn,
                    spring_terms(c.spring_soft, wrap_angle(angle - j.spring_target)), 0.0f,
                    -kUnbounded, kUnbounded, c.spring_impulse.x, kKeptAxis);
  }
  if ((j.flags & kJointMotor) != 0) {
    const float max = j.max_motor * c.h;
    solve_extra_row(base, a, b, turn, RowTerms{}, j.motor_speed, -max, max, c.motor_impulse.x,
                    kKeptAxis);
  }
}

}  // namespace

const JointOps kHingeOps = {nullptr,      hinge_rows,       hinge_tilt, hinge_limits,
                            hinge_extras, warm_start_hinge, nullptr};

}  // namespace rwd::sim::d3
