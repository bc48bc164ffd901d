// SPDX-License-Identifier: MIT
#pragma once
// The solver's passes over contact batches, written once for any lane type:
// four lanes over half a batch (contact_batches.cpp: SSE2, NEON or plain
// arrays) or eight over a whole batch (contact_lanes_avx.cpp: AVX, chosen at
// run time). A batch's constraints share no movable body, so solving its
// halves at once is solving them one after the other: the lane count cannot
// change a result.
//
// An access type A says where the lanes come from:
//   A::F                  the lane type (+ - * /, < >, select, sqrt by ADL)
//   A::kWidth             lanes
//   A::kSettles           the normal block's sweeps stop once one changes
//                         nothing (then A::bits(v): a lane's float's bits)
//   A::splat(x)           x in every lane
//   A::from(p), A::to(p)  kWidth contiguous floats
//   acc.ld(field)         the access's lanes of a [kBatchLanes] field
//   acc.st(field, v)
//   acc.body_a(lane)      solver body of a lane (body_b likewise)
//   acc.first()           the batch, whose fields name what to load
//   acc.movable_a(lane)   whether the lane's body can move (movable_b likewise)
//   A::gather_rows(rows, out), A::scatter_rows(in, rows)
//                         kWidth solver-body rows of eight floats into eight
//                         lane values and back
//
// Everything here has internal linkage: each file that includes it compiles
// its own copy for its own instruction set.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "d3/contact_batches.h"
#include "d3/contact_lane_bodies.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// What the passes keep fixed for the step, from the packed anchors and
// axes: the inverse-inertia products of each point's Jacobian, the tangent
// masses, the normal K matrix and from its diagonal the normal masses.
// Points past a lane's count get exact zeros, as if never there.
template <uint32_t N, class A>
void prepare_lanes(const A& acc, const std::vector<SolverBody>& bodies) {
  using F = typename A::F;
  ContactBatch& batch = acc.first();
  const F zero = A::splat(0.0f);
  const F mass_sum =
      gather_bodies(acc, bodies, false).inv_mass + gather_bodies(acc, bodies, true).inv_mass;
  const LaneInertia<F> ia = gather_inertia(acc, bodies, false);
  const LaneInertia<F> ib = gather_inertia(acc, bodies, true);
  const V3<F> n = ld3(acc, batch.normal);
  const V3<F> t1 = ld3(acc, batch.tangent1);
  const V3<F> t2 = ld3(acc, batch.tangent2);
  const F count = acc.ld(batch.point_count);
  V3<F> rn_a[kMaxManifoldPoints];
  V3<F> rn_b[kMaxManifoldPoints];
  V3<F> in_a[kMaxManifoldPoints];
  V3<F> in_b[kMaxManifoldPoints];
  for (uint32_t p = 0; p < N; ++p) {
    ContactBatch::Point& bp = batch.points[p];
    const auto real = A::splat(static_cast<float>(p)) < count;
    const auto keep = [&](const V3<F>& v) {
      return V3<F>{select(real, v.x, zero), select(real, v.y, zero), select(real, v.z, zero)};
    };
    const V3<F> ra = ld3(acc, bp.anchor_a);
    const V3<F> rb = ld3(acc, bp.anchor_b);
    rn_a[p] = cross3(ra, n);
    rn_b[p] = cross3(rb, n);
    in_a[p] = keep(mul(ia, rn_a[p]));
    in_b[p] = keep(mul(ib, rn_b[p]));
    const V3<F> rt1_a = cross3(ra, t1);
    const V3<F> rt1_b = cross3(rb, t1);
    const V3<F> rt2_a = cross3(ra, t2);
    const V3<F> rt2_b = cross3(rb, t2);
    const V3<F> it1_a = keep(mul(ia, rt1_a));
    const V3<F> it1_b = keep(mul(ib, rt1_b));
    const V3<F> it2_a = keep(mul(ia, rt2_a));
    const V3<F> it2_b = keep(mul(ib, rt2_b));
    st3(acc, bp.in_a, in_a[p]);
    st3(acc, bp.in_b, in_b[p]);
    st3(acc, bp.it1_a, it1_a);
    st3(acc, bp.it1_b, it1_b);
    st3(acc, bp.it2_a, it2_a);
    st3(acc, bp.it2_b, it2_b);
    // The effective mass along each tangent at the point.
    const F k1 = mass_sum + dot3(rt1_a, it1_a) + dot3(rt1_b, it1_b);
    const F k2 = mass_sum + dot3(rt2_a, it2_a) + dot3(rt2_b, it2_b);
    acc.st(bp.tangent_mass1, select(real, inverse_or_zero<A>(k1), zero));
    acc.st(bp.tangent_mass2, select(real, inverse_or_zero<A>(k2), zero));
  }
  for (uint32_t i = 0; i < N; ++i) {
    const auto real_i = A::splat(static_cast<float>(i)) < count;
    for (uint32_t j = 0; j < N; ++j) {
      const auto real_j = A::splat(static_cast<float>(j)) < count;
      const F k = mass_sum + dot3(rn_a[j], in_a[i]) + dot3(rn_b[j], in_b[i]);
      acc.st(batch.coupling[i][j], select(real_i, select(real_j, k, zero), zero));
    }
    const F diagonal = acc.ld(batch.coupling[i][i]);
    acc.st(batch.points[i].normal_mass, inverse_or_zero<A>(diagonal));
  }
}

