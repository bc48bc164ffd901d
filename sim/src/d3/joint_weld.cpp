// SPDX-License-Identifier: MIT
// The weld: B keeps the pose relative to A it had at creation. Rigid, its
// six rows are one block; a soft half (linear_hertz or angular_hertz set)
// is a spring in every pass, solved as its own three-row block, the
// orientation first so the point rows, which carry the load, end the pass.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

void prepare_weld(const JointRecord&, JointConstraint&, const SolverBody&, const SolverBody&) {}

void warm_start_weld(const JointRecord&, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  apply_linear(a, b, f.ra, f.rb, c.linear_impulse);
  apply_angular(a, b, c.angular_impulse);
}

void solve_half(RowBlock& block, SolverBody& a, SolverBody& b, Vec3 error,
                const JointSoftness& soft, bool use_bias, Vec3& impulse) {
  block.factor(a, b);
  float acc[3] = {impulse.x, impulse.y, impulse.z};
  const float bias[3] = {error.x * soft.bias_rate, error.y * soft.bias_rate,
                         error.z * soft.bias_rate};
  solve_block(block, a, b, bias, soft, use_bias, acc);
  impulse = {acc[0], acc[1], acc[2]};
}

void solve_weld(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                bool use_bias) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 turn = orientation_error(f);
  if (j.angular_hertz == 0.0f && j.linear_hertz == 0.0f) {
    RowBlock block;
    add_point_rows(block, f);
    add_orientation_rows(block);
    block.factor(a, b);
    float acc[6] = {c.linear_impulse.x,  c.linear_impulse.y,  c.linear_impulse.z,
                    c.angular_impulse.x, c.angular_impulse.y, c.angular_impulse.z};
    const float rate = c.soft.bias_rate;
    const float bias[6] = {f.d.x * rate,  f.d.y * rate,  f.d.z * rate,
                           turn.x * rate, turn.y * rate, turn.z * rate};
    solve_block(block, a, b, bias, c.soft, use_bias, acc);
    c.linear_impulse = {acc[0], acc[1], acc[2]};
    c.angular_impulse = {acc[3], acc[4], acc[5]};
    return;
  }
  // A soft half is a spring in every pass; a rigid one has the joint's
  // softness while solving and none while relaxing.
  RowBlock orientation;
  add_orientation_rows(orientation);
  const bool soft_turn = j.angular_hertz > 0.0f;
  solve_half(orientation, a, b, turn, soft_turn ? c.angular_soft : c.soft, soft_turn || use_bias,
             c.angular_impulse);
  RowBlock point;
  add_point_rows(point, f);
  const bool soft_point = j.linear_hertz > 0.0f;
  solve_half(point, a, b, f.d, soft_point ? c.spring_soft : c.soft, soft_point || use_bias,
             c.linear_impulse);
}

}  // namespace

const JointOps kWeldOps = {prepare_weld, warm_start_weld, solve_weld};

}  // namespace rwd::sim::d3
