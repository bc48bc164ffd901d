// SPDX-License-Identifier: MIT
#pragma once
// det_atan2 (det_math.h) on kLanes floats at once, bit for bit what it
// computes on each: the engine's atan2 works in IEEE double with + - * /
// alone and rounds once to float, so its lanes are doubles too (two
// double vectors per four floats on SSE2 and NEON, plain doubles with
// REWIND_SCALAR_LANES), with the same operations in the same order. Its
// branches are compare-and-select: both sides computed, one kept (a side
// not kept may divide by zero; no lane keeps it). Negation is a product
// by -1, which flips the sign of a zero as the scalar minus does. No
// native min/max, no fused multiply-add, no estimates.
#include "d3/wide_float.h"

namespace rwd::sim::d3 {
namespace lane_atan2_detail {

#if defined(REWIND_LANES_SSE2)

struct D {
  __m128d lo, hi;  // lanes 0, 1 and 2, 3
};
struct M {
  __m128d lo, hi;
};
inline D dsplat(double x) {
  return {_mm_set1_pd(x), _mm_set1_pd(x)};
}
inline D widen(FloatW f) {
  return {_mm_cvtps_pd(f.v), _mm_cvtps_pd(_mm_movehl_ps(f.v, f.v))};
}
inline FloatW narrow(D d) {
  return {_mm_movelh_ps(_mm_cvtpd_ps(d.lo), _mm_cvtpd_ps(d.hi))};
}
inline D operator+(D a, D b) {
  return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)};
}
inline D operator-(D a, D b) {
  return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)};
}
inline D operator*(D a, D b) {
  return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)};
}
inline D operator/(D a, D b) {
  return {_mm_div_pd(a.lo, b.lo), _mm_div_pd(a.hi, b.hi)};
}
inline M operator<(D a, D b) {
  return {_mm_cmplt_pd(a.lo, b.lo), _mm_cmplt_pd(a.hi, b.hi)};
}
inline M operator<=(D a, D b) {
  return {_mm_cmple_pd(a.lo, b.lo), _mm_cmple_pd(a.hi, b.hi)};
}
inline M operator>(D a, D b) {
  return {_mm_cmpgt_pd(a.lo, b.lo), _mm_cmpgt_pd(a.hi, b.hi)};
}
inline M operator==(D a, D b) {
  return {_mm_cmpeq_pd(a.lo, b.lo), _mm_cmpeq_pd(a.hi, b.hi)};
}
inline M operator&(M a, M b) {
  return {_mm_and_pd(a.lo, b.lo), _mm_and_pd(a.hi, b.hi)};
}
inline D select(M m, D a, D b) {
  return {_mm_or_pd(_mm_and_pd(m.lo, a.lo), _mm_andnot_pd(m.lo, b.lo)),
          _mm_or_pd(_mm_and_pd(m.hi, a.hi), _mm_andnot_pd(m.hi, b.hi))};
}

#elif defined(REWIND_LANES_NEON)

struct D {
  float64x2_t lo, hi;
};
struct M {
  uint64x2_t lo, hi;
};
inline D dsplat(double x) {
  return {vdupq_n_f64(x), vdupq_n_f64(x)};
}
inline D widen(FloatW f) {
  return {vcvt_f64_f32(vget_low_f32(f.v)), vcvt_high_f64_f32(f.v)};
}
inline FloatW narrow(D d) {
  return {vcvt_high_f32_f64(vcvt_f32_f64(d.lo), d.hi)};
}
inline D operator+(D a, D b) {
  return {vaddq_f64(a.lo, b.lo), vaddq_f64(a.hi, b.hi)};
}
inline D operator-(D a, D b) {
  return {vsubq_f64(a.lo, b.lo), vsubq_f64(a.hi, b.hi)};
}
inline D operator*(D a, D b) {
  return {vmulq_f64(a.lo, b.lo), vmulq_f64(a.hi, b.hi)};
}
inline D operator/(D a, D b) {
  return {vdivq_f64(a.lo, b.lo), vdivq_f64(a.hi, b.hi)};
}
inline M operator<(D a, D b) {
  return {vcltq_f64(a.lo, b.lo), vcltq_f64(a.hi, b.hi)};
}
inline M operator<=(D a, D b) {
  return {vcleq_f64(a.lo, b.lo), vcleq_f64(a.hi, b.hi)};
}
inline M operator>(D a, D b) {
  return {vcgtq_f64(a.lo, b.lo), vcgtq_f64(a.hi, b.hi)};
}
inline M operator==(D a, D b) {
  return {vceqq_f64(a.lo, b.lo), vceqq_f64(a.hi, b.hi)};
}
inline M operator&(M a, M b) {
  return {vandq_u64(a.lo, b.lo), vandq_u64(a.hi, b.hi)};
}
inline D select(M m, D a, D b) {
  return {vbslq_f64(m.lo, a.lo, b.lo), vbslq_f64(m.hi, a.hi, b.hi)};
}

