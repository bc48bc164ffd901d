// SPDX-License-Identifier: MIT
// Point joints in the solver's lanes (joint_point_batches.h): colouring and
// packing, and the stages of joint_point.cpp written once for kLanes lanes.
#include "d3/joint_point_batches.h"

#include "d3/contact_lane_bodies.h"
#include "d3/joint_angular_lanes.h"
#include "d3/joint_lanes.h"
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

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

namespace {

uint8_t point_kind(const JointRecord& j, const JointConstraint& c) {
  if (!c.angular) return kPointBare;
  return j.type == JointType::kHinge ? kPointHinge : kPointBall;
}

// A fresh batch of `kind` (its part batch too), every lane empty.
uint32_t open_batch(WorldScratch& s, uint8_t kind) {
  PointBatch& fresh = s.point_batches.emplace_back();
  fresh.kind = kind;
  fresh.part = 0;
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
  const auto index = static_cast<uint32_t>(s.point_batches.size() - 1);
  if (kind == kPointBall) {
    s.ball_batches.push_back(index);
    fresh.part = static_cast<uint32_t>(s.ball_parts.size());
    BallPartBatch& part = s.ball_parts.emplace_back();
    for (int i = 0; i < kLanes; ++i) clear_ball_lane(part, i);
  } else if (kind == kPointHinge) {
    s.hinge_batches.push_back(index);
    fresh.part = static_cast<uint32_t>(s.hinge_parts.size());
    HingePartBatch& part = s.hinge_parts.emplace_back();
    for (int i = 0; i < kLanes; ++i) clear_hinge_lane(part, i);
  }
  return index;
}

}  // namespace