template <uint32_t N, class A>
void warm_start_lanes(const A& acc, std::vector<SolverBody>& bodies) {
  using F = typename A::F;
  ContactBatch& batch = acc.first();
  LaneBodies<F> a = gather_bodies(acc, bodies, false);
  LaneBodies<F> b = gather_bodies(acc, bodies, true);
  const V3<F> n = ld3(acc, batch.normal);
  const V3<F> t1 = ld3(acc, batch.tangent1);
  const V3<F> t2 = ld3(acc, batch.tangent2);
  const F zero = A::splat(0.0f);
  V3<F> linear{zero, zero, zero};
  V3<F> turn_a = linear;
  V3<F> turn_b = linear;
  for (uint32_t k = 0; k < N; ++k) {
    ContactBatch::Point& p = batch.points[k];
    const F ln = acc.ld(p.normal_impulse);
    acc.st(p.tick_normal_impulse, acc.ld(p.tick_normal_impulse) + ln);
    const F l1 = acc.ld(p.tangent_impulse1);
    const F l2 = acc.ld(p.tangent_impulse2);
    linear = linear + (n * ln + t1 * l1 + t2 * l2);
    turn_a = turn_a + (ld3(acc, p.in_a) * ln + ld3(acc, p.it1_a) * l1 + ld3(acc, p.it2_a) * l2);
    turn_b = turn_b + (ld3(acc, p.in_b) * ln + ld3(acc, p.it1_b) * l1 + ld3(acc, p.it2_b) * l2);
  }
  a.v = a.v - linear * a.inv_mass;
  a.w = a.w - turn_a;
  b.v = b.v + linear * b.inv_mass;
  b.w = b.w + turn_b;
  scatter_bodies(acc, bodies, false, a);
  scatter_bodies(acc, bodies, true, b);
}

// A point's Jacobian angular parts (anchor x normal, both sides) and the
// normal velocity of b relative to a there.
template <class A>
[[gnu::always_inline]] inline typename A::F normal_velocity(
    const A& acc, const ContactBatch::Point& bp, const V3<typename A::F>& n,
    const LaneBodies<typename A::F>& a, const LaneBodies<typename A::F>& b, V3<typename A::F>& rn_a,
    V3<typename A::F>& rn_b) {
  rn_a = cross3(ld3(acc, bp.anchor_a), n);
  rn_b = cross3(ld3(acc, bp.anchor_b), n);
  return dot3(b.v - a.v, n) + dot3(rn_b, b.w) - dot3(rn_a, a.w);
}

// Sweeps over a manifold's normal block: one for a bound of one point, as
// a lone point is solved by the first sweep and the later ones would only
// move it by rounding (they run with a gain of zero for lone points in
// batches of more, so a lane's result does not depend on its batch).
template <uint32_t N>
inline constexpr int kBlockSweeps = N == 1 ? 1 : kManifoldSweeps;

