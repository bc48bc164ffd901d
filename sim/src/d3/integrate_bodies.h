// SPDX-License-Identifier: MIT
#pragma once
// A substep's integration of the solver bodies (contact_solver.cpp's
// "integrate velocities" and "integrate positions"), cut across the step's
// threads for large worlds: each body is its own, so the result is the same
// on any number of threads.
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

/// Velocities after gravity, forces and damping over a substep of h
/// seconds; linear speed capped at 400 m/s. Kinematic bodies keep theirs.
void integrate_velocities(WorldScratch& scratch, float h);

/// Each body's motion since the tick began advanced by a substep of h
/// seconds at its real plus push velocities; turning capped at a quarter
/// turn per substep.
void integrate_positions(WorldScratch& scratch, float h);

}  // namespace rwd::sim::d3
