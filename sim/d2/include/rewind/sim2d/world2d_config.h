// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/vec2.h"

namespace rwd::sim2d {

using fixed::Fx;
using fixed::Vec2;
using namespace rwd::fixed::literals;

/// Tuning of the 2D world. Part of the world state (a restored world steps
/// with the configuration it was saved with) and of the checksum. Every
/// value is checked by World2D::validate_config().
struct World2DConfig {
  Vec2 gravity{Fx(), -10_fx};  ///< m/s^2
  int32_t tick_hz = 60;        ///< steps per second, [1, 1000]
  /// Soft-step substeps per tick, [1, 32], each at most 1/240 s long
  /// (tick_hz * substeps >= 240, so 4 or more at 60 Hz; fewer are
  /// refused): at 1/180 s a 40 x 40 grid of revolute joints stretches 5 m
  /// and at 1/120 s 29 m, where 1/240 s holds it within 3.4 cm, and at 1/60
  /// s a base-100 box pyramid falls.
  int32_t substeps = 4;
  int32_t relax_iterations = 1;  ///< rigid contact passes after each substep's move, [0, 8]
  /// Overlaps deeper than the slop are pushed apart by a spring-damper of
  /// this frequency (Hz, (0, 1000]; at most a quarter of the substep rate,
  /// twice that against static bodies) and damping ratio ([0, 100]). It
  /// moves bodies apart without leaving them velocity.
  Fx contact_hertz = 30_fx;
  Fx contact_damping_ratio = 10_fx;
  /// Joints push their errors out with a spring of twice the contact
  /// hertz and this damping ratio ([0, 100]).
  Fx joint_damping_ratio = 2_fx;
  Fx contact_push_max = 3_fx;         ///< m/s, cap on the push-out speed, (0, 1000]
  Fx restitution_threshold = 1_fx;    ///< m/s, no bounce below this approach speed, [0, 1000]
  Fx linear_slop = 0.005_fx;          ///< m, allowed penetration, [0, 1]
  Fx speculative_distance = 0.02_fx;  ///< m, contacts are kept this far apart, (0, 10]
  Fx max_linear_speed = 400_fx;       ///< m/s, every body's speed is capped here, (0, 10000]
  /// Islands of touching or joined bodies that all stay slower than
  /// sleep_threshold (m/s at the centre and at the body's rim, [0, 100])
  /// for time_to_sleep (s, (0, 100]) sleep until something wakes them.
  bool enable_sleep = true;
  Fx sleep_threshold = 0.05_fx;
  Fx time_to_sleep = 0.5_fx;
  uint32_t max_bodies = 8192;  ///< create_body refuses beyond this, [1, 1 << 20]
  /// The box body centres may occupy (m, lower < upper). A moving body
  /// whose centre of mass leaves it is disabled where it crossed (clamped
  /// onto the box, velocities zeroed; is_enabled() turns false and its
  /// contacts end with exit events).
  Vec2 bounds_lower{-32000_fx, -32000_fx};
  Vec2 bounds_upper{32000_fx, 32000_fx};
};

}  // namespace rwd::sim2d
