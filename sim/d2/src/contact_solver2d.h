// SPDX-License-Identifier: MIT
#pragma once
// The contact stages of the soft step (solver stages, DESIGN 6a): prepare,
// warm start, solve (with or without the soft push-out), restitution and
// store. Joints will plug in beside them with the same stages.
#include "rewind/sim2d/world2d_state.h"
#include "step_scratch2d.h"

namespace rwd::sim2d::detail {

/// The soft constraint of a spring of `hertz` and damping `zeta` for a
/// substep of `h` seconds; hertz 0 gives a rigid constraint.
Softness2D make_softness(W hertz, W zeta, W h);

/// Builds scratch.constraints from the touching contacts, in the order
/// every pass solves them.
void prepare_contacts(const World2DState& state, StepScratch2D& scratch, W h);
void warm_start_contacts(StepScratch2D& scratch);
/// One pass over every contact. With `use_bias` overlaps are pushed apart
/// softly; without (relax), only speculative gaps and velocities count.
void solve_contacts(StepScratch2D& scratch, W inv_h, W push_max, bool use_bias);
void apply_restitution(StepScratch2D& scratch, W threshold);
void store_impulses(World2DState& state, const StepScratch2D& scratch);

}  // namespace rwd::sim2d::detail
