// SPDX-License-Identifier: MIT
// Distance and spring joints: rows along the line between the anchors,
// solved one by one (no block: a distance joint leaves every other motion
// free). A distance joint holds the length in [min_length, max_length]
// (one two-sided row when they are equal, one-sided rows otherwise: a
// rope has only the upper); a spring pulls toward its rest length in every
// pass, within the range when it has one. The reaction along the line is
// kept as a vector (linear_impulse) for breaking and reports.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

bool rigid(const JointRecord& j) {
  return j.type == JointType::kDistance && j.min_length == j.max_length;
}
bool ranged(const JointRecord& j) {
  return j.type == JointType::kDistance || (j.flags & kJointLimit) != 0;
}

float line_impulse(const JointConstraint& c) {
  return c.axial_impulse + c.spring_impulse.x + c.lower_impulse - c.upper_impulse;
}

void warm_start_distance(const JointRecord&, const JointConstraint& c, SolverBody& a,
                         SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 n = normalize_or_zero(f.d);
  apply_linear(a, b, f.ra, f.rb, n * line_impulse(c));
}

void solve_distance(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                    bool use_bias) {
  const JointFrames f = joint_frames(c, a, b);
  const float len = length(f.d);
  // Anchors on top of each other have no line to act along.
  if (!(len > 1e-6f)) return;
  const Vec3 n = f.d * (1.0f / len);
  // Nothing held rigid: each row on its own effective mass.
  const RowBlock none;
  ExtraBase base;
  base.block = &none;
  const JointRow line = linear_jacobian(n, f.ra, f.rb);
  if (j.type == JointType::kSpring) {
    solve_extra_row(base, a, b, line, spring_terms(c.spring_soft, len - j.length), 0.0f,
                    -kUnbounded, kUnbounded, c.spring_impulse.x, kKeptAxis);
  }
  if (rigid(j)) {
    solve_extra_row(base, a, b, line, structural_terms(c.soft, len - j.min_length, use_bias), 0.0f,
                    -kUnbounded, kUnbounded, c.axial_impulse, kKeptAxis);
  } else if (ranged(j)) {
    if (j.min_length > 0.0f) {
      solve_extra_row(base, a, b, line, limit_terms(c.soft, len - j.min_length, c.h, use_bias),
                      0.0f, 0.0f, kUnbounded, c.lower_impulse, kRowLower);
    }
    solve_extra_row(base, a, b, linear_jacobian(-n, f.ra, f.rb),
                    limit_terms(c.soft, j.max_length - len, c.h, use_bias), 0.0f, 0.0f, kUnbounded,
                    c.upper_impulse, kRowUpper);
  }
  c.linear_impulse = n * line_impulse(c);
}

}  // namespace

const JointOps kDistanceOps = {
    nullptr, nullptr, nullptr, nullptr, nullptr, warm_start_distance, solve_distance};

}  // namespace rwd::sim::d3
