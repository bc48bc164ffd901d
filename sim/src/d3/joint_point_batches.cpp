// SPDX-License-Identifier: MIT
// Point joints in the solver's lanes (joint_point_batches.h): colouring and
// packing, and the stages of joint_point.cpp written once for kLanes lanes.
#include "d3/joint_point_batches.h"

#include <cstddef>

#include "d3/contact_lane_bodies.h"
#include "d3/joint_solver.h"
#include "d3/world_scratch.h"

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

V3<F> ld3(const float (&f)[3][kLanes]) {
  return {load(f[0]), load(f[1]), load(f[2])};
}
void st3(float (&f)[3][kLanes], const V3<F>& v) {
  store(f[0], v.x);
  store(f[1], v.y);
  store(f[2], v.z);
}

struct LaneQuat {
  F x, y, z, w;
};

// rotate(q, v) of math.h, lane by lane.
V3<F> rotate_lanes(const LaneQuat& q, const V3<F>& v) {
  const V3<F> u{q.x, q.y, q.z};
  const V3<F> t = cross3(u, v) * splat(2.0f);
  return v + t * q.w + cross3(u, t);
}

// integrate_rotation(q, w, 1) of math.h, lane by lane (a zero length gives
// the identity, as normalize does).
LaneQuat integrate_lanes(const LaneQuat& q, const V3<F>& w) {
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

LanePositions gather_positions(const PointBatch& batch, const std::vector<SolverBody>& bodies,
                               bool side_b) {
  const float* rows[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    rows[i] = body_row(bodies[side_b ? batch.body_b[i] : batch.body_a[i]]) + kPositionRow;
  }
  F f[8];
  load_rows(rows, f);
  return {f[0], {f[1], f[2], f[3]}, {f[4], f[5], f[6], f[7]}};
}

void scatter_positions(const PointBatch& batch, std::vector<SolverBody>& bodies, bool side_b,
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

// T v for a turn matrix stored column-major in 9 lane rows.
V3<F> turn(const float (&t)[9][kLanes], const V3<F>& v) {
  const V3<F> c0{load(t[0]), load(t[1]), load(t[2])};
  const V3<F> c1{load(t[3]), load(t[4]), load(t[5])};
  const V3<F> c2{load(t[6]), load(t[7]), load(t[8])};
  return c0 * v.x + c1 * v.y + c2 * v.z;
}

// K^-1 v for the symmetric inverse stored as xx, xy, xz, yy, yz, zz.
V3<F> inv_k_times(const PointBatch& b, const V3<F>& v) {
  const F xx = load(b.inv_k[0]), xy = load(b.inv_k[1]), xz = load(b.inv_k[2]);
  const F yy = load(b.inv_k[3]), yz = load(b.inv_k[4]), zz = load(b.inv_k[5]);
  return {xx * v.x + xy * v.y + xz * v.z, xy * v.x + yy * v.y + yz * v.z,
          xz * v.x + yz * v.y + zz * v.z};
}

// Impulse p at the anchors: -p to A, +p to B.
void apply(const PointBatch& b, LaneBodies<F>& a, LaneBodies<F>& bb, const V3<F>& p) {
  const F ma = load(b.mass_a);
  const F mb = load(b.mass_b);
  a.v = a.v - p * ma;
  a.w = a.w - turn(b.turn_a, p);
  bb.v = bb.v + p * mb;
  bb.w = bb.w + turn(b.turn_b, p);
}

V3<F> anchor_velocity_lanes(const PointBatch& b, const LaneBodies<F>& a, const LaneBodies<F>& bb) {
  const V3<F> ra = ld3(b.ra);
  const V3<F> rb = ld3(b.rb);
  return (bb.v + cross3(bb.w, rb)) - (a.v + cross3(a.w, ra));
}

}  // namespace

void build_point_batches(WorldScratch& s) {
  s.point_batches.clear();
  std::vector<JointConstraint>& joints = s.joint_constraints;
  const size_t words = (s.solver_bodies.size() + 63) / 64;
  s.point_color_bits.assign(words * kColorCount, 0);
  s.point_color_of.assign(joints.size(), kColorCount);
  bool any = false;
  for (uint32_t k = 0; k < joints.size(); ++k) {
    JointConstraint& c = joints[k];
    c.batched = false;
    if (!c.point) continue;
    const bool movable_a = s.solver_bodies[c.body_a].inv_mass != 0.0f;
    const bool movable_b = s.solver_bodies[c.body_b].inv_mass != 0.0f;
    s.point_color_of[k] =
        take_color(s.point_color_bits.data(), words, c.body_a, movable_a, c.body_b, movable_b);
    c.batched = s.point_color_of[k] != kColorCount;
    any = any || c.batched;
  }
  if (!any) return;
  // Colour by colour, in slot order within a colour, kLanes to a batch:
  // the batched joints sorted by colour in one counting pass.
  s.point_color_start.assign(kColorCount + 1, 0);
  for (uint32_t k = 0; k < joints.size(); ++k) {
    if (joints[k].batched) ++s.point_color_start[s.point_color_of[k] + 1];
  }
  for (uint32_t col = 0; col < kColorCount; ++col) {
    s.point_color_start[col + 1] += s.point_color_start[col];
  }
  s.point_color_order.resize(s.point_color_start[kColorCount]);
  s.point_color_fill.assign(s.point_color_start.begin(), s.point_color_start.end() - 1);
  for (uint32_t k = 0; k < joints.size(); ++k) {
    if (joints[k].batched) s.point_color_order[s.point_color_fill[s.point_color_of[k]]++] = k;
  }
  for (uint32_t col = 0; col < kColorCount; ++col) {
    int lane = kLanes;
    for (uint32_t q = s.point_color_start[col]; q < s.point_color_start[col + 1]; ++q) {
      const uint32_t k = s.point_color_order[q];
      if (lane == kLanes) {
        PointBatch& fresh = s.point_batches.emplace_back();
        for (int i = 0; i < kLanes; ++i) {
          fresh.joint[i] = kNoPointJoint;
          fresh.body_a[i] = fresh.body_b[i] = 0;
          fresh.movable_a[i] = fresh.movable_b[i] = 0;
          for (int d = 0; d < 3; ++d) {
            fresh.anchor_a[d][i] = fresh.anchor_b[d][i] = fresh.delta_center[d][i] = 0.0f;
            fresh.impulse[d][i] = 0.0f;
            fresh.tick_impulse[d][i] = 0.0f;
          }
        }
        lane = 0;
      }
      PointBatch& b = s.point_batches.back();
      const JointConstraint& c = joints[k];
      b.joint[lane] = k;
      b.body_a[lane] = c.body_a;
      b.body_b[lane] = c.body_b;
      b.movable_a[lane] = s.solver_bodies[c.body_a].inv_mass != 0.0f ? 1 : 0;
      b.movable_b[lane] = s.solver_bodies[c.body_b].inv_mass != 0.0f ? 1 : 0;
      const Vec3 v[3] = {c.anchor_a, c.anchor_b, c.delta_center};
      float(*dst[3])[kLanes] = {b.anchor_a, b.anchor_b, b.delta_center};
      for (int f = 0; f < 3; ++f) {
        dst[f][0][lane] = v[f].x;
        dst[f][1][lane] = v[f].y;
        dst[f][2][lane] = v[f].z;
      }
      b.impulse[0][lane] = c.linear_impulse.x;
      b.impulse[1][lane] = c.linear_impulse.y;
      b.impulse[2][lane] = c.linear_impulse.z;
      ++lane;
    }
  }
  // Every batched joint has the same softness (prepare_joints).
  for (const JointConstraint& c : joints) {
    if (c.batched) {
      s.point_soft = c.soft;
      break;
    }
  }
}

void refresh_point_batches(WorldScratch& s) {
  for (PointBatch& b : s.point_batches) {
    const PointAccess acc{&b};
    const LaneBodies<F> va = gather_bodies(acc, s.solver_bodies, false);
    const LaneBodies<F> vb = gather_bodies(acc, s.solver_bodies, true);
    const LaneInertia<F> ia = gather_inertia(acc, s.solver_bodies, false);
    const LaneInertia<F> ib = gather_inertia(acc, s.solver_bodies, true);
    const LanePositions pa = gather_positions(b, s.solver_bodies, false);
    const LanePositions pb = gather_positions(b, s.solver_bodies, true);
    const V3<F> ra = rotate_lanes(pa.q, ld3(b.anchor_a));
    const V3<F> rb = rotate_lanes(pb.q, ld3(b.anchor_b));
    st3(b.ra, ra);
    st3(b.rb, rb);
    store(b.mass_a, va.inv_mass);
    store(b.mass_b, vb.inv_mass);
    // r x e_j for the three axes, and the inverse inertia times them.
    const F zero = splat(0.0f);
    const V3<F> xa[3] = {
        {zero, ra.z, zero - ra.y}, {zero - ra.z, zero, ra.x}, {ra.y, zero - ra.x, zero}};
    const V3<F> xb[3] = {
        {zero, rb.z, zero - rb.y}, {zero - rb.z, zero, rb.x}, {rb.y, zero - rb.x, zero}};
    V3<F> ta[3];
    V3<F> tb[3];
    for (int j = 0; j < 3; ++j) {
      ta[j] = mul(ia, xa[j]);
      tb[j] = mul(ib, xb[j]);
      store(b.turn_a[3 * j], ta[j].x);
      store(b.turn_a[3 * j + 1], ta[j].y);
      store(b.turn_a[3 * j + 2], ta[j].z);
      store(b.turn_b[3 * j], tb[j].x);
      store(b.turn_b[3 * j + 1], tb[j].y);
      store(b.turn_b[3 * j + 2], tb[j].z);
    }
    // K = (m_a + m_b) I + sum over both bodies of (r x e_i) . I^-1 (r x e_j).
    const F m = va.inv_mass + vb.inv_mass;
    F k[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) {
        F v = dot3(xa[i], ta[j]) + dot3(xb[i], tb[j]);
        if (i == j) v = m + v;
        k[i][j] = v;
      }
    }
    const F c00 = k[1][1] * k[2][2] - k[1][2] * k[1][2];
    const F c01 = k[0][2] * k[1][2] - k[0][1] * k[2][2];
    const F c02 = k[0][1] * k[1][2] - k[0][2] * k[1][1];
    const F c11 = k[0][0] * k[2][2] - k[0][2] * k[0][2];
    const F c12 = k[0][1] * k[0][2] - k[0][0] * k[1][2];
    const F c22 = k[0][0] * k[1][1] - k[0][1] * k[0][1];
    const F det = k[0][0] * c00 + k[0][1] * c01 + k[0][2] * c02;
    // Positive for any lane with a movable body; an empty lane gets zeros.
    const F inv = inverse_or_zero<PointAccess>(det);
    store(b.inv_k[0], c00 * inv);
    store(b.inv_k[1], c01 * inv);
    store(b.inv_k[2], c02 * inv);
    store(b.inv_k[3], c11 * inv);
    store(b.inv_k[4], c12 * inv);
    store(b.inv_k[5], c22 * inv);
  }
}

