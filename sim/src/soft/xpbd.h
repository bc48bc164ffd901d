// SPDX-License-Identifier: MIT
#pragma once
// The particle solver's steps (XPBD: extended position-based dynamics,
// Macklin, Müller and Chentanez 2016), as plain functions over arrays of
// particles, so each can be checked alone and run over any range:
//   predict             x_prev = x; v += g dt; x += v dt (free particles)
//   solve_distance      one pass over links: each moves its two particles
//                       toward its rest length, softened by its compliance
//   update_velocities   v = (x - x_prev) / dt
// A substep is predict, `iterations` passes of the constraints (their
// multipliers zeroed first), then the velocity update.
//
// Units: metres, seconds, kilograms; compliance in metres per newton (the
// inverse of a stiffness; 0 = rigid). Determinism: only + - * / and sqrt,
// each written out, in the links' fixed order.
#include <cstdint>
#include <span>

#include "rewind/sim/math.h"
#include "soft/cloth_links.h"

namespace rwd::sim::soft {

/// Moves free particles (inverse mass > 0) by their velocity after adding
/// gravity; pinned ones (inverse mass 0) stay. Keeps the start in `previous`.
void predict(std::span<Vec3> position, std::span<Vec3> previous, std::span<Vec3> velocity,
             std::span<const float> inverse_mass, Vec3 gravity, float dt);

/// One Gauss-Seidel pass over `links` (in order), with their accumulated
/// multipliers `lambda` (one per link, zeroed at the start of a substep).
/// `compliance[kind]` is each kind's compliance in m/N; `dt` the substep.
void solve_distance(std::span<Vec3> position, std::span<const float> inverse_mass,
                    std::span<const DistanceLink> links, std::span<float> lambda,
                    const float (&compliance)[3], float dt);

/// The velocity each particle moved at over the substep.
void update_velocities(std::span<const Vec3> position, std::span<const Vec3> previous,
                       std::span<Vec3> velocity, float dt);

}  // namespace rwd::sim::soft