// One projected Gauss-Seidel step at point p of a manifold's normal
// system (sweep_normal_block).
template <uint32_t N, class A>
[[gnu::always_inline]] inline void sweep_step(const A& acc, const ContactBatch& batch, uint32_t p,
                                              typename A::F gain,
                                              typename A::F (&residual)[kMaxManifoldPoints],
                                              typename A::F (&total)[kMaxManifoldPoints]) {
  using F = typename A::F;
  const F zero = A::splat(0.0f);
  F next = total[p] - gain * residual[p];
  next = select(next < zero, zero, next);
  const F change = next - total[p];
  total[p] = next;
  for (uint32_t j = 0; j < N; ++j) {
    residual[j] = residual[j] + acc.ld(batch.coupling[j][p]) * change;
  }
}

// Whether a sweep that started from `total_before` and `residual_before`
// left both exactly as they were (bit for bit), with no impulse of -0. Every
// later sweep then repeats it exactly and changes nothing either, so the
// sweeps can stop: a sweep step moves an impulse by -gain * residual, and
// with every impulse unchanged each change was +0 (x - x), which leaves
// every residual's bits as they were unless a residual was -0 (the check
// sees that). The later sweeps' gains differ from the first's only for a
// lone point, whose later gain is 0: an impulse x less 0 * residual (+0 or
// -0) is x for every x but -0, which the check excludes. Only the one-lane
// access (a small world's batches) looks, where the test is a few scalar
// compares against a sweep's N * N products; the wide lanes run every sweep
// (all their lanes would have to settle at once).
template <uint32_t N, class A>
[[gnu::always_inline]] inline bool sweep_settled(
    const typename A::F (&total_before)[kMaxManifoldPoints],
    const typename A::F (&residual_before)[kMaxManifoldPoints],
    const typename A::F (&residual)[kMaxManifoldPoints],
    const typename A::F (&total)[kMaxManifoldPoints]) {
  bool settled = true;
  for (uint32_t p = 0; p < N; ++p) {
    const uint32_t t = A::bits(total[p]);
    settled = settled && t == A::bits(total_before[p]) && t != 0x80000000u &&
              A::bits(residual[p]) == A::bits(residual_before[p]);
  }
  return settled;
}

// Projected Gauss-Seidel sweeps over each lane's manifold normal system
// with the bodies held: impulse total[p] (accumulated, >= 0) moves so the
// normal velocity residual[p] reaches zero, the first sweep scaled by
// first_gain[p] and the later ones by later_gain[p]. The residual is kept up
// to date column by column, so no body is touched; the caller applies the
// change once. The one-lane access stops once a sweep changes nothing
// (sweep_settled), with the same result.
template <uint32_t N, class A>
void sweep_normal_block(const A& acc, const ContactBatch& batch,
                        const typename A::F (&first_gain)[kMaxManifoldPoints],
                        const typename A::F (&later_gain)[kMaxManifoldPoints],
                        typename A::F (&residual)[kMaxManifoldPoints],
                        typename A::F (&total)[kMaxManifoldPoints]) {
  // Whether this access looks for a settled sweep (a lone point's one
  // sweep has nothing after it to skip).
  constexpr bool kLooks = A::kSettles && (kBlockSweeps<N>) > 1;
  for (int sweep = 0; sweep < kBlockSweeps<N>; ++sweep) {
    typename A::F total_before[kMaxManifoldPoints];
    typename A::F residual_before[kMaxManifoldPoints];
    if constexpr (kLooks) {
      for (uint32_t p = 0; p < N; ++p) {
        total_before[p] = total[p];
        residual_before[p] = residual[p];
      }
    }
    for (uint32_t p = 0; p < N; ++p) {
      sweep_step<N>(acc, batch, p, sweep == 0 ? first_gain[p] : later_gain[p], residual, total);
    }
    if constexpr (kLooks) {
      if (sweep_settled<N, A>(total_before, residual_before, residual, total)) return;
    }
  }
}

