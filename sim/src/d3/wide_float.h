// SPDX-License-Identifier: MIT
#pragma once
// Four floats processed as one: the lanes of the contact solver
// (contact_batches.cpp) and of the broadphase's sweep. Each operation is the IEEE single-precision
// operation applied lane by lane, with no fused multiply-add, no
// reciprocal or square-root estimate and no reordering, so a lane computes
// bit for bit what the same expression computes on one float. SSE2 (every
// x86-64), NEON (every aarch64) and plain arrays (REWIND_SCALAR_LANES, or
// any other target) therefore give identical results; the determinism
// matrix builds the plain-array version too to prove it.
//
// min/max/clamps are written as compare-and-select, not with the native
// min/max instructions, whose results for NaN differ between SSE and NEON.
#include <cstdint>

// Eight-lane AVX passes exist on x86-64 and are chosen at run time
// (contact_lanes_avx.cpp); REWIND_SCALAR_LANES turns them off too.
#if !defined(REWIND_SCALAR_LANES) && defined(__x86_64__) && defined(__GNUC__)
#define REWIND_LANES_AVX 1
#endif

#if !defined(REWIND_SCALAR_LANES) && defined(__SSE2__)
#define REWIND_LANES_SSE2 1
#include <emmintrin.h>
#elif !defined(REWIND_SCALAR_LANES) && defined(__ARM_NEON) && defined(__aarch64__)
#define REWIND_LANES_NEON 1
#include <arm_neon.h>
#endif

namespace rwd::sim::d3 {

inline constexpr int kLanes = 4;

#if defined(REWIND_LANES_SSE2)

struct FloatW {
  __m128 v;
};
struct MaskW {
  __m128 v;
};
inline FloatW splat(float x) {
  return {_mm_set1_ps(x)};
}
inline FloatW load(const float* p) {
  return {_mm_loadu_ps(p)};
}
inline void store(float* p, FloatW a) {
  _mm_storeu_ps(p, a.v);
}
inline FloatW operator+(FloatW a, FloatW b) {
  return {_mm_add_ps(a.v, b.v)};
}
inline FloatW operator-(FloatW a, FloatW b) {
  return {_mm_sub_ps(a.v, b.v)};
}
inline FloatW operator*(FloatW a, FloatW b) {
  return {_mm_mul_ps(a.v, b.v)};
}
inline FloatW operator/(FloatW a, FloatW b) {
  return {_mm_div_ps(a.v, b.v)};
}
inline FloatW sqrt(FloatW a) {
  return {_mm_sqrt_ps(a.v)};
}
inline MaskW operator<(FloatW a, FloatW b) {
  return {_mm_cmplt_ps(a.v, b.v)};
}
inline MaskW operator>(FloatW a, FloatW b) {
  return {_mm_cmpgt_ps(a.v, b.v)};
}
/// m ? a : b, lane by lane.
inline FloatW select(MaskW m, FloatW a, FloatW b) {
  return {_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))};
}
/// The lesser and the greater of a and b, lane by lane, for lanes that are
/// never NaN: only there do the instructions of every target agree, and
/// even then not on which of +0 and -0 is the lesser, so only for values
/// that are compared, never kept.
inline FloatW min_no_nan(FloatW a, FloatW b) {
  return {_mm_min_ps(a.v, b.v)};
}
inline FloatW max_no_nan(FloatW a, FloatW b) {
  return {_mm_max_ps(a.v, b.v)};
}
inline MaskW operator>=(FloatW a, FloatW b) {
  return {_mm_cmpge_ps(a.v, b.v)};
}
inline MaskW operator==(FloatW a, FloatW b) {
  return {_mm_cmpeq_ps(a.v, b.v)};
}
inline MaskW operator|(MaskW a, MaskW b) {
  return {_mm_or_ps(a.v, b.v)};
}
inline MaskW operator&(MaskW a, MaskW b) {
  return {_mm_and_ps(a.v, b.v)};
}
/// Bit i set when lane i of m is true.
inline uint32_t lane_bits(MaskW m) {
  return static_cast<uint32_t>(_mm_movemask_ps(m.v));
}

#elif defined(REWIND_LANES_NEON)

struct FloatW {
  float32x4_t v;
};
struct MaskW {
  uint32x4_t v;
};
inline FloatW splat(float x) {
  return {vdupq_n_f32(x)};
}
inline FloatW load(const float* p) {
  return {vld1q_f32(p)};
}
inline void store(float* p, FloatW a) {
  vst1q_f32(p, a.v);
}
inline FloatW operator+(FloatW a, FloatW b) {
  return {vaddq_f32(a.v, b.v)};
}
inline FloatW operator-(FloatW a, FloatW b) {
  return {vsubq_f32(a.v, b.v)};
}
inline FloatW operator*(FloatW a, FloatW b) {
  return {vmulq_f32(a.v, b.v)};
}
inline FloatW operator/(FloatW a, FloatW b) {
  return {vdivq_f32(a.v, b.v)};
}
inline FloatW sqrt(FloatW a) {
  return {vsqrtq_f32(a.v)};
}
inline MaskW operator<(FloatW a, FloatW b) {
  return {vcltq_f32(a.v, b.v)};
}
inline MaskW operator>(FloatW a, FloatW b) {
  return {vcgtq_f32(a.v, b.v)};
}
inline FloatW select(MaskW m, FloatW a, FloatW b) {
  return {vbslq_f32(m.v, a.v, b.v)};
}
inline FloatW min_no_nan(FloatW a, FloatW b) {
  return {vminq_f32(a.v, b.v)};
}
inline FloatW max_no_nan(FloatW a, FloatW b) {
  return {vmaxq_f32(a.v, b.v)};
}
inline MaskW operator>=(FloatW a, FloatW b) {
  return {vcgeq_f32(a.v, b.v)};
}
inline MaskW operator==(FloatW a, FloatW b) {
  return {vceqq_f32(a.v, b.v)};
}
inline MaskW operator|(MaskW a, MaskW b) {
  return {vorrq_u32(a.v, b.v)};
}
inline MaskW operator&(MaskW a, MaskW b) {
  return {vandq_u32(a.v, b.v)};
}
inline uint32_t lane_bits(MaskW m) {
  const uint32x4_t weights = {1u, 2u, 4u, 8u};
  return vaddvq_u32(vandq_u32(m.v, weights));
}

