// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/core/build_checks.h"

// Rewind's own transcendental functions. The C library's sin/cos/atan2 differ
// between libm versions and architectures; these are polynomials built from
// + - * / and sqrt only, so they give the same bits everywhere.
namespace rwd {

/// Sine of x radians. Range-reduced to [-pi/4, pi/4]; |error| < 2e-7 for |x| < 1e5.
float det_sin(float x);
/// Cosine of x radians, same accuracy as det_sin.
float det_cos(float x);
/// Angle of (x, y) in radians, in [-pi, pi]; atan2(0, 0) = 0.
float det_atan2(float y, float x);
/// Arc cosine of x clamped to [-1, 1], in [0, pi].
float det_acos(float x);
/// e^x; clamps to avoid overflow.
float det_exp(float x);

inline constexpr float kPi = 3.14159265358979323846f;

}  // namespace rwd