// One pass on the real velocities: the manifold's normal impulses as a
// block (sweeps with the bodies held, the residual kept up to date column
// by column, then one impulse per body; a gap may close within the substep,
// no more), then friction point by point, |t| <= mu * normal impulse.
//
// The pass is split where the bodies are held (begin, sweep, finish), so
// two batches of one colour, or the two halves of a batch, can run their
// sweeps interleaved: the sweeps are a chain of dependent operations per
// point, and two independent chains in flight take little longer than one.
// Batches of one colour share no movable body, so this is the same as
// running them one after the other, bit for bit.
template <class A>
struct SolveLanes {
  using F = typename A::F;
  LaneBodies<F> a;
  LaneBodies<F> b;
  V3<F> n;
  F residual[kMaxManifoldPoints];
  F step[kMaxManifoldPoints];
  F later_step[kMaxManifoldPoints];  ///< step, or 0 for a lone point
  F total[kMaxManifoldPoints];
  F start[kMaxManifoldPoints];
};

template <uint32_t N, class A>
[[gnu::always_inline]] inline void begin_solve(const A& acc, const std::vector<SolverBody>& bodies,
                                               float inv_h, SolveLanes<A>& s) {
  using F = typename A::F;
  const ContactBatch& batch = acc.first();
  const F zero = A::splat(0.0f);
  const F inv_h_w = A::splat(inv_h);
  s.a = gather_bodies(acc, bodies, false);
  s.b = gather_bodies(acc, bodies, true);
  s.n = ld3(acc, batch.normal);
  for (uint32_t p = 0; p < N; ++p) {
    const ContactBatch::Point& bp = batch.points[p];
    const F sep = acc.ld(bp.separation);
    const F bias = select(sep > zero, sep * inv_h_w, zero);  // speculative
    V3<F> rn_a;
    V3<F> rn_b;
    const F vn = normal_velocity(acc, bp, s.n, s.a, s.b, rn_a, rn_b);
    s.residual[p] = vn + bias;
    s.step[p] = acc.ld(bp.normal_mass);
    s.total[p] = acc.ld(bp.normal_impulse);
    s.start[p] = s.total[p];
  }
  // A lone point's later sweeps have no gain (kBlockSweeps).
  const auto several = acc.ld(batch.point_count) > A::splat(1.0f);
  for (uint32_t p = 0; p < N; ++p) s.later_step[p] = select(several, s.step[p], zero);
}