#else

struct FloatW {
  float v[kLanes];
};
struct MaskW {
  bool v[kLanes];
};
inline FloatW splat(float x) {
  return {{x, x, x, x}};
}
inline FloatW load(const float* p) {
  return {{p[0], p[1], p[2], p[3]}};
}
inline void store(float* p, FloatW a) {
  for (int i = 0; i < kLanes; ++i) p[i] = a.v[i];
}
#define REWIND_LANEWISE(op)                                   \
  FloatW r;                                                   \
  for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] op b.v[i]; \
  return r
inline FloatW operator+(FloatW a, FloatW b) {
  REWIND_LANEWISE(+);
}
inline FloatW operator-(FloatW a, FloatW b) {
  REWIND_LANEWISE(-);
}
inline FloatW operator*(FloatW a, FloatW b) {
  REWIND_LANEWISE(*);
}
inline FloatW operator/(FloatW a, FloatW b) {
  REWIND_LANEWISE(/);
}
#undef REWIND_LANEWISE
inline FloatW sqrt(FloatW a) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = __builtin_sqrtf(a.v[i]);
  return r;
}
inline MaskW operator<(FloatW a, FloatW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] < b.v[i];
  return m;
}
inline MaskW operator>(FloatW a, FloatW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] > b.v[i];
  return m;
}
inline FloatW select(MaskW m, FloatW a, FloatW b) {
  FloatW r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = m.v[i] ? a.v[i] : b.v[i];
  return r;
}
inline FloatW min_no_nan(FloatW a, FloatW b) {
  return select(b < a, b, a);
}
inline FloatW max_no_nan(FloatW a, FloatW b) {
  return select(a < b, b, a);
}
inline MaskW operator>=(FloatW a, FloatW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] >= b.v[i];
  return m;
}
inline MaskW operator==(FloatW a, FloatW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] == b.v[i];
  return m;
}
inline MaskW operator|(MaskW a, MaskW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] || b.v[i];
  return m;
}
inline MaskW operator&(MaskW a, MaskW b) {
  MaskW m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] && b.v[i];
  return m;
}
inline uint32_t lane_bits(MaskW m) {
  uint32_t bits = 0;
  for (int i = 0; i < kLanes; ++i) bits |= (m.v[i] ? 1u : 0u) << i;
  return bits;
}

#endif

inline FloatW operator-(FloatW a) {
  return splat(0.0f) - a;
}

/// Eight floats from each of kLanes rows (a solver body's row, 16-byte
/// aligned) into eight lane values: out[k] holds float k of every row.
inline void load_rows(const float* const (&rows)[kLanes], FloatW (&out)[8]) {
#if defined(REWIND_LANES_SSE2)
  __m128 lo[kLanes];
  __m128 hi[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    lo[i] = _mm_load_ps(rows[i]);
    hi[i] = _mm_load_ps(rows[i] + 4);
  }
  _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
  _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
  for (int k = 0; k < 4; ++k) {
    out[k] = {lo[k]};
    out[4 + k] = {hi[k]};
  }
#else
  alignas(16) float f[8][kLanes];
  for (int i = 0; i < kLanes; ++i) {
    for (int k = 0; k < 8; ++k) f[k][i] = rows[i][k];
  }
  for (int k = 0; k < 8; ++k) out[k] = load(f[k]);
#endif
}

/// The inverse of load_rows, whole rows at a time.
inline void store_rows(const FloatW (&in)[8], float* const (&rows)[kLanes]) {
#if defined(REWIND_LANES_SSE2)
  __m128 lo[4] = {in[0].v, in[1].v, in[2].v, in[3].v};
  __m128 hi[4] = {in[4].v, in[5].v, in[6].v, in[7].v};
  _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
  _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
  for (int i = 0; i < kLanes; ++i) {
    _mm_store_ps(rows[i], lo[i]);
    _mm_store_ps(rows[i] + 4, hi[i]);
  }
#else
  alignas(16) float f[8][kLanes];
  for (int k = 0; k < 8; ++k) store(f[k], in[k]);
  for (int i = 0; i < kLanes; ++i) {
    for (int k = 0; k < 8; ++k) rows[i][k] = f[k][i];
  }
#endif
}

}  // namespace rwd::sim::d3