void build_point_batches(const WorldState& state, WorldScratch& s) {
  s.point_batches.clear();
  s.ball_parts.clear();
  s.hinge_parts.clear();
  s.ball_batches.clear();
  s.hinge_batches.clear();
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
  // Colour by colour, in slot order within a colour, kLanes of one kind to
  // a batch: the batched joints sorted by colour in one counting pass.
  // (The joints of a colour share no movable body, so how they are
  // grouped into batches within it changes no result.)
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
  constexpr int kKinds = 3;
  for (uint32_t col = 0; col < kColorCount; ++col) {
    uint32_t open[kKinds] = {};
    int lane[kKinds] = {kLanes, kLanes, kLanes};
    for (uint32_t q = s.point_color_start[col]; q < s.point_color_start[col + 1]; ++q) {
      const uint32_t k = s.point_color_order[q];
      const JointConstraint& c = joints[k];
      const JointRecord& j = state.joints[c.record];
      const uint8_t kind = point_kind(j, c);
      if (lane[kind] == kLanes) {
        open[kind] = open_batch(s, kind);
        lane[kind] = 0;
      }
      PointBatch& b = s.point_batches[open[kind]];
      const int i = lane[kind]++;
      b.joint[i] = k;
      b.body_a[i] = c.body_a;
      b.body_b[i] = c.body_b;
      b.movable_a[i] = s.solver_bodies[c.body_a].inv_mass != 0.0f ? 1 : 0;
      b.movable_b[i] = s.solver_bodies[c.body_b].inv_mass != 0.0f ? 1 : 0;
      const Vec3 v[3] = {c.anchor_a, c.anchor_b, c.delta_center};
      float(*dst[3])[kLanes] = {b.anchor_a, b.anchor_b, b.delta_center};
      for (int f = 0; f < 3; ++f) {
        dst[f][0][i] = v[f].x;
        dst[f][1][i] = v[f].y;
        dst[f][2][i] = v[f].z;
      }
      b.impulse[0][i] = c.linear_impulse.x;
      b.impulse[1][i] = c.linear_impulse.y;
      b.impulse[2][i] = c.linear_impulse.z;
      if (kind == kPointBall) pack_ball_lane(s.ball_parts[b.part], i, j, c);
      if (kind == kPointHinge) pack_hinge_lane(s.hinge_parts[b.part], i, j, c);
    }
  }
  // Every batched joint has the same softness and substep (prepare_joints).
  for (const JointConstraint& c : joints) {
    if (c.batched) {
      s.point_soft = c.soft;
      s.point_h = c.h;
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
    const F k6[6] = {c00 * inv, c01 * inv, c02 * inv, c11 * inv, c12 * inv, c22 * inv};
    for (int q = 0; q < 6; ++q) store(b.inv_k[q], k6[q]);
  }
  // The angular parts against the points just made, in loops of their own
  // (a test of each batch's kind in the loop above slowed a grid of bare
  // points by a percent or two).
  for (const std::vector<uint32_t>* kind : {&s.ball_batches, &s.hinge_batches}) {
    for (const uint32_t index : *kind) {
      const PointBatch& b = s.point_batches[index];
      const PointAccess acc{&b};
      const LaneInertia<F> ia = gather_inertia(acc, s.solver_bodies, false);
      const LaneInertia<F> ib = gather_inertia(acc, s.solver_bodies, true);
      const LanePositions pa = gather_positions(b, s.solver_bodies, false);
      const LanePositions pb = gather_positions(b, s.solver_bodies, true);
      V3<F> ta[3];
      V3<F> tb[3];
      for (int j = 0; j < 3; ++j) {
        ta[j] = {load(b.turn_a[3 * j]), load(b.turn_a[3 * j + 1]), load(b.turn_a[3 * j + 2])};
        tb[j] = {load(b.turn_b[3 * j]), load(b.turn_b[3 * j + 1]), load(b.turn_b[3 * j + 2])};
      }
      const PointLanes pt{ld3(b.ra),
                          ld3(b.rb),
                          load(b.mass_a),
                          load(b.mass_b),
                          ia,
                          ib,
                          {ta[0], ta[1], ta[2]},
                          {tb[0], tb[1], tb[2]},
                          {load(b.inv_k[0]), load(b.inv_k[1]), load(b.inv_k[2]), load(b.inv_k[3]),
                           load(b.inv_k[4]), load(b.inv_k[5])}};
      if (b.kind == kPointBall) {
        refresh_ball_lanes(s.ball_parts[b.part], pt, pa.q, pb.q);
      } else {
        refresh_hinge_lanes(s.hinge_parts[b.part], pt, pa.q, pb.q);
      }
    }
  }
}

void warm_start_angular_batches(WorldScratch& s) {
  for (const std::vector<uint32_t>* kind : {&s.ball_batches, &s.hinge_batches}) {
    for (const uint32_t index : *kind) {
      const PointBatch& b = s.point_batches[index];
      const PointAccess acc{&b};
      LaneBodies<F> a = gather_bodies(acc, s.solver_bodies, false);
      LaneBodies<F> bb = gather_bodies(acc, s.solver_bodies, true);
      if (b.kind == kPointBall) {
        warm_start_ball_lanes(s.ball_parts[b.part], a, bb);
      } else {
        warm_start_hinge_lanes(s.hinge_parts[b.part], a, bb);
      }
      scatter_bodies(acc, s.solver_bodies, false, a);
      scatter_bodies(acc, s.solver_bodies, true, bb);
    }
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

namespace {

// The lanes a pass changes: all of a batch's, or (`contacted_only`) those
// with a body a contact acts on; `keep` 1 for those. False: none.
bool pass_lanes(const WorldScratch& s, const PointBatch& b, bool contacted_only, PointAccess& acc,
                float (&keep)[kLanes]) {
  if (!contacted_only) {
    for (float& k : keep) k = 1.0f;
    return true;
  }
  acc.active = 0;
  for (int i = 0; i < kLanes; ++i) {
    const bool hit = b.joint[i] != kNoPointJoint && (s.solver_bodies[b.body_a[i]].contacted ||
                                                     s.solver_bodies[b.body_b[i]].contacted);
    acc.active = static_cast<uint8_t>(acc.active | (hit ? 1u << i : 0u));
    keep[i] = hit ? 1.0f : 0.0f;
  }
  return acc.active != 0;
}

}  // namespace

void solve_angular_batches(WorldScratch& s, bool use_bias, bool contacted_only) {
  const JointSoftness& soft = s.point_soft;
  const F h = splat(s.point_h);
  const bool at_refresh = s.joint_frames_fresh;
  // The ball joints' parts first, then the hinges': a hinge's limit (an
  // elbow's, a knee's) ends the angular pass holding. The other way round
  // the shoulders' and hips' friction and cones, solved after, turned the
  // upper limbs against the elbows and knees just held: a running figure
  // handed over to the simulation bent an elbow 2 degrees backwards
  // (0.1 degree this way).
  for (const std::vector<uint32_t>* kind : {&s.ball_batches, &s.hinge_batches}) {
    for (const uint32_t index : *kind) {
      PointBatch& b = s.point_batches[index];
      PointAccess acc{&b};
      alignas(16) float keep[kLanes];  // 1: the lane's impulses change
      if (!pass_lanes(s, b, contacted_only, acc, keep)) continue;
      LaneBodies<F> a = gather_bodies(acc, s.solver_bodies, false);
      LaneBodies<F> bb = gather_bodies(acc, s.solver_bodies, true);
      // A lane left out keeps its impulses, and its bodies are not written.
      const auto changes = load(keep) > splat(0.0f);
      if (b.kind == kPointBall) {
        solve_ball_lanes(s.ball_parts[b.part], soft, h, use_bias, at_refresh, changes, a, bb);
      } else {
        solve_hinge_lanes(s.hinge_parts[b.part], soft, h, use_bias, at_refresh, changes, a, bb);
      }
      scatter_bodies(acc, s.solver_bodies, false, a);
      scatter_bodies(acc, s.solver_bodies, true, bb);
    }
  }
}

void solve_point_batches(WorldScratch& s, bool use_bias, bool contacted_only) {
  const JointSoftness& soft = s.point_soft;
  for (PointBatch& b : s.point_batches) {
    PointAccess acc{&b};
    alignas(16) float keep[kLanes];  // 1: the lane's impulse changes
    if (!pass_lanes(s, b, contacted_only, acc, keep)) continue;
    LaneBodies<F> a = gather_bodies(acc, s.solver_bodies, false);
    LaneBodies<F> bb = gather_bodies(acc, s.solver_bodies, true);
    // A lane left out keeps its impulse, and its bodies are not written.
    const auto changes = load(keep) > splat(0.0f);
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
    const V3<F> next = acc_impulse + p;
    st3(b.impulse,
        V3<F>{select(changes, next.x, acc_impulse.x), select(changes, next.y, acc_impulse.y),
              select(changes, next.z, acc_impulse.z)});
    apply(b, a, bb, p);
    scatter_bodies(acc, s.solver_bodies, false, a);
    scatter_bodies(acc, s.solver_bodies, true, bb);
  }
}

void project_angular_batches(WorldScratch& s) {
  const F zero = splat(0.0f);
  for (const uint32_t index : s.hinge_batches) {
    const PointBatch& b = s.point_batches[index];
    LanePositions pa = gather_positions(b, s.solver_bodies, false);
    LanePositions pb = gather_positions(b, s.solver_bodies, true);
    project_hinge_lanes(s.hinge_parts[b.part], load(b.mass_a) > zero, load(b.mass_b) > zero, pa,
                        pb);
    scatter_positions(b, s.solver_bodies, false, pa);
    scatter_positions(b, s.solver_bodies, true, pb);
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
  for (HingePartBatch& p : s.hinge_parts) sum_hinge_part(p);
}

void store_point_batches(WorldScratch& s, int substeps) {
  for (const PointBatch& b : s.point_batches) {
    for (int i = 0; i < kLanes; ++i) {
      if (b.joint[i] == kNoPointJoint) continue;
      JointConstraint& c = s.joint_constraints[b.joint[i]];
      c.linear_impulse = {b.impulse[0][i], b.impulse[1][i], b.impulse[2][i]};
      c.tick_linear = {b.tick_impulse[0][i], b.tick_impulse[1][i], b.tick_impulse[2][i]};
      if (b.kind == kPointHinge) {
        // Its turns' impulses, and their sums over the tick.
        store_hinge_lane(s.hinge_parts[b.part], i, c);
        continue;
      }
      if (b.kind == kPointBall) store_ball_lane(s.ball_parts[b.part], i, c);
      // (The angular impulse a point joint or a ball joint's angular part
      // holds, from a loaded state, is summed as the other joints' are.)
      for (int k = 0; k < substeps; ++k) c.tick_angular += c.angular_impulse;
    }
  }
}

}  // namespace rwd::sim::d3