template <uint32_t N, class A>
[[gnu::always_inline]] inline void finish_solve(const A& acc, std::vector<SolverBody>& bodies,
                                                SolveLanes<A>& s) {
  using F = typename A::F;
  ContactBatch& batch = acc.first();
  const F zero = A::splat(0.0f);
  LaneBodies<F>& a = s.a;
  LaneBodies<F>& b = s.b;
  const V3<F>& n = s.n;
  F pushed = zero;
  V3<F> turn_a{zero, zero, zero};
  V3<F> turn_b = turn_a;
  for (uint32_t p = 0; p < N; ++p) {
    ContactBatch::Point& bp = batch.points[p];
    acc.st(bp.normal_impulse, s.total[p]);
    const F max_seen = acc.ld(bp.max_normal_impulse);
    acc.st(bp.max_normal_impulse, select(s.total[p] > max_seen, s.total[p], max_seen));
    const F change = s.total[p] - s.start[p];
    pushed = pushed + change;
    turn_a = turn_a + ld3(acc, bp.in_a) * change;
    turn_b = turn_b + ld3(acc, bp.in_b) * change;
  }
  a.v = a.v - n * (pushed * a.inv_mass);
  a.w = a.w - turn_a;
  b.v = b.v + n * (pushed * b.inv_mass);
  b.w = b.w + turn_b;

  const V3<F> t1 = ld3(acc, batch.tangent1);
  const V3<F> t2 = ld3(acc, batch.tangent2);
  const F mu = acc.ld(batch.friction);
  const F one = A::splat(1.0f);
  for (uint32_t p = 0; p < N; ++p) {
    ContactBatch::Point& bp = batch.points[p];
    const V3<F> ra = ld3(acc, bp.anchor_a);
    const V3<F> rb = ld3(acc, bp.anchor_b);
    const V3<F> rt1_a = cross3(ra, t1);
    const V3<F> rt1_b = cross3(rb, t1);
    const V3<F> rt2_a = cross3(ra, t2);
    const V3<F> rt2_b = cross3(rb, t2);
    const V3<F> dv = b.v - a.v;
    const F v1 = dot3(dv, t1) + dot3(rt1_b, b.w) - dot3(rt1_a, a.w);
    const F v2 = dot3(dv, t2) + dot3(rt2_b, b.w) - dot3(rt2_a, a.w);
    const F old1 = acc.ld(bp.tangent_impulse1);
    const F old2 = acc.ld(bp.tangent_impulse2);
    F f1 = old1 - acc.ld(bp.tangent_mass1) * v1;
    F f2 = old2 - acc.ld(bp.tangent_mass2) * v2;
    const F limit = mu * s.total[p];
    const F len_sq = f1 * f1 + f2 * f2;
    const auto over = len_sq > limit * limit;
    // Lanes under the limit keep their impulse; the others scale onto the
    // cone (len_sq > 0 there).
    const F scale = select(over, limit / sqrt(len_sq), one);
    f1 = select(over, f1 * scale, f1);
    f2 = select(over, f2 * scale, f2);
    acc.st(bp.tangent_impulse1, f1);
    acc.st(bp.tangent_impulse2, f2);
    const F i1 = f1 - old1;
    const F i2 = f2 - old2;
    const V3<F> impulse = t1 * i1 + t2 * i2;
    a.v = a.v - impulse * a.inv_mass;
    a.w = a.w - (ld3(acc, bp.it1_a) * i1 + ld3(acc, bp.it2_a) * i2);
    b.v = b.v + impulse * b.inv_mass;
    b.w = b.w + (ld3(acc, bp.it1_b) * i1 + ld3(acc, bp.it2_b) * i2);
  }
  scatter_bodies(acc, bodies, false, a);
  scatter_bodies(acc, bodies, true, b);
}

template <uint32_t N, class A>
void solve_lanes(const A& acc, std::vector<SolverBody>& bodies, float inv_h) {
  SolveLanes<A> s;
  begin_solve<N>(acc, bodies, inv_h, s);
  const ContactBatch& batch = acc.first();
  sweep_normal_block<N>(acc, batch, s.step, s.later_step, s.residual, s.total);
  finish_solve<N>(acc, bodies, s);
}

// solve_lanes on two accesses whose movable bodies differ (two batches of
// one colour with the same point bound, or a batch's two halves), their
// sweeps interleaved.
template <uint32_t N, class A>
void solve_lanes_pair(const A& first, const A& second, std::vector<SolverBody>& bodies,
                      float inv_h) {
  SolveLanes<A> s1;
  SolveLanes<A> s2;
  begin_solve<N>(first, bodies, inv_h, s1);
  begin_solve<N>(second, bodies, inv_h, s2);
  const ContactBatch& batch1 = first.first();
  const ContactBatch& batch2 = second.first();
  for (int sweep = 0; sweep < kBlockSweeps<N>; ++sweep) {
    for (uint32_t p = 0; p < N; ++p) {
      sweep_step<N>(first, batch1, p, sweep == 0 ? s1.step[p] : s1.later_step[p], s1.residual,
                    s1.total);
      sweep_step<N>(second, batch2, p, sweep == 0 ? s2.step[p] : s2.later_step[p], s2.residual,
                    s2.total);
    }
  }
  finish_solve<N>(first, bodies, s1);
  finish_solve<N>(second, bodies, s2);
}