#else

struct D {
  double v[kLanes];
};
struct M {
  bool v[kLanes];
};
inline D dsplat(double x) {
  D r;
  for (double& e : r.v) e = x;
  return r;
}
inline D widen(FloatW f) {
  alignas(16) float in[kLanes];
  store(in, f);
  D r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = static_cast<double>(in[i]);
  return r;
}
inline FloatW narrow(D d) {
  alignas(16) float out[kLanes];
  for (int i = 0; i < kLanes; ++i) out[i] = static_cast<float>(d.v[i]);
  return load(out);
}
#define REWIND_DOUBLE_LANEWISE(T, op)                         \
  T r;                                                        \
  for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] op b.v[i]; \
  return r
inline D operator+(D a, D b) {
  REWIND_DOUBLE_LANEWISE(D, +);
}
inline D operator-(D a, D b) {
  REWIND_DOUBLE_LANEWISE(D, -);
}
inline D operator*(D a, D b) {
  REWIND_DOUBLE_LANEWISE(D, *);
}
inline D operator/(D a, D b) {
  REWIND_DOUBLE_LANEWISE(D, /);
}
inline M operator<(D a, D b) {
  REWIND_DOUBLE_LANEWISE(M, <);
}
inline M operator<=(D a, D b) {
  REWIND_DOUBLE_LANEWISE(M, <=);
}
inline M operator>(D a, D b) {
  REWIND_DOUBLE_LANEWISE(M, >);
}
inline M operator==(D a, D b) {
  REWIND_DOUBLE_LANEWISE(M, ==);
}
inline M operator&(M a, M b) {
  REWIND_DOUBLE_LANEWISE(M, &&);
}
#undef REWIND_DOUBLE_LANEWISE
inline D select(M m, D a, D b) {
  D r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = m.v[i] ? a.v[i] : b.v[i];
  return r;
}

#endif

// atan_unit of det_math.cpp: atan on [0, 1], shifted by pi/4 above
// 0.4142 (the tangent of pi/8), the series in Estrin's order.
inline D atan_unit(D t) {
  const D one = dsplat(1.0);
  const M shift = t > dsplat(0.41421356237309503);
  const D offset = select(shift, dsplat(7.85398163397448278999e-01), dsplat(0.0));
  t = select(shift, (t - one) / (t + one), t);
  const D t2 = t * t;
  const D t4 = t2 * t2;
  const D t8 = t4 * t4;
  const D q0 = dsplat(-1.0 / 3.0) + t2 * dsplat(1.0 / 5.0);
  const D q1 = dsplat(-1.0 / 7.0) + t2 * dsplat(1.0 / 9.0);
  const D q2 = dsplat(-1.0 / 11.0) + t2 * dsplat(1.0 / 13.0);
  const D q3 = dsplat(-1.0 / 15.0) + t2 * dsplat(1.0 / 17.0);
  const D q4 = dsplat(-1.0 / 19.0) + t2 * dsplat(1.0 / 21.0);
  const D r0 = q0 + t4 * q1;
  const D r1 = q2 + t4 * q3;
  const D p = (r0 + t8 * r1) + (t8 * t8) * q4;
  return (offset + t) + (t * t2) * p;
}

}  // namespace lane_atan2_detail

/// det_atan2(y, x) lane by lane, bit for bit.
inline FloatW det_atan2_lanes(FloatW yf, FloatW xf) {
  using namespace lane_atan2_detail;
  const D y = widen(yf);
  const D x = widen(xf);
  const D zero = dsplat(0.0);
  const D minus = dsplat(-1.0);
  const D ax = select(x < zero, x * minus, x);
  const D ay = select(y < zero, y * minus, y);
  const M low = ay <= ax;
  // One quotient, the side the lane takes (atan_unit(ay / ax) or
  // pi/2 - atan_unit(ax / ay)).
  const D u = atan_unit(select(low, ay, ax) / select(low, ax, ay));
  D a = select(low, u, dsplat(1.57079632679489655800e+00) - u);
  a = select(x < zero, dsplat(3.14159265358979311600e+00) - a, a);
  a = select(y < zero, a * minus, a);
  return narrow(select((x == zero) & (y == zero), zero, a));
}

}  // namespace rwd::sim::d3
