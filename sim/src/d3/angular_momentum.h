// SPDX-License-Identifier: MIT
#pragma once
// The gyroscopic term of a free body over one tick (angular_momentum.cpp).
#include "rewind/sim/math.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// A body's angular velocity and orientation at the end of a tick.
struct Spin {
  Vec3 angular_velocity;  ///< rad/s, world frame
  Quat rotation;
};

/// Carries the angular momentum a body had at orientation `q0` with angular
/// velocity `w` over its turn to `q1` during a tick of `tick` seconds:
/// returns the velocity and a corrected orientation (turned by the mean of
/// the tick's start and end rates) that keep |L| and the kinetic energy of
/// rotation.
Spin carry_angular_momentum(const BodyMass& mass, Quat q0, Quat q1, Vec3 w, float tick);

}  // namespace rwd::sim::d3