// One pass of the push-out on the push velocities: overlaps deeper than the
// slop are pushed apart at the contact's bias rate, at most at the speed
// cap, and a gap may close no faster than it would in the real pass. As in
// the real pass, a manifold's points are solved as a block (one sweep for a
// single point), each step scaled by the softness's mass scale; the
// impulses accumulate over the tick's substeps. A lane takes part only when
// it overlaps or one of its bodies already moves on push velocities, and
// never when its overlap is deep (push_out_deep held it).
template <uint32_t N, class A>
void push_lanes(const A& acc, std::vector<SolverBody>& bodies, const PushSettings& push) {
  using F = typename A::F;
  ContactBatch& batch = acc.first();
  const F zero = A::splat(0.0f);
  const F one = A::splat(1.0f);
  LaneBodies<F> a = gather_bodies(acc, bodies, false, kPushRow);
  LaneBodies<F> b = gather_bodies(acc, bodies, true, kPushRow);
  const V3<F> n = ld3(acc, batch.normal);
  const F count = acc.ld(batch.point_count);
  const F rate = acc.ld(batch.push_rate);
  const F scale = acc.ld(batch.push_mass_scale);
  const F inv_h = A::splat(push.inv_h);
  const F slop = A::splat(push.slop);
  const F cap = A::splat(-push.max_speed);
  F deepest = zero;
  F overlapping = zero;
  F residual[kMaxManifoldPoints];
  F step[kMaxManifoldPoints];
  F total[kMaxManifoldPoints];
  F start[kMaxManifoldPoints];
  V3<F> rn_a[kMaxManifoldPoints];
  V3<F> rn_b[kMaxManifoldPoints];
  for (uint32_t p = 0; p < N; ++p) {
    const ContactBatch::Point& bp = batch.points[p];
    const auto real = A::splat(static_cast<float>(p)) < count;
    const F s = acc.ld(bp.separation);
    const F depth = s + slop;  // overlap up to the slop is allowed
    const F pushing = rate * depth;
    const F bias = select(depth < zero, select(pushing < cap, cap, pushing),
                          select(s > zero, s * inv_h, zero));
    deepest = select(real, select(depth < deepest, depth, deepest), deepest);
    overlapping = select(real, select(depth < zero, one, overlapping), overlapping);
    const F vn = normal_velocity(acc, bp, n, a, b, rn_a[p], rn_b[p]);
    residual[p] = vn + bias;
    step[p] = acc.ld(bp.normal_mass) * scale;
    total[p] = acc.ld(bp.push_impulse);
    start[p] = total[p];
  }
  // Single points converge in one sweep; further sweeps leave them be.
  const auto several = count > one;
  F later_step[kMaxManifoldPoints];
  for (uint32_t p = 0; p < N; ++p) later_step[p] = select(several, step[p], zero);
  sweep_normal_block<N>(acc, batch, step, later_step, residual, total);
  const F shallow = select(deepest < A::splat(push.deep_limit), zero, one);
  const F wanted = select(overlapping + a.rest + b.rest > zero, shallow, zero);
  const auto active = wanted > zero;
  F pushed = zero;
  F moved = zero;
  V3<F> turn_a{zero, zero, zero};
  V3<F> turn_b = turn_a;
  for (uint32_t p = 0; p < N; ++p) {
    ContactBatch::Point& bp = batch.points[p];
    const F change = select(active, total[p] - start[p], zero);
    acc.st(bp.push_impulse, start[p] + change);
    pushed = pushed + change;
    moved = select(change < zero, one, select(change > zero, one, moved));
    turn_a = turn_a + ld3(acc, bp.in_a) * change;
    turn_b = turn_b + ld3(acc, bp.in_b) * change;
  }
  a.v = a.v - n * (pushed * a.inv_mass);
  a.w = a.w - turn_a;
  b.v = b.v + n * (pushed * b.inv_mass);
  b.w = b.w + turn_b;
  a.rest = select(moved > zero, one, a.rest);
  b.rest = select(moved > zero, one, b.rest);
  scatter_bodies(acc, bodies, false, a, kPushRow);
  scatter_bodies(acc, bodies, true, b, kPushRow);
}

