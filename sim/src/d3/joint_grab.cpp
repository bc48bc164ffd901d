// SPDX-License-Identifier: MIT
// The grab joint: body B's anchor pulled toward a world target by a spring
// (the joint's hertz and damping ratio) through a point block, the pull's
// accumulated impulse capped at max_force per unit time, so a grabbed body
// can be dragged but never launched. A is the world: the target stands in
// for its anchor.
#include <cmath>

#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

void warm_start_grab(const JointRecord&, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  apply_linear(a, b, f.ra, f.rb, c.linear_impulse);
}

void solve_grab(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b, bool) {
  const JointFrames f = joint_frames(c, a, b);
  RowBlock block;
  JointRow rows[3];
  point_rows(f, rows);
  for (const JointRow& r : rows) block.add(r);
  block.factor(a, b);
  const JointSoftness& s = c.spring_soft;
  float rhs[3];
  for (int i = 0; i < 3; ++i) rhs[i] = block.velocity(i, a, b) + component(f.d, i) * s.bias_rate;
  float x[3];
  block.solve(rhs, x);
  const Vec3 old = c.linear_impulse;
  Vec3 next = old - Vec3{x[0], x[1], x[2]} * s.mass_scale - old * s.impulse_scale;
  const float max = j.max_force * c.h;
  const float len_sq = length_squared(next);
  if (len_sq > max * max) next = next * (max / std::sqrt(len_sq));
  c.linear_impulse = next;
  const Vec3 d = next - old;
  const float delta[3] = {d.x, d.y, d.z};
  block.apply(a, b, delta);
}

}  // namespace

const JointOps kGrabOps = {nullptr, nullptr,         nullptr,   nullptr,
                           nullptr, warm_start_grab, solve_grab};

}  // namespace rwd::sim::d3
