// SPDX-License-Identifier: MIT
#pragma once
// What the solver's lane passes (contact_lanes.h) compute with: vectors of
// lanes, and the lanes' bodies gathered from the solver bodies' rows and
// scattered back. Written for any access type (see contact_lanes.h); like
// the passes, everything here has internal linkage, so each file that
// includes it compiles its own copy for its own instruction set.
#include <cstdint>
#include <vector>

#include "d3/contact_batches.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

template <class F>
struct V3 {
  F x, y, z;
};
template <class F>
V3<F> operator+(const V3<F>& a, const V3<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
V3<F> operator-(const V3<F>& a, const V3<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
V3<F> operator*(const V3<F>& a, F s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class F>
F dot3(const V3<F>& a, const V3<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class F>
V3<F> cross3(const V3<F>& a, const V3<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class A>
V3<typename A::F> ld3(const A& acc, const float (&f)[3][kBatchLanes]) {
  return {acc.ld(f[0]), acc.ld(f[1]), acc.ld(f[2])};
}
template <class A>
void st3(const A& acc, float (&f)[3][kBatchLanes], const V3<typename A::F>& v) {
  acc.st(f[0], v.x);
  acc.st(f[1], v.y);
  acc.st(f[2], v.z);
}

// The velocities of the lanes' bodies.
template <class F>
struct LaneBodies {
  V3<F> v;
  V3<F> w;
  F inv_mass;
  F rest;  // the row's eighth float, written back unchanged
};

// A solver body's first eight floats: its row (see SolverBody).
inline const float* body_row(const SolverBody& b) {
  return reinterpret_cast<const float*>(&b);
}
inline float* body_row(SolverBody& b) {
  return reinterpret_cast<float*>(&b);
}

// Offsets of a solver body's rows (see SolverBody).
inline constexpr int kVelocityRow = 0;
inline constexpr int kPushRow = 8;
inline constexpr int kInertiaRow = 16;

// The lanes' bodies: one of their rows (the velocities, or the push row read
// the same way: push velocities, inverse mass, pushed), transposed into lanes
// by the access.
template <class A>
[[gnu::always_inline]] inline LaneBodies<typename A::F> gather_bodies(
    const A& acc, const std::vector<SolverBody>& bodies, bool side_b, int row = kVelocityRow) {
  const float* rows[A::kWidth];
  for (int i = 0; i < A::kWidth; ++i) {
    rows[i] = body_row(bodies[side_b ? acc.body_b(i) : acc.body_a(i)]) + row;
  }
  typename A::F f[8];
  A::gather_rows(rows, f);
  return {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}, f[6], f[7]};
}

// The lanes' bodies' world inverse inertias (columns): a row transposed like
// the velocities, and the ninth float one lane at a time.
template <class F>
struct LaneInertia {
  V3<F> c0, c1, c2;
};

template <class A>
LaneInertia<typename A::F> gather_inertia(const A& acc, const std::vector<SolverBody>& bodies,
                                          bool side_b) {
  const float* rows[A::kWidth];
  alignas(32) float last[A::kWidth];
  for (int i = 0; i < A::kWidth; ++i) {
    rows[i] = body_row(bodies[side_b ? acc.body_b(i) : acc.body_a(i)]) + kInertiaRow;
    last[i] = rows[i][8];
  }
  typename A::F f[8];
  A::gather_rows(rows, f);
  return {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], A::from(last)}};
}

// m v with the association of Mat3 * Vec3 (math.h), so a lane's product is
// bit for bit the scalar one.
template <class F>
V3<F> mul(const LaneInertia<F>& m, const V3<F>& v) {
  return m.c0 * v.x + m.c1 * v.y + m.c2 * v.z;
}

// Writes the lanes' rows back (velocities; the inverse mass and the eighth
// float as they were read, so a row is stored whole and the next gather's
// load of it is forwarded from the store) to the bodies that can move. A
// movable body is in at most one lane of a colour; a body that cannot move
// (static, sleeping, kinematic) may be in several and is never written (its
// lanes store to a sink on the stack), so no lane order or lane count can
// leave a different signed zero in it.
template <class A>
[[gnu::always_inline]] inline void scatter_bodies(const A& acc, std::vector<SolverBody>& bodies,
                                                  bool side_b, const LaneBodies<typename A::F>& b,
                                                  int row = kVelocityRow) {
  alignas(32) float sink[8];
  float* rows[A::kWidth];
  for (int i = 0; i < A::kWidth; ++i) {
    const bool movable = side_b ? acc.movable_b(i) : acc.movable_a(i);
    rows[i] = movable ? body_row(bodies[side_b ? acc.body_b(i) : acc.body_a(i)]) + row : sink;
  }
  const typename A::F f[8] = {b.v.x, b.v.y, b.v.z, b.w.x, b.w.y, b.w.z, b.inv_mass, b.rest};
  A::scatter_rows(f, rows);
}

// 1 / k where k > 0, else 0 (no division by zero in any lane).
template <class A>
typename A::F inverse_or_zero(typename A::F k) {
  const typename A::F zero = A::splat(0.0f);
  const typename A::F one = A::splat(1.0f);
  const auto positive = k > zero;
  return select(positive, one / select(positive, k, one), zero);
}

}  // namespace
}  // namespace rwd::sim::d3