// Runs fn(std::integral_constant<uint32_t, N>) with N the batch's point
// bound (1 to kMaxManifoldPoints), so each pass is compiled for exactly the
// points its batch holds. The bound belongs to the whole batch, so every
// lane width runs the same points.
template <class Fn>
void for_point_bound(const ContactBatch& batch, Fn&& fn) {
  switch (batch.point_bound) {
    case 1:
      fn(std::integral_constant<uint32_t, 1>{});
      break;
    case 2:
      fn(std::integral_constant<uint32_t, 2>{});
      break;
    case 3:
      fn(std::integral_constant<uint32_t, 3>{});
      break;
    default:
      fn(std::integral_constant<uint32_t, kMaxManifoldPoints>{});
      break;
  }
}

// q rotating v, per lane, as rotate() in math.h.
template <class A>
[[gnu::always_inline]] inline V3<typename A::F> rotate_lanes(const typename A::F (&q)[4],
                                                             const V3<typename A::F>& v) {
  using F = typename A::F;
  const V3<F> u{q[0], q[1], q[2]};
  const V3<F> uv = cross3(u, v);
  const F two = A::splat(2.0f);
  const V3<F> t{two * uv.x, two * uv.y, two * uv.z};
  const V3<F> wt{q[3] * t.x, q[3] * t.y, q[3] * t.z};
  return v + wt + cross3(u, t);
}

// Each point's separation from the motion since the tick began (the
// batches only; the caller copies them to the scalar constraints).
template <uint32_t N, class A>
void separations_lanes(const A& acc, const std::vector<SolverBody>& bodies) {
  using F = typename A::F;
  ContactBatch& batch = acc.first();
  alignas(32) float f[14][A::kWidth];
  for (int i = 0; i < A::kWidth; ++i) {
    const SolverBody& a = bodies[acc.body_a(i)];
    const SolverBody& b = bodies[acc.body_b(i)];
    const float values[14] = {a.delta_position.x, a.delta_position.y, a.delta_position.z,
                              a.delta_rotation.x, a.delta_rotation.y, a.delta_rotation.z,
                              a.delta_rotation.w, b.delta_position.x, b.delta_position.y,
                              b.delta_position.z, b.delta_rotation.x, b.delta_rotation.y,
                              b.delta_rotation.z, b.delta_rotation.w};
    for (int k = 0; k < 14; ++k) f[k][i] = values[k];
  }
  const V3<F> pos_a{A::from(f[0]), A::from(f[1]), A::from(f[2])};
  const F rot_a[4] = {A::from(f[3]), A::from(f[4]), A::from(f[5]), A::from(f[6])};
  const V3<F> pos_b{A::from(f[7]), A::from(f[8]), A::from(f[9])};
  const F rot_b[4] = {A::from(f[10]), A::from(f[11]), A::from(f[12]), A::from(f[13])};
  const V3<F> dp = pos_b - pos_a;
  const V3<F> n = ld3(acc, batch.normal);
  for (uint32_t k = 0; k < N; ++k) {
    ContactBatch::Point& bp = batch.points[k];
    const V3<F> pa = rotate_lanes<A>(rot_a, ld3(acc, bp.anchor_a));
    const V3<F> pb = rotate_lanes<A>(rot_b, ld3(acc, bp.anchor_b));
    acc.st(bp.separation, dot3(dp + (pb - pa), n) + acc.ld(bp.base_separation));
  }
}

}  // namespace

#if defined(REWIND_LANES_AVX)
/// Eight lanes over a whole batch (contact_lanes_avx.cpp); only call when
/// lanes8_available().
bool lanes8_available();
void prepare_full(ContactBatch& batch, const std::vector<SolverBody>& bodies);
void warm_start_full(ContactBatch& batch, std::vector<SolverBody>& bodies);
void solve_full(ContactBatch& batch, std::vector<SolverBody>& bodies, float inv_h);
/// solve_full on two batches of one colour with the same point bound.
void solve_full_pair(ContactBatch& first, ContactBatch& second, std::vector<SolverBody>& bodies,
                     float inv_h);
void separations_full(ContactBatch& batch, const std::vector<SolverBody>& bodies);
void push_full(ContactBatch& batch, std::vector<SolverBody>& bodies, const PushSettings& push);
#endif

}  // namespace rwd::sim::d3
