// SPDX-License-Identifier: MIT
#include "rewind/fixed/trig.h"

#include <bit>
#include <cstdint>

#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {
namespace {

// CORDIC works in Q2.30: atan(2^-i) * 2^30 for i = 0..29, rounded to
// nearest (derived with 60-digit arithmetic). An entry off by one Fx ulp
// (2^-16 rad) breaks the unit tests' 1-ulp bounds on sin, cos and atan2;
// a smaller error that still changes any result bit changes the golden
// digest (tests/unit/fixed/golden_test.cpp).
constexpr int kIterations = 30;
constexpr int64_t kAtanTable[kIterations] = {
    843314857, 497837829, 263043837, 133525159, 67021687, 33543516, 16775851, 8388437,
    4194283,   2097149,   1048576,   524288,    262144,   131072,   65536,    32768,
    16384,     8192,      4096,      2048,      1024,     512,      256,      128,
    64,        32,        16,        8,         4,        2};
// 1 / prod(sqrt(1 + 2^-2i)) for 30 iterations, Q2.30: starting the rotation
// at this x makes the result come out unscaled.
constexpr int64_t kCordicGainInv = 652032874;
// pi in Q2.30, and pi, pi/2, 2*pi in Q32.32 (all rounded to nearest).
constexpr int64_t kPiQ30 = 3373259426;
constexpr int64_t kPiQ32 = 13493037705;
constexpr int64_t kHalfPiQ32 = 6746518852;
constexpr int64_t kTwoPiQ32 = 26986075409;

// radians reduced to (-pi, pi] in Q32.32. |raw| * 2^16 < 2^47 and the
// quotient is at most 5216, so the error of the 2*pi constant (2^-33) adds
// at most 6e-7 rad, well below an Fx ulp.
int64_t reduce_q32(Fx radians) {
  const int64_t a = static_cast<int64_t>(radians.raw()) * 65536;
  int64_t r = a % kTwoPiQ32;  // C++ truncates: r has the sign of a
  if (r < 0) r += kTwoPiQ32;  // [0, 2*pi)
  if (r > kPiQ32) r -= kTwoPiQ32;
  return r;
}

// x >> shift with the sign kept (arithmetic shift, defined since C++20).
constexpr int64_t asr(int64_t v, int shift) {
  return v >> shift;
}

// v when `mask` is 0, -v when it is -1 (all bits set): CORDIC's choice of
// direction without a branch, which the loops would mispredict about half
// the time. |v| stays far below 2^63 here.
constexpr int64_t negate_if(int64_t v, int64_t mask) {
  return (v ^ mask) - mask;
}

}  // namespace

SinCos sin_cos(Fx radians) {
  int64_t r = reduce_q32(radians);
  // Fold into [-pi/2, pi/2]: sin(pi - r) = sin r, cos(pi - r) = -cos r.
  bool negate_cos = false;
  if (r > kHalfPiQ32) {
    r = kPiQ32 - r;
    negate_cos = true;
  } else if (r < -kHalfPiQ32) {
    r = -kPiQ32 - r;
    negate_cos = true;
  }
  int64_t z = static_cast<int64_t>(shift_round(r, 2));  // Q2.30
  int64_t x = kCordicGainInv;
  int64_t y = 0;
  for (int i = 0; i < kIterations; ++i) {
    const int64_t dx = asr(y, i);
    const int64_t dy = asr(x, i);
    const int64_t m = asr(z, 63);  // z >= 0: turn toward it by atan 2^-i
    x -= negate_if(dx, m);
    y += negate_if(dy, m);
    z -= negate_if(kAtanTable[i], m);
  }
  Fx c = Fx::from_raw(saturate_i32(shift_round(x, 14)));
  const Fx s = Fx::from_raw(saturate_i32(shift_round(y, 14)));
  if (negate_cos) c = -c;
  return {s, c};
}

namespace {

// The angle of (vx, vy), neither zero, as Q2.30 radians in (-pi, pi]: the
// CORDIC vectoring both atan2 and vector_angle use. The larger magnitude
// is scaled into [2^40, 2^41) (left shifts are exact; inputs at or beyond
// 2^41 lose their lowest bits to right shifts); the CORDIC gain (< 1.65)
// and sqrt(2) then keep every value below 2^43.
int64_t cordic_angle_q30(int64_t vy, int64_t vx) {
  // Left half-plane: rotate by pi so x >= 0, and add the pi back at the end.
  int64_t offset = 0;
  if (vx < 0) {
    offset = vy >= 0 ? kPiQ30 : -kPiQ30;
    vx = -vx;
    vy = -vy;
  }
  const uint64_t big = magnitude(vx) > magnitude(vy) ? magnitude(vx) : magnitude(vy);
  // Into [2^40, 2^41): one shift either way (arithmetic right shifts
  // compose, so one shift by n equals n shifts by 1).
  const int width = std::bit_width(big);
  if (width > 41) {
    vx = asr(vx, width - 41);
    vy = asr(vy, width - 41);
  } else {
    vx *= int64_t{1} << (41 - width);
    vy *= int64_t{1} << (41 - width);
  }
  int64_t z = 0;  // Q2.30
  for (int i = 0; i < kIterations; ++i) {
    const int64_t dx = asr(vy, i);
    const int64_t dy = asr(vx, i);
    const int64_t m = asr(vy, 63);  // vy >= 0: turn down by atan 2^-i
    vx += negate_if(dx, m);
    vy -= negate_if(dy, m);
    z += negate_if(kAtanTable[i], m);
  }
  return z + offset;
}

}  // namespace

Fx atan2(Fx y, Fx x) {
  // The axes are answered exactly: CORDIC would leave a residue of a few
  // 2^-30 there, which could round differently from the documented values.
  if (y.raw() == 0) return x.raw() >= 0 ? Fx::zero() : Fx::pi();
  if (x.raw() == 0) return y.raw() > 0 ? Fx::half_pi() : -Fx::half_pi();
  return Fx::from_raw(saturate_i32(shift_round(cordic_angle_q30(y.raw(), x.raw()), 14)));
}

FxWide vector_angle(int64_t y, int64_t x) {
  if (y == 0) return FxWide::from_raw(x >= 0 ? 0 : kPiQ32);
  if (x == 0) return FxWide::from_raw(y > 0 ? kHalfPiQ32 : -kHalfPiQ32);
  if (y == INT64_MIN || x == INT64_MIN) return vector_angle(y / 2, x / 2);
  return FxWide::from_raw(cordic_angle_q30(y, x) * 4);
}

Fx normalize_angle(Fx radians) {
  if (radians > -Fx::pi() && radians < Fx::pi()) return radians;
  return Fx::from_raw(saturate_i32(shift_round(reduce_q32(radians), 16)));
}

}  // namespace rwd::fixed
