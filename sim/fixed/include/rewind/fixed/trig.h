// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_wide.h"

namespace rwd::fixed {

/// Sine and cosine of one angle, each in [-1, 1].
struct SinCos {
  Fx sin;
  Fx cos;
};

/// sin and cos of `radians` (any Fx value), computed with integer CORDIC
/// (30 iterations in Q2.30) after an exact-enough reduction modulo 2*pi
/// (2*pi held to 2^-32). Each result is within 1 ulp (2^-16) of the true
/// sine/cosine of the exact input over the whole Fx range; the tests check
/// this bound over the full circle and at the range edges.
SinCos sin_cos(Fx radians);
inline Fx sin(Fx radians) {
  return sin_cos(radians).sin;
}
inline Fx cos(Fx radians) {
  return sin_cos(radians).cos;
}

/// The angle of the vector (x, y) in radians, in [-pi(), pi()], within 1 ulp
/// of the true value; quadrant-correct for every sign combination. Exact
/// special cases: atan2(0, 0) = 0; atan2(0, x > 0) = 0; atan2(0, x < 0) =
/// +pi() (never -pi()); atan2(y > 0, 0) = half_pi(); atan2(y < 0, 0) =
/// -half_pi(). Integer CORDIC vectoring; the inputs are scaled to 41 bits
/// first, so small vectors are as accurate as large ones.
Fx atan2(Fx y, Fx x);

/// The angle of the vector (x, y) as Q32.32 radians in [-pi, pi], for
/// components of any one integer scale (raw Q16.16, Q32.32 or whole
/// numbers): the same CORDIC as atan2, kept to its 2^-30 working precision
/// instead of rounded to an Fx ulp, for callers that need angles finer
/// than 2^-16 (the 2D lane's joint angles). Exact on the axes; (0, 0)
/// gives 0. Components of 2^41 or more lose their lowest bits first.
FxWide vector_angle(int64_t y, int64_t x);

/// `radians` reduced to [-pi(), pi()], within 1 ulp of the exact reduction
/// (2*pi is held to 2^-32 during it). Angles already in (-pi(), pi()) are
/// returned unchanged.
Fx normalize_angle(Fx radians);

}  // namespace rwd::fixed
