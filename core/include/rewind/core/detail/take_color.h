// SPDX-License-Identifier: MIT
#pragma once
// Greedy colouring of constraints by the bodies they move, shared by both
// lanes' solvers (3D contacts and point joints, 2D joints), as Box2D v3's
// constraint graph: each constraint in turn takes the first colour in which
// neither body it can move already has a constraint. A colour's
// constraints then share no moving body, so solving them in any order (or
// side by side in lanes) gives the same result. The colours depend only on
// the order of the constraints, never on the lane count or the instruction
// set. Working memory only: not part of any state.
#include <cstddef>
#include <cstdint>

namespace rwd::detail {

/// The first of `colors` colours in which neither body a nor b (each only
/// if it moves) is taken yet, marking them taken in it; `colors` when every
/// colour has one of them. `bits` holds `colors` runs of `words` words, one
/// bit per body (all zero before the first constraint).
inline uint32_t take_color(uint64_t* bits, size_t words, uint32_t colors, uint32_t a, bool moves_a,
                           uint32_t b, bool moves_b) {
  for (uint32_t col = 0; col < colors; ++col) {
    uint64_t* run = bits + col * words;
    const bool used_a = moves_a && (run[a / 64] >> (a % 64) & 1u) != 0;
    const bool used_b = moves_b && (run[b / 64] >> (b % 64) & 1u) != 0;
    if (used_a || used_b) continue;
    if (moves_a) run[a / 64] |= uint64_t{1} << (a % 64);
    if (moves_b) run[b / 64] |= uint64_t{1} << (b % 64);
    return col;
  }
  return colors;
}

}  // namespace rwd::detail
