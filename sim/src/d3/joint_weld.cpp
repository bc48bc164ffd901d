// SPDX-License-Identifier: MIT
// The weld: B keeps the pose relative to A it had at creation. Rigid, its
// six rows are its structure; a soft half (linear_hertz or angular_hertz
// set) is a spring in every pass, and a soft weld solves its two halves as
// three-row blocks of their own.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

bool rigid(const JointRecord& j) {
  return j.angular_hertz == 0.0f && j.linear_hertz == 0.0f;
}

// A rigid weld's structure is all six rows; a soft one solves itself.
int weld_rows(const JointRecord& j, const JointFrames& f, JointRow* out) {
  if (!rigid(j)) return 0;
  point_rows(f, out);
  orientation_rows(out + 3);
  return 6;
}

Vec3 weld_turn(const JointRecord&, const JointFrames& f) {
  return orientation_error(f);
}

void warm_start_weld(const JointRecord& j, const JointConstraint& c, SolverBody& a, SolverBody& b) {
  if (rigid(j)) return;  // all structure, warm started by the stage
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

// A soft weld: a soft half is a spring in every pass; a rigid one has the
// joint's softness while solving and none while relaxing. Orientation
// first, so the point rows, which carry the load, end the pass.
void solve_soft_weld(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                     bool use_bias) {
  const JointFrames f = joint_frames(c, a, b);
  JointRow rows[3];
  RowBlock orientation;
  orientation_rows(rows);
  for (const JointRow& r : rows) orientation.add(r);
  const bool soft_turn = j.angular_hertz > 0.0f;
  solve_half(orientation, a, b, orientation_error(f), soft_turn ? c.angular_soft : c.soft,
             soft_turn || use_bias, c.angular_impulse);
  RowBlock point;
  point_rows(f, rows);
  for (const JointRow& r : rows) point.add(r);
  const bool soft_point = j.linear_hertz > 0.0f;
  solve_half(point, a, b, f.d, soft_point ? c.spring_soft : c.soft, soft_point || use_bias,
             c.linear_impulse);
}

}  // namespace

const JointOps kWeldOps = {nullptr, weld_rows,       weld_turn,      nullptr,
                           nullptr, warm_start_weld, solve_soft_weld};

}  // namespace rwd::sim::d3