void warm_start_point_batches(WorldScratch& s) {
  for (const PointBatch& b : s.point_batches) {
    const PointAccess acc{&b};
    LaneBodies<F> a = gather_bodies(acc, s.solver_bodies, false);
    LaneBodies<F> bb = gather_bodies(acc, s.solver_bodies, true);
    apply(b, a, bb, ld3(b.impulse));
    scatter_bodies(acc, s.solver_bodies, false, a);
    scatter_bodies(acc, s.solver_bodies, true, bb);
  }
}

void solve_point_batches(WorldScratch& s, bool use_bias, bool contacted_only) {
  const JointSoftness& soft = s.point_soft;
  for (PointBatch& b : s.point_batches) {
    PointAccess acc{&b};
    alignas(16) float keep[kLanes];  // 1: the lane's impulse changes
    if (contacted_only) {
      acc.active = 0;
      for (int i = 0; i < kLanes; ++i) {
        const bool hit = b.joint[i] != kNoPointJoint && (s.solver_bodies[b.body_a[i]].contacted ||
                                                         s.solver_bodies[b.body_b[i]].contacted);
        acc.active = static_cast<uint8_t>(acc.active | (hit ? 1u << i : 0u));
        keep[i] = hit ? 1.0f : 0.0f;
      }
      if (acc.active == 0) continue;
    } else {
      for (float& k : keep) k = 1.0f;
    }
    LaneBodies<F> a = gather_bodies(acc, s.solver_bodies, false);
    LaneBodies<F> bb = gather_bodies(acc, s.solver_bodies, true);
    V3<F> rhs = anchor_velocity_lanes(b, a, bb);
    const V3<F> acc_impulse = ld3(b.impulse);
    V3<F> p;
    if (use_bias) {
      // The anchors have not moved since the refresh (joint_point.cpp).
      const LanePositions pa = gather_positions(b, s.solver_bodies, false);
      const LanePositions pb = gather_positions(b, s.solver_bodies, true);
      const V3<F> d = ((pb.p - pa.p) + ld3(b.delta_center)) + (ld3(b.rb) - ld3(b.ra));
      rhs = rhs + d * splat(soft.bias_rate);
      const V3<F> x = inv_k_times(b, rhs);
      const F mass_scale = splat(soft.mass_scale);
      const F impulse_scale = splat(soft.impulse_scale);
      p = V3<F>{splat(0.0f) - x.x, splat(0.0f) - x.y, splat(0.0f) - x.z} * mass_scale -
          acc_impulse * impulse_scale;
    } else {
      const V3<F> x = inv_k_times(b, rhs);
      p = V3<F>{splat(0.0f) - x.x, splat(0.0f) - x.y, splat(0.0f) - x.z};
    }
    // A lane left out keeps its impulse, and its bodies are not written.
    const auto changes = load(keep) > splat(0.0f);
    const V3<F> next = acc_impulse + p;
    st3(b.impulse,
        V3<F>{select(changes, next.x, acc_impulse.x), select(changes, next.y, acc_impulse.y),
              select(changes, next.z, acc_impulse.z)});
    apply(b, a, bb, p);
    scatter_bodies(acc, s.solver_bodies, false, a);
    scatter_bodies(acc, s.solver_bodies, true, bb);
  }
}

