// SPDX-License-Identifier: MIT
// The solver's passes on eight AVX lanes: a whole batch at a time
// (contact_lanes.h). Compiled for AVX through a target pragma, so the
// rest of the engine stays plain x86-64; contact_batches.cpp calls in only
// when the processor and the OS support AVX. Each AVX operation is the same
// IEEE single-precision operation per lane as the SSE2 one (no FMA, exact
// division and square root, compare-and-select), so the results are those of
// the four-lane passes.
#include "d3/wide_float.h"

#if defined(REWIND_LANES_AVX)

#include <immintrin.h>

#include <cstddef>
#include <vector>

#include "d3/contact_batches.h"
#include "d3/world_scratch.h"

// Everything defined from here on may use AVX instructions.
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx")
#endif

namespace rwd::sim::d3 {
namespace {

struct FloatW8 {
  __m256 v;
};
struct MaskW8 {
  __m256 v;
};
inline FloatW8 operator+(FloatW8 a, FloatW8 b) {
  return {_mm256_add_ps(a.v, b.v)};
}
inline FloatW8 operator-(FloatW8 a, FloatW8 b) {
  return {_mm256_sub_ps(a.v, b.v)};
}
inline FloatW8 operator*(FloatW8 a, FloatW8 b) {
  return {_mm256_mul_ps(a.v, b.v)};
}
inline FloatW8 operator/(FloatW8 a, FloatW8 b) {
  return {_mm256_div_ps(a.v, b.v)};
}
inline FloatW8 sqrt(FloatW8 a) {
  return {_mm256_sqrt_ps(a.v)};
}
// Ordered, non-signalling compares: false for NaN, as SSE's cmplt/cmpgt.
inline MaskW8 operator<(FloatW8 a, FloatW8 b) {
  return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)};
}
inline MaskW8 operator>(FloatW8 a, FloatW8 b) {
  return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)};
}
inline FloatW8 select(MaskW8 m, FloatW8 a, FloatW8 b) {
  return {_mm256_or_ps(_mm256_and_ps(m.v, a.v), _mm256_andnot_ps(m.v, b.v))};
}

// Eight lanes over one batch.
struct FullBatch {
  using F = FloatW8;
  static constexpr int kWidth = kBatchLanes;
  static constexpr bool kSettles = false;
  ContactBatch* batch;
  static F splat(float x) { return {_mm256_set1_ps(x)}; }
  static F from(const float* p) { return {_mm256_loadu_ps(p)}; }
  static void to(float* p, F v) { _mm256_storeu_ps(p, v.v); }
  // Batches are 32-byte aligned and every field is a multiple of 32 bytes
  // from the start, so lane arrays load and store aligned.
  F ld(const float (&field)[kBatchLanes]) const { return {_mm256_load_ps(field)}; }
  void st(float (&field)[kBatchLanes], F v) const { _mm256_store_ps(field, v.v); }
  // Rows of eight floats into eight lane values and back (8x8 transpose).
  static void transpose8(__m256 (&r)[8]) {
    const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]);
    const __m256 t1 = _mm256_unpackhi_ps(r[0], r[1]);
    const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]);
    const __m256 t3 = _mm256_unpackhi_ps(r[2], r[3]);
    const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]);
    const __m256 t5 = _mm256_unpackhi_ps(r[4], r[5]);
    const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]);
    const __m256 t7 = _mm256_unpackhi_ps(r[6], r[7]);
    const __m256 s0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 s1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 s2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 s3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 s4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 s5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 s6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 s7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
    r[0] = _mm256_permute2f128_ps(s0, s4, 0x20);
    r[1] = _mm256_permute2f128_ps(s1, s5, 0x20);
    r[2] = _mm256_permute2f128_ps(s2, s6, 0x20);
    r[3] = _mm256_permute2f128_ps(s3, s7, 0x20);
    r[4] = _mm256_permute2f128_ps(s0, s4, 0x31);
    r[5] = _mm256_permute2f128_ps(s1, s5, 0x31);
    r[6] = _mm256_permute2f128_ps(s2, s6, 0x31);
    r[7] = _mm256_permute2f128_ps(s3, s7, 0x31);
  }
  static void gather_rows(const float* const (&rows)[kBatchLanes], F (&out)[8]) {
    __m256 r[8];
    for (int i = 0; i < 8; ++i) r[i] = _mm256_load_ps(rows[i]);
    transpose8(r);
    for (int k = 0; k < 8; ++k) out[k] = {r[k]};
  }
  static void scatter_rows(const F (&in)[8], float* const (&rows)[kBatchLanes]) {
    __m256 r[8];
    for (int k = 0; k < 8; ++k) r[k] = in[k].v;
    transpose8(r);
    for (int i = 0; i < 8; ++i) {
      _mm256_store_ps(rows[i], r[i]);
    }
  }
  uint32_t body_a(int lane) const { return batch->body_a[lane]; }
  uint32_t body_b(int lane) const { return batch->body_b[lane]; }
  bool movable_a(int lane) const { return batch->movable_a[lane] != 0; }
  bool movable_b(int lane) const { return batch->movable_b[lane] != 0; }
  ContactBatch& first() const { return *batch; }
};

}  // namespace
}  // namespace rwd::sim::d3

#include "d3/contact_lanes.h"

namespace rwd::sim::d3 {

void prepare_full(ContactBatch& batch, const std::vector<SolverBody>& bodies) {
  for_point_bound(batch,
                  [&](auto n) { prepare_lanes<decltype(n)::value>(FullBatch{&batch}, bodies); });
}

void warm_start_full(ContactBatch& batch, std::vector<SolverBody>& bodies) {
  for_point_bound(batch,
                  [&](auto n) { warm_start_lanes<decltype(n)::value>(FullBatch{&batch}, bodies); });
}

void solve_full(ContactBatch& batch, std::vector<SolverBody>& bodies, float inv_h) {
  for_point_bound(
      batch, [&](auto n) { solve_lanes<decltype(n)::value>(FullBatch{&batch}, bodies, inv_h); });
}

void solve_full_pair(ContactBatch& first, ContactBatch& second, std::vector<SolverBody>& bodies,
                     float inv_h) {
  for_point_bound(first, [&](auto n) {
    solve_lanes_pair<decltype(n)::value>(FullBatch{&first}, FullBatch{&second}, bodies, inv_h);
  });
}

void separations_full(ContactBatch& batch, const std::vector<SolverBody>& bodies) {
  for_point_bound(
      batch, [&](auto n) { separations_lanes<decltype(n)::value>(FullBatch{&batch}, bodies); });
}

void push_full(ContactBatch& batch, std::vector<SolverBody>& bodies, const PushSettings& push) {
  for_point_bound(batch,
                  [&](auto n) { push_lanes<decltype(n)::value>(FullBatch{&batch}, bodies, push); });
}

}  // namespace rwd::sim::d3

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

namespace rwd::sim::d3 {

bool lanes8_available() {
  // AVX in the processor and its 256-bit registers saved by the OS.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx");
}

}  // namespace rwd::sim::d3

#endif  // REWIND_LANES_AVX
