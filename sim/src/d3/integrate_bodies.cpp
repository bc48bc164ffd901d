// SPDX-License-Identifier: MIT
// The substep's integration of the solver bodies (integrate_bodies.h).
#include "d3/integrate_bodies.h"

#include <cmath>

#include "d3/step_threads.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {
namespace {

// Speed limits keep one bad input from producing inf/NaN state: no body
// moves faster than this, or turns more than a quarter turn per substep.
constexpr float kMaxLinearSpeed = 400.0f;  // m/s
constexpr float kMaxRotationPerSubstep = 0.25f * kPi;

// Solver bodies per range when the integration is cut across the step's
// threads.
constexpr uint32_t kBodyGrain = 512;

// Calls fn(body) for every solver body but the shared immovable one, on
// the step's threads (each body is its own).
template <class Fn>
void for_solver_bodies(WorldScratch& scratch, Fn fn) {
  const uint32_t count = static_cast<uint32_t>(scratch.solver_bodies.size()) - 1;
  for_ranges(scratch, count, kBodyGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin + 1; i <= end; ++i) fn(scratch.solver_bodies[i]);
  });
}

}  // namespace

void integrate_velocities(WorldScratch& scratch, float h) {
  for_solver_bodies(scratch, [h](SolverBody& b) {
    if (b.inv_mass == 0.0f) return;  // kinematic: keeps its set velocity
    Vec3 v = b.linear_velocity * b.linear_damping_factor + b.linear_acceleration * h;
    Vec3 w = b.angular_velocity * b.angular_damping_factor;
    if (b.torqued) w += b.angular_acceleration * h;
    float speed_sq = length_squared(v);
    if (speed_sq > kMaxLinearSpeed * kMaxLinearSpeed) {
      v = v * (kMaxLinearSpeed / std::sqrt(speed_sq));
    }
    b.linear_velocity = v;
    b.angular_velocity = w;
  });
}

void integrate_positions(WorldScratch& scratch, float h) {
  const float max_w = kMaxRotationPerSubstep / h;
  for_solver_bodies(scratch, [h, max_w](SolverBody& b) {
    Vec3 w = b.angular_velocity;
    float w_sq = length_squared(w);
    if (w_sq > max_w * max_w) {
      w = w * (max_w / std::sqrt(w_sq));
      b.angular_velocity = w;
    }
    Vec3 v = b.linear_velocity;
    if (b.pushed != 0.0f) {
      v += b.push_linear;
      w += b.push_angular;
      w_sq = length_squared(w);
      if (w_sq > max_w * max_w) w = w * (max_w / std::sqrt(w_sq));
    }
    b.delta_position += v * h;
    b.delta_rotation = integrate_rotation(b.delta_rotation, w, h);
  });
}

}  // namespace rwd::sim::d3