void project_point_batches(WorldScratch& s) {
  const F limit = splat(kMaxProjection);
  const F neg_limit = splat(-kMaxProjection);
  const auto clamp = [&](F v) {
    return select(v > limit, limit, select(v < neg_limit, neg_limit, v));
  };
  for (const PointBatch& b : s.point_batches) {
    LanePositions pa = gather_positions(b, s.solver_bodies, false);
    LanePositions pb = gather_positions(b, s.solver_bodies, true);
    const V3<F> ra_now = rotate_lanes(pa.q, ld3(b.anchor_a));
    const V3<F> rb_now = rotate_lanes(pb.q, ld3(b.anchor_b));
    const V3<F> d = ((pb.p - pa.p) + ld3(b.delta_center)) + (rb_now - ra_now);
    const V3<F> error{clamp(d.x), clamp(d.y), clamp(d.z)};
    const V3<F> e = inv_k_times(b, error);
    const V3<F> x{splat(0.0f) - e.x, splat(0.0f) - e.y, splat(0.0f) - e.z};
    pa.p = pa.p - x * load(b.mass_a);
    pb.p = pb.p + x * load(b.mass_b);
    const V3<F> wa = turn(b.turn_a, x);
    pa.q = integrate_lanes(pa.q, V3<F>{splat(0.0f) - wa.x, splat(0.0f) - wa.y, splat(0.0f) - wa.z});
    pb.q = integrate_lanes(pb.q, turn(b.turn_b, x));
    scatter_positions(b, s.solver_bodies, false, pa);
    scatter_positions(b, s.solver_bodies, true, pb);
  }
}

void sum_point_batches(WorldScratch& s) {
  for (PointBatch& b : s.point_batches) {
    for (int d = 0; d < 3; ++d) {
      for (int i = 0; i < kLanes; ++i) b.tick_impulse[d][i] += b.impulse[d][i];
    }
  }
}

void store_point_batches(WorldScratch& s, int substeps) {
  for (const PointBatch& b : s.point_batches) {
    for (int i = 0; i < kLanes; ++i) {
      if (b.joint[i] == kNoPointJoint) continue;
      JointConstraint& c = s.joint_constraints[b.joint[i]];
      c.linear_impulse = {b.impulse[0][i], b.impulse[1][i], b.impulse[2][i]};
      c.tick_linear = {b.tick_impulse[0][i], b.tick_impulse[1][i], b.tick_impulse[2][i]};
      // (The angular impulse a point joint holds, from a loaded state, is
      // summed as the other joints' are.)
      for (int k = 0; k < substeps; ++k) c.tick_angular += c.angular_impulse;
    }
  }
}

}  // namespace rwd::sim::d3
