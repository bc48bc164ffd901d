// SPDX-License-Identifier: MIT
#pragma once
// The solver's view of a body (contact_solver.cpp, the joints, the lanes).
#include <cstddef>

#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// A body as the solver sees it: velocities and the pose change since the
/// start of the step. Index 0 is a shared immovable body standing in for
/// every static or sleeping body.
///
/// The solver's lanes gather and scatter bodies as aligned rows of eight
/// floats with a few vector loads and a transpose (contact_lanes.h): the
/// velocities row, the push-out row, then the inverse inertia.
struct alignas(32) SolverBody {
  // Row 0: the real velocities.
  Vec3 linear_velocity;
  Vec3 angular_velocity;
  float inv_mass;
  float angular_damping_factor;
  // Row 1: the push-out. Push velocities move the body out of overlaps
  // during the tick's substeps and are then dropped, so recovering from an
  // overlap never becomes real velocity (a split impulse).
  Vec3 push_linear;
  Vec3 push_angular;
  float push_inv_mass;  ///< inv_mass again, so the push row is self-contained
  float pushed;         ///< 1 once push velocities are set this tick, else 0
  Mat3 inv_inertia;     ///< world frame, fixed for the step
  Vec3 delta_position;
  Quat delta_rotation;
  Vec3 linear_acceleration;     ///< gravity plus applied force, m/s^2
  float linear_damping_factor;  ///< 1 / (1 + h * damping), per substep
  /// Applied torque through the (locked) inverse inertia, rad/s^2; used
  /// only when `torqued`, so bodies without a torque are integrated as if
  /// the term did not exist.
  Vec3 angular_acceleration;
  bool torqued;
  /// An acting joint holds the body this tick: its velocity is the
  /// joint's answer, so the free body's gyroscopic carry is not applied.
  bool jointed;
  /// A contact of this tick acts on the body (the joints are solved again
  /// after the contacts only where one does).
  bool contacted;
};
static_assert(offsetof(SolverBody, angular_velocity) == 3 * sizeof(float) &&
                  offsetof(SolverBody, inv_mass) == 6 * sizeof(float) &&
                  offsetof(SolverBody, angular_damping_factor) == 7 * sizeof(float) &&
                  offsetof(SolverBody, push_linear) == 8 * sizeof(float) &&
                  offsetof(SolverBody, push_angular) == 11 * sizeof(float) &&
                  offsetof(SolverBody, push_inv_mass) == 14 * sizeof(float) &&
                  offsetof(SolverBody, pushed) == 15 * sizeof(float) &&
                  offsetof(SolverBody, inv_inertia) == 16 * sizeof(float),
              "the solver's lanes read a body as rows of eight floats");

}  // namespace rwd::sim::d3
