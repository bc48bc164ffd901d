// SPDX-License-Identifier: MIT
#pragma once
// The two accesses the portable passes of contact_batches.cpp run the lane
// passes (contact_lanes.h) through: four lanes over half a batch, and one
// lane in plain floats. The eight-lane AVX access is contact_lanes_avx.cpp's.
//
// Everything here has internal linkage, as in contact_lanes.h: each file
// that includes it compiles its own copy for its own instruction set.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "d3/contact_batches.h"
#include "d3/wide_float.h"

namespace rwd::sim::d3 {
namespace {

// Four lanes over half a batch, lanes [base, base + 4) (see
// contact_lanes.h for what an access is).
struct HalfBatch {
  using F = FloatW;
  static constexpr int kWidth = kLanes;
  static constexpr bool kSettles = false;
  ContactBatch* batch;
  int base;  ///< 0 or kLanes
  static F splat(float x) { return d3::splat(x); }
  static F from(const float* p) { return load(p); }
  static void to(float* p, F v) { store(p, v); }
  F ld(const float (&field)[kBatchLanes]) const { return load(field + base); }
  void st(float (&field)[kBatchLanes], F v) const { store(field + base, v); }
  static void gather_rows(const float* const (&rows)[kLanes], F (&out)[8]) { load_rows(rows, out); }
  static void scatter_rows(const F (&in)[8], float* const (&rows)[kLanes]) { store_rows(in, rows); }
  uint32_t body_a(int lane) const { return batch->body_a[base + lane]; }
  uint32_t body_b(int lane) const { return batch->body_b[base + lane]; }
  bool movable_a(int lane) const { return batch->movable_a[base + lane] != 0; }
  bool movable_b(int lane) const { return batch->movable_b[base + lane] != 0; }
  ContactBatch& first() const { return *batch; }
};

// One lane in plain floats: what a batch of one or two constraints runs
// on (a small world's, a colour's last few, the overflow's), where eight or
// four lanes would compute mostly empty lanes: a pass over a whole batch
// costs about as much with one constraint as with eight. Each operation is
// the IEEE single-precision one, as in every lane type (wide_float.h), so
// a constraint's result does not depend on which access ran it.
struct Float1 {
  float v;
};
struct Mask1 {
  bool v;
};
inline Float1 operator+(Float1 a, Float1 b) {
  return {a.v + b.v};
}
inline Float1 operator-(Float1 a, Float1 b) {
  return {a.v - b.v};
}
inline Float1 operator*(Float1 a, Float1 b) {
  return {a.v * b.v};
}
inline Float1 operator/(Float1 a, Float1 b) {
  return {a.v / b.v};
}
inline Float1 sqrt(Float1 a) {
  return {__builtin_sqrtf(a.v)};
}
// Ordered compares: false for NaN, as the lanes' are.
inline Mask1 operator<(Float1 a, Float1 b) {
  return {a.v < b.v};
}
inline Mask1 operator>(Float1 a, Float1 b) {
  return {a.v > b.v};
}
inline Mask1 operator>=(Float1 a, Float1 b) {
  return {a.v >= b.v};
}
inline Mask1 operator==(Float1 a, Float1 b) {
  return {a.v == b.v};
}
inline Mask1 operator|(Mask1 a, Mask1 b) {
  return {a.v || b.v};
}
inline Mask1 operator&(Mask1 a, Mask1 b) {
  return {a.v && b.v};
}
inline Float1 select(Mask1 m, Float1 a, Float1 b) {
  return m.v ? a : b;
}

struct OneLane {
  using F = Float1;
  static constexpr int kWidth = 1;
  static constexpr bool kSettles = true;
  // memcpy rather than std::bit_cast, which Emscripten's standard library
  // does not have yet.
  static uint32_t bits(F v) {
    uint32_t b = 0;
    std::memcpy(&b, &v.v, sizeof b);
    return b;
  }
  ContactBatch* batch;
  int lane;
  static F splat(float x) { return {x}; }
  static F from(const float* p) { return {p[0]}; }
  static void to(float* p, F v) { p[0] = v.v; }
  F ld(const float (&field)[kBatchLanes]) const { return {field[lane]}; }
  void st(float (&field)[kBatchLanes], F v) const { field[lane] = v.v; }
  uint32_t body_a(int) const { return batch->body_a[lane]; }
  uint32_t body_b(int) const { return batch->body_b[lane]; }
  bool movable_a(int) const { return batch->movable_a[lane] != 0; }
  bool movable_b(int) const { return batch->movable_b[lane] != 0; }
  ContactBatch& first() const { return *batch; }
  // A row moves as two 4-float vectors built and taken apart in registers.
  // Left to itself the compiler merges the eight scalar stores of a row
  // into vector stores by way of the stack: eight 4-byte stores there, then
  // a 16-byte load of them that no store can forward, a stall of a dozen
  // cycles in each pass of each small world's contact.
  static void gather_rows(const float* const (&rows)[1], F (&out)[8]) {
#if defined(REWIND_LANES_SSE2)
    const __m128 lo = _mm_loadu_ps(rows[0]);
    const __m128 hi = _mm_loadu_ps(rows[0] + 4);
    out[0] = {_mm_cvtss_f32(lo)};
    out[1] = {_mm_cvtss_f32(_mm_shuffle_ps(lo, lo, 1))};
    out[2] = {_mm_cvtss_f32(_mm_movehl_ps(lo, lo))};
    out[3] = {_mm_cvtss_f32(_mm_shuffle_ps(lo, lo, 3))};
    out[4] = {_mm_cvtss_f32(hi)};
    out[5] = {_mm_cvtss_f32(_mm_shuffle_ps(hi, hi, 1))};
    out[6] = {_mm_cvtss_f32(_mm_movehl_ps(hi, hi))};
    out[7] = {_mm_cvtss_f32(_mm_shuffle_ps(hi, hi, 3))};
#else
    for (int k = 0; k < 8; ++k) out[k] = {rows[0][k]};
#endif
  }
  static void scatter_rows(const F (&in)[8], float* const (&rows)[1]) {
#if defined(REWIND_LANES_SSE2)
    _mm_storeu_ps(rows[0], _mm_setr_ps(in[0].v, in[1].v, in[2].v, in[3].v));
    _mm_storeu_ps(rows[0] + 4, _mm_setr_ps(in[4].v, in[5].v, in[6].v, in[7].v));
#else
    for (int k = 0; k < 8; ++k) rows[0][k] = in[k].v;
#endif
  }
};

}  // namespace
}  // namespace rwd::sim::d3
