// SPDX-License-Identifier: MIT
#pragma once
// The joint stages of the soft step, beside the contact stages: prepare,
// warm start, solve (with or without the soft push-out) and, after the
// substeps, breaking. Impulses accumulate in the joint records themselves,
// which is what warm starts the next step.
#include "rewind/sim2d/world2d_state.h"
#include "step_scratch2d.h"

namespace rwd::sim2d::detail {

/// Context of one substep pass.
struct JointPass2D {
  W h = 0;
  W inv_h = 0;
  bool use_bias = true;
  /// Position integrations so far in this step: a pass with the same
  /// count sees the same rotations (solve_step2d.cpp).
  uint32_t positions = 0;
};

void prepare_joints(World2DState& state, StepScratch2D& scratch, W h);
void warm_start_joints(World2DState& state, StepScratch2D& scratch);
void solve_joints(World2DState& state, StepScratch2D& scratch, const JointPass2D& pass);
/// Breaks every joint whose impulse over the tick exceeded break_impulse.
void break_joints(World2DState& state, int substeps);

// One set of stages per joint type (joint_<type>2d.cpp).
void prepare_distance(const JointRecord2D& j, JointConstraint2D& c, const SolverBody2D& a,
                      const SolverBody2D& b);
void warm_start_distance(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                         SolverBody2D& b);
void solve_distance(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                    const JointPass2D& pass);
void prepare_revolute(JointConstraint2D& c, const SolverBody2D& a, const SolverBody2D& b);
void warm_start_revolute(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                         SolverBody2D& b);
void solve_revolute(JointRecord2D& j, JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                    const JointPass2D& pass);
void prepare_slider(const JointRecord2D& j, JointConstraint2D& c, const SolverBody2D& a,
                    const SolverBody2D& b);
void warm_start_slider(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                       SolverBody2D& b);
void solve_prismatic(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                     const JointPass2D& pass);
void solve_wheel(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                 const JointPass2D& pass);
void warm_start_weld(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a,
                     SolverBody2D& b);
void solve_weld(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& a, SolverBody2D& b,
                const JointPass2D& pass);
void warm_start_grab(const JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& b);
void solve_grab(JointRecord2D& j, const JointConstraint2D& c, SolverBody2D& b,
                const JointPass2D& pass);

}  // namespace rwd::sim2d::detail
