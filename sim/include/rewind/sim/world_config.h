// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/math.h"

namespace rwd::sim {

/// The longest substep a world accepts, seconds (1/240 s: 4 substeps of a
/// 60 Hz tick, 8 of a 30 Hz one). WorldConfig::substeps says why.
inline constexpr float kMaxSubstepSeconds = 1.0f / 240.0f;

/// Tuning of the 3D world. Part of world state (a restored world steps with
/// the configuration it was saved with) and of the checksum.
struct WorldConfig {
  Vec3 gravity{0.0f, -9.81f, 0.0f};   ///< m/s^2
  float tick_seconds = 1.0f / 60.0f;  ///< length of one step(), (0, 0.1]
  /// TGS-Soft substeps per tick, [1, 64], each at most kMaxSubstepSeconds
  /// long (tick_seconds / substeps; a longer one is refused: at 60 Hz
  /// ticks, 4 substeps or more). Longer substeps fail the stability
  /// scenes: at 1/120 s with one contact pass a substep, box pyramids of
  /// base 20 and 30 fall apart within 10 s and the three-level card house
  /// falls at 1/180 s; three passes hold those, but the 30 x 30 joint grid
  /// still opens by 0.99 m (2.16 m with one pass; 0.04 m at 1/240 s), a
  /// 1:100 mass ratio sinks 10.5 mm and a bounce falls 8% short of its
  /// apex. Three passes also cost what the fourth substep does, so nothing
  /// is saved (tests/stability/stability3d_substeps.cpp holds the accepted
  /// lengths; docs/BENCHMARKS.md the joint sweep).
  int32_t substeps = 4;
  int32_t relax_iterations = 1;  ///< rigid contact passes after each substep's move, [0, 16]
  /// The push-out of overlaps deeper than the slop acts as a spring-damper
  /// of this frequency (Hz, > 0; at most a quarter of the substep rate, twice
  /// that against static bodies) and damping ratio (>= 0): it separates at
  /// 2 pi hertz / (2 ratio + 2 pi hertz h) per second times the overlap. It
  /// moves bodies apart without giving them velocity.
  float contact_hertz = 30.0f;
  float contact_damping_ratio = 1.0f;
  float contact_push_max_mps = 3.0f;       ///< cap on the push-out speed per contact, m/s
  float restitution_threshold_mps = 1.0f;  ///< no bounce below this approach speed
  float linear_slop_m = 0.005f;            ///< allowed penetration, m
  float speculative_distance_m = 0.02f;    ///< contacts are kept this far apart, m
  bool enable_sleep = true;
  /// A body rests through each half of time_to_sleep_s in which no point
  /// of it strays more than sleep_threshold_mps times that half from where
  /// the half began (its average speed stays below the threshold: a body
  /// trembling in place or creeping slower rests, one going somewhere
  /// starts over). An island sleeps once every body in it has rested for
  /// time_to_sleep_s.
  float sleep_threshold_mps = 0.05f;  ///< m/s
  float time_to_sleep_s = 0.5f;       ///< seconds within the threshold before sleeping
  uint32_t max_bodies = 4096;         ///< create_body refuses beyond this
  /// The box body centres may occupy, metres (each component in
  /// [-1e5, 1e5], lower < upper). Bodies cannot be created or placed
  /// outside it; a moving body whose centre leaves it during a step is
  /// disabled where it crossed (clamped onto the box, velocities zeroed) and
  /// reported once by a BodyEvent of type kLeftBounds. The default keeps
  /// float32 resolution near 0.5 mm at the edge.
  Vec3 bounds_lower{-5000.0f, -5000.0f, -5000.0f};
  Vec3 bounds_upper{5000.0f, 5000.0f, 5000.0f};
};

}  // namespace rwd::sim
