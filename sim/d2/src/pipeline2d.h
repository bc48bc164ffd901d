// SPDX-License-Identifier: MIT
#pragma once
// The stages of one 2D step, in the order World2D::step() runs them.
#include "rewind/sim2d/world2d.h"
#include "step_scratch2d.h"

namespace rwd::sim2d::detail {

/// Sort and sweep over the bodies' bounds (grown by half the speculative
/// distance): scratch.pairs gets every pair with a dynamic body whose
/// layers agree, sorted by (a, b).
void find_pairs(const World2DState& state, StepScratch2D& scratch);

/// Rebuilds state.contacts from scratch.pairs: a manifold per pair, each
/// point keeping the impulses of the point with the same feature id last
/// step (warm starting). Pairs without points are dropped.
void update_contacts(World2DState& state, StepScratch2D& scratch);

/// The soft-step solve of the contacts: substeps of integrate velocities,
/// warm start, solve, integrate positions and relax, then restitution;
/// impulses are stored back into state.contacts for the next step.
void solve_step(World2DState& state, StepScratch2D& scratch, StepStats2D& stats);

}  // namespace rwd::sim2d::detail
