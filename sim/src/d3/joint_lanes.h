// SPDX-License-Identifier: MIT
#pragma once
// What the point joints' lane passes (joint_point_batches.cpp) and their
// angular parts' (joint_angular_lanes.h) compute with: a batch's lanes as
// contact_lane_bodies.h's access, lane quaternions, and the lanes' bodies'
// position rows. Internal linkage, like contact_lane_bodies.h.
#include <cstddef>
#include <vector>

#include "d3/contact_lane_bodies.h"
#include "d3/joint_point_batches.h"
#include "d3/wide_float.h"

namespace rwd::sim::d3 {
namespace {

// A solver body's position row: the ninth float of its inverse inertia
// (written back unchanged), then its delta position and delta rotation.
inline constexpr int kPositionRow = 24;
static_assert(offsetof(SolverBody, delta_position) == 25 * sizeof(float) &&
                  offsetof(SolverBody, delta_rotation) == 28 * sizeof(float),
              "the position row is the ninth inertia float, delta position, delta rotation");

using F = FloatW;

// The lanes of one batch (contact_lanes.h's access, for contact_lane_bodies.h).
struct PointAccess {
  using F = FloatW;
  static constexpr int kWidth = kLanes;
  const PointBatch* batch;
  uint8_t active = 0xFu;  ///< lanes whose bodies may be written
  static F splat(float x) { return d3::splat(x); }
  static F from(const float* p) { return load(p); }
  static void gather_rows(const float* const (&rows)[kLanes], F (&out)[8]) { load_rows(rows, out); }
  static void scatter_rows(const F (&in)[8], float* const (&rows)[kLanes]) { store_rows(in, rows); }
  uint32_t body_a(int lane) const { return batch->body_a[lane]; }
  uint32_t body_b(int lane) const { return batch->body_b[lane]; }
  bool movable_a(int lane) const { return batch->movable_a[lane] != 0 && (active >> lane & 1u); }
  bool movable_b(int lane) const { return batch->movable_b[lane] != 0 && (active >> lane & 1u); }
};

inline V3<F> ld3(const float (&f)[3][kLanes]) {
  return {load(f[0]), load(f[1]), load(f[2])};
}
inline void st3(float (&f)[3][kLanes], const V3<F>& v) {
  store(f[0], v.x);
  store(f[1], v.y);
  store(f[2], v.z);
}

struct LaneQuat {
  F x, y, z, w;
};

// rotate(q, v) of math.h, lane by lane.
inline V3<F> rotate_lanes(const LaneQuat& q, const V3<F>& v) {
  const V3<F> u{q.x, q.y, q.z};
  const V3<F> t = cross3(u, v) * splat(2.0f);
  return v + t * q.w + cross3(u, t);
}

// integrate_rotation(q, w, 1) of math.h, lane by lane (a zero length gives
// the identity, as normalize does).
inline LaneQuat integrate_lanes(const LaneQuat& q, const V3<F>& w) {
  const F hh = splat(0.5f);
  const V3<F> d{w.x * hh, w.y * hh, w.z * hh};
  // dq * q with dq.w = 0.
  const F rx = d.x * q.w + d.y * q.z - d.z * q.y;
  const F ry = d.y * q.w - d.x * q.z + d.z * q.x;
  const F rz = d.x * q.y - d.y * q.x + d.z * q.w;
  const F rw = splat(0.0f) - d.x * q.x - d.y * q.y - d.z * q.z;
  const LaneQuat s{q.x + rx, q.y + ry, q.z + rz, q.w + rw};
  const F len = sqrt(s.x * s.x + s.y * s.y + s.z * s.z + s.w * s.w);
  const auto real = len > splat(1e-12f);
  const F inv = splat(1.0f) / select(real, len, splat(1.0f));
  return {select(real, s.x * inv, splat(0.0f)), select(real, s.y * inv, splat(0.0f)),
          select(real, s.z * inv, splat(0.0f)), select(real, s.w * inv, splat(1.0f))};
}

// The lanes' bodies' position rows.
struct LanePositions {
  F keep;  // the row's first float (inertia), written back unchanged
  V3<F> p;
  LaneQuat q;
};

inline LanePositions gather_positions(const PointBatch& batch,
                                      const std::vector<SolverBody>& bodies, bool side_b) {
  const float* rows[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    rows[i] = body_row(bodies[side_b ? batch.body_b[i] : batch.body_a[i]]) + kPositionRow;
  }
  F f[8];
  load_rows(rows, f);
  return {f[0], {f[1], f[2], f[3]}, {f[4], f[5], f[6], f[7]}};
}

inline void scatter_positions(const PointBatch& batch, std::vector<SolverBody>& bodies, bool side_b,
                              const LanePositions& s) {
  alignas(32) float sink[8];
  float* rows[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const bool movable = side_b ? batch.movable_b[i] != 0 : batch.movable_a[i] != 0;
    rows[i] = movable ? body_row(bodies[side_b ? batch.body_b[i] : batch.body_a[i]]) + kPositionRow
                      : sink;
  }
  const F f[8] = {s.keep, s.p.x, s.p.y, s.p.z, s.q.x, s.q.y, s.q.z, s.q.w};
  store_rows(f, rows);
}

}  // namespace
}  // namespace rwd::sim::d3
