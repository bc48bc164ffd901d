// SPDX-License-Identifier: MIT
// The solver's wide passes over coloured batches of four contacts (see
// contact_batches.h for the colouring). Per batch: gather the bodies'
// velocities into lanes, solve, scatter them back. The arithmetic is the
// scalar solver's, written once for four lanes (wide_float.h), so a lane
// computes what one contact alone would.
#include "d3/contact_batches.h"

#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

FloatW lane_load(const float (&a)[kLanes]) {
  return load(a);
}
Vec3W lane_load(const float (&a)[3][kLanes]) {
  return {load(a[0]), load(a[1]), load(a[2])};
}
void lane_store(float (&a)[kLanes], FloatW v) {
  store(a, v);
}

// The velocities of four bodies, one per lane.
struct BodiesW {
  Vec3W v;
  Vec3W w;
  FloatW inv_mass;
};

BodiesW gather(const std::vector<SolverBody>& bodies, const uint32_t (&index)[kLanes]) {
  alignas(16) float f[7][kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const SolverBody& b = bodies[index[i]];
    f[0][i] = b.linear_velocity.x;
    f[1][i] = b.linear_velocity.y;
    f[2][i] = b.linear_velocity.z;
    f[3][i] = b.angular_velocity.x;
    f[4][i] = b.angular_velocity.y;
    f[5][i] = b.angular_velocity.z;
    f[6][i] = b.inv_mass;
  }
  return {{load(f[0]), load(f[1]), load(f[2])}, {load(f[3]), load(f[4]), load(f[5])}, load(f[6])};
}

// Writes the lanes' velocities back to the bodies that can move. A movable
// body is in at most one lane of a batch; a body that cannot move (static,
// sleeping, kinematic) may be in several and is never written, so no lane
// order or lane count can leave a different signed zero in it.
void scatter(std::vector<SolverBody>& bodies, const uint32_t (&index)[kLanes], const BodiesW& b) {
  alignas(16) float f[6][kLanes];
  store(f[0], b.v.x);
  store(f[1], b.v.y);
  store(f[2], b.v.z);
  store(f[3], b.w.x);
  store(f[4], b.w.y);
  store(f[5], b.w.z);
  for (int i = 0; i < kLanes; ++i) {
    SolverBody& s = bodies[index[i]];
    if (s.inv_mass == 0.0f) continue;
    s.linear_velocity = {f[0][i], f[1][i], f[2][i]};
    s.angular_velocity = {f[3][i], f[4][i], f[5][i]};
  }
}

FloatW clamp_at_zero(FloatW x) {
  const FloatW zero = splat(0.0f);
  return select(x < zero, zero, x);
}

// --- colouring ---------------------------------------------------------

// Sets the colour of every constraint; kColorCount for those that fit none.
void color(WorldScratch& scratch) {
  const size_t words = (scratch.solver_bodies.size() + 63) / 64;
  scratch.color_bits.assign(words * kColorCount, 0);
  scratch.color_of.resize(scratch.constraints.size());
  for (size_t k = 0; k < scratch.constraints.size(); ++k) {
    const ContactConstraint& c = scratch.constraints[k];
    const bool movable_a = scratch.solver_bodies[c.body_a].inv_mass != 0.0f;
    const bool movable_b = scratch.solver_bodies[c.body_b].inv_mass != 0.0f;
    uint32_t chosen = kColorCount;
    for (uint32_t col = 0; col < kColorCount; ++col) {
      uint64_t* bits = &scratch.color_bits[col * words];
      const bool used_a = movable_a && (bits[c.body_a / 64] >> (c.body_a % 64) & 1u) != 0;
      const bool used_b = movable_b && (bits[c.body_b / 64] >> (c.body_b % 64) & 1u) != 0;
      if (used_a || used_b) continue;
      if (movable_a) bits[c.body_a / 64] |= uint64_t{1} << (c.body_a % 64);
      if (movable_b) bits[c.body_b / 64] |= uint64_t{1} << (c.body_b % 64);
      chosen = col;
      break;
    }
    scratch.color_of[k] = chosen;
  }
}

void clear_point(ContactBatch::Point& p, int lane) {
  for (float(*v)[kLanes] : {p.anchor_a, p.anchor_b, p.rn_a, p.rn_b, p.rt1_a, p.rt1_b, p.rt2_a,
                            p.rt2_b, p.in_a, p.in_b, p.it1_a, p.it1_b, p.it2_a, p.it2_b}) {
    for (int i = 0; i < 3; ++i) v[i][lane] = 0.0f;
  }
  p.base_separation[lane] = 0.0f;
  p.separation[lane] = 0.0f;
  p.normal_mass[lane] = 0.0f;
  p.tangent_mass1[lane] = 0.0f;
  p.tangent_mass2[lane] = 0.0f;
  p.normal_impulse[lane] = 0.0f;
  p.tangent_impulse1[lane] = 0.0f;
  p.tangent_impulse2[lane] = 0.0f;
  p.max_normal_impulse[lane] = 0.0f;
}

void clear_lane(ContactBatch& batch, int lane) {
  batch.constraint[lane] = kNoConstraint;
  batch.body_a[lane] = 0;
  batch.body_b[lane] = 0;
  for (int i = 0; i < 3; ++i) {
    batch.normal[i][lane] = 0.0f;
    batch.tangent1[i][lane] = 0.0f;
    batch.tangent2[i][lane] = 0.0f;
  }
  batch.friction[lane] = 0.0f;
  for (ContactBatch::Point& p : batch.points) clear_point(p, lane);
  for (auto& row : batch.coupling) {
    for (auto& k : row) k[lane] = 0.0f;
  }
}

void put(float (&dst)[3][kLanes], int lane, Vec3 v) {
  dst[0][lane] = v.x;
  dst[1][lane] = v.y;
  dst[2][lane] = v.z;
}

void fill_lane(ContactBatch& batch, int lane, uint32_t index, const ContactConstraint& c,
               const std::vector<SolverBody>& bodies) {
  const SolverBody& body_a = bodies[c.body_a];
  const SolverBody& body_b = bodies[c.body_b];
  batch.constraint[lane] = index;
  batch.body_a[lane] = c.body_a;
  batch.body_b[lane] = c.body_b;
  const Vec3 axes[3] = {c.normal, c.tangent1, c.tangent2};
  float(*dst[3])[kLanes] = {batch.normal, batch.tangent1, batch.tangent2};
  for (int a = 0; a < 3; ++a) {
    dst[a][0][lane] = axes[a].x;
    dst[a][1][lane] = axes[a].y;
    dst[a][2][lane] = axes[a].z;
  }
  batch.friction[lane] = c.friction;
  for (uint32_t p = 0; p < c.point_count; ++p) {
    const ConstraintPoint& cp = c.points[p];
    ContactBatch::Point& bp = batch.points[p];
    bp.anchor_a[0][lane] = cp.anchor_a.x;
    bp.anchor_a[1][lane] = cp.anchor_a.y;
    bp.anchor_a[2][lane] = cp.anchor_a.z;
    bp.anchor_b[0][lane] = cp.anchor_b.x;
    bp.anchor_b[1][lane] = cp.anchor_b.y;
    bp.anchor_b[2][lane] = cp.anchor_b.z;
    const Vec3 rn_a = cross(cp.anchor_a, c.normal);
    const Vec3 rn_b = cross(cp.anchor_b, c.normal);
    const Vec3 rt1_a = cross(cp.anchor_a, c.tangent1);
    const Vec3 rt1_b = cross(cp.anchor_b, c.tangent1);
    const Vec3 rt2_a = cross(cp.anchor_a, c.tangent2);
    const Vec3 rt2_b = cross(cp.anchor_b, c.tangent2);
    put(bp.rn_a, lane, rn_a);
    put(bp.rn_b, lane, rn_b);
    put(bp.rt1_a, lane, rt1_a);
    put(bp.rt1_b, lane, rt1_b);
    put(bp.rt2_a, lane, rt2_a);
    put(bp.rt2_b, lane, rt2_b);
    const Vec3 it1_a = body_a.inv_inertia * rt1_a;
    const Vec3 it1_b = body_b.inv_inertia * rt1_b;
    const Vec3 it2_a = body_a.inv_inertia * rt2_a;
    const Vec3 it2_b = body_b.inv_inertia * rt2_b;
    put(bp.in_a, lane, body_a.inv_inertia * rn_a);
    put(bp.in_b, lane, body_b.inv_inertia * rn_b);
    put(bp.it1_a, lane, it1_a);
    put(bp.it1_b, lane, it1_b);
    put(bp.it2_a, lane, it2_a);
    put(bp.it2_b, lane, it2_b);
    bp.base_separation[lane] = cp.base_separation;
    bp.separation[lane] = cp.separation;
    bp.normal_mass[lane] = cp.normal_mass;
    // Tangent masses from the same vectors (the effective mass along each
    // tangent at the point).
    const float k1 = body_a.inv_mass + body_b.inv_mass + dot(rt1_a, it1_a) + dot(rt1_b, it1_b);
    const float k2 = body_a.inv_mass + body_b.inv_mass + dot(rt2_a, it2_a) + dot(rt2_b, it2_b);
    bp.tangent_mass1[lane] = k1 > 0.0f ? 1.0f / k1 : 0.0f;
    bp.tangent_mass2[lane] = k2 > 0.0f ? 1.0f / k2 : 0.0f;
    bp.normal_impulse[lane] = cp.normal_impulse;
    bp.tangent_impulse1[lane] = cp.tangent_impulse1;
    bp.tangent_impulse2[lane] = cp.tangent_impulse2;
    bp.max_normal_impulse[lane] = cp.max_normal_impulse;
    for (uint32_t j = 0; j < kMaxManifoldPoints; ++j) {
      batch.coupling[p][j][lane] = j < c.point_count ? c.coupling[p][j] : 0.0f;
    }
  }
  for (uint32_t p = c.point_count; p < kMaxManifoldPoints; ++p) {
    clear_point(batch.points[p], lane);
    for (auto& k : batch.coupling[p]) k[lane] = 0.0f;
  }
}

}  // namespace

void build_batches(WorldScratch& scratch) {
  color(scratch);
  const uint32_t count = static_cast<uint32_t>(scratch.constraints.size());
  // Constraints by colour (counting sort, stable: constraint order within a
  // colour), overflow last.
  scratch.color_start.assign(kColorCount + 2, 0);
  for (uint32_t k = 0; k < count; ++k) ++scratch.color_start[scratch.color_of[k] + 1];
  for (uint32_t col = 0; col <= kColorCount; ++col) {
    scratch.color_start[col + 1] += scratch.color_start[col];
  }
  scratch.colored.resize(count);
  scratch.color_fill.assign(scratch.color_start.begin(), scratch.color_start.end() - 1);
  for (uint32_t k = 0; k < count; ++k)
    scratch.colored[scratch.color_fill[scratch.color_of[k]]++] = k;

  // Batches of four within a colour; overflow constraints one per batch.
  scratch.batches.clear();
  for (uint32_t col = 0; col <= kColorCount; ++col) {
    const uint32_t begin = scratch.color_start[col];
    const uint32_t end = scratch.color_start[col + 1];
    const uint32_t per_batch = col == kColorCount ? 1 : kLanes;
    for (uint32_t first = begin; first < end; first += per_batch) {
      ContactBatch& batch = scratch.batches.emplace_back();
      for (uint32_t lane = 0; lane < kLanes; ++lane) {
        const uint32_t at = first + lane;
        if (lane < per_batch && at < end) {
          const uint32_t index = scratch.colored[at];
          fill_lane(batch, static_cast<int>(lane), index, scratch.constraints[index],
                    scratch.solver_bodies);
        } else {
          clear_lane(batch, static_cast<int>(lane));
        }
      }
    }
  }
}

void warm_start_batches(WorldScratch& scratch) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for (ContactBatch& batch : scratch.batches) {
    BodiesW a = gather(bodies, batch.body_a);
    BodiesW b = gather(bodies, batch.body_b);
    const Vec3W n = lane_load(batch.normal);
    const Vec3W t1 = lane_load(batch.tangent1);
    const Vec3W t2 = lane_load(batch.tangent2);
    Vec3W linear{splat(0.0f), splat(0.0f), splat(0.0f)};
    Vec3W turn_a = linear;
    Vec3W turn_b = linear;
    for (const ContactBatch::Point& p : batch.points) {
      const FloatW ln = lane_load(p.normal_impulse);
      const FloatW l1 = lane_load(p.tangent_impulse1);
      const FloatW l2 = lane_load(p.tangent_impulse2);
      linear = linear + (n * ln + t1 * l1 + t2 * l2);
      turn_a =
          turn_a + (lane_load(p.in_a) * ln + lane_load(p.it1_a) * l1 + lane_load(p.it2_a) * l2);
      turn_b =
          turn_b + (lane_load(p.in_b) * ln + lane_load(p.it1_b) * l1 + lane_load(p.it2_b) * l2);
    }
    a.v = a.v - linear * a.inv_mass;
    a.w = a.w - turn_a;
    b.v = b.v + linear * b.inv_mass;
    b.w = b.w + turn_b;
    scatter(bodies, batch.body_a, a);
    scatter(bodies, batch.body_b, b);
  }
}

void solve_batches(WorldScratch& scratch, float inv_h) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  const FloatW zero = splat(0.0f);
  const FloatW inv_h_w = splat(inv_h);
  for (ContactBatch& batch : scratch.batches) {
    BodiesW a = gather(bodies, batch.body_a);
    BodiesW b = gather(bodies, batch.body_b);
    const Vec3W n = lane_load(batch.normal);

    // Normal impulses of the manifold as a block: sweeps with the bodies
    // held (the residual kept up to date column by column), then one
    // impulse per body.
    FloatW residual[kMaxManifoldPoints];
    FloatW step[kMaxManifoldPoints];
    FloatW total[kMaxManifoldPoints];
    for (uint32_t p = 0; p < kMaxManifoldPoints; ++p) {
      const ContactBatch::Point& bp = batch.points[p];
      const FloatW s = lane_load(bp.separation);
      const FloatW bias = select(s > zero, s * inv_h_w, zero);  // speculative
      const FloatW vn =
          dot(b.v - a.v, n) + dot(lane_load(bp.rn_b), b.w) - dot(lane_load(bp.rn_a), a.w);
      residual[p] = vn + bias;
      step[p] = lane_load(bp.normal_mass);
      total[p] = lane_load(bp.normal_impulse);
    }
    const FloatW start[kMaxManifoldPoints] = {total[0], total[1], total[2], total[3]};
    for (int sweep = 0; sweep < kManifoldSweeps; ++sweep) {
      for (uint32_t p = 0; p < kMaxManifoldPoints; ++p) {
        const FloatW next = clamp_at_zero(total[p] - step[p] * residual[p]);
        const FloatW change = next - total[p];
        total[p] = next;
        for (uint32_t j = 0; j < kMaxManifoldPoints; ++j) {
          residual[j] = residual[j] + lane_load(batch.coupling[j][p]) * change;
        }
      }
    }
    FloatW pushed = zero;
    Vec3W turn_a{zero, zero, zero};
    Vec3W turn_b = turn_a;
    for (uint32_t p = 0; p < kMaxManifoldPoints; ++p) {
      ContactBatch::Point& bp = batch.points[p];
      lane_store(bp.normal_impulse, total[p]);
      const FloatW max_seen = lane_load(bp.max_normal_impulse);
      lane_store(bp.max_normal_impulse, select(total[p] > max_seen, total[p], max_seen));
      const FloatW change = total[p] - start[p];
      pushed = pushed + change;
      turn_a = turn_a + lane_load(bp.in_a) * change;
      turn_b = turn_b + lane_load(bp.in_b) * change;
    }
    a.v = a.v - n * (pushed * a.inv_mass);
    a.w = a.w - turn_a;
    b.v = b.v + n * (pushed * b.inv_mass);
    b.w = b.w + turn_b;

    // Friction after the normal impulses (the cones use this pass's
    // values), point by point: |t| <= mu * normal impulse.
    const Vec3W t1 = lane_load(batch.tangent1);
    const Vec3W t2 = lane_load(batch.tangent2);
    const FloatW mu = lane_load(batch.friction);
    for (uint32_t p = 0; p < kMaxManifoldPoints; ++p) {
      ContactBatch::Point& bp = batch.points[p];
      const Vec3W dv = b.v - a.v;
      const FloatW v1 = dot(dv, t1) + dot(lane_load(bp.rt1_b), b.w) - dot(lane_load(bp.rt1_a), a.w);
      const FloatW v2 = dot(dv, t2) + dot(lane_load(bp.rt2_b), b.w) - dot(lane_load(bp.rt2_a), a.w);
      const FloatW old1 = lane_load(bp.tangent_impulse1);
      const FloatW old2 = lane_load(bp.tangent_impulse2);
      FloatW f1 = old1 - lane_load(bp.tangent_mass1) * v1;
      FloatW f2 = old2 - lane_load(bp.tangent_mass2) * v2;
      const FloatW limit = mu * total[p];
      const FloatW len_sq = f1 * f1 + f2 * f2;
      const MaskW over = len_sq > limit * limit;
      // Lanes under the limit keep their impulse; the others scale onto the
      // cone (len_sq > 0 there).
      const FloatW scale = select(over, limit / sqrt(len_sq), splat(1.0f));
      f1 = select(over, f1 * scale, f1);
      f2 = select(over, f2 * scale, f2);
      lane_store(bp.tangent_impulse1, f1);
      lane_store(bp.tangent_impulse2, f2);
      const FloatW i1 = f1 - old1;
      const FloatW i2 = f2 - old2;
      const Vec3W impulse = t1 * i1 + t2 * i2;
      a.v = a.v - impulse * a.inv_mass;
      a.w = a.w - (lane_load(bp.it1_a) * i1 + lane_load(bp.it2_a) * i2);
      b.v = b.v + impulse * b.inv_mass;
      b.w = b.w + (lane_load(bp.it1_b) * i1 + lane_load(bp.it2_b) * i2);
    }
    scatter(bodies, batch.body_a, a);
    scatter(bodies, batch.body_b, b);
  }
}

// q rotating v, per lane, as rotate() in math.h.
Vec3W rotate_w(const FloatW (&q)[4], const Vec3W& v) {
  const Vec3W u{q[0], q[1], q[2]};
  const Vec3W uv = cross(u, v);
  const FloatW two = splat(2.0f);
  const Vec3W t{two * uv.x, two * uv.y, two * uv.z};
  const Vec3W wt{q[3] * t.x, q[3] * t.y, q[3] * t.z};
  return v + wt + cross(u, t);
}

void update_separations(WorldScratch& scratch) {
  const std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for (ContactBatch& batch : scratch.batches) {
    alignas(16) float f[14][kLanes];
    for (int i = 0; i < kLanes; ++i) {
      const SolverBody& a = bodies[batch.body_a[i]];
      const SolverBody& b = bodies[batch.body_b[i]];
      const float values[14] = {a.delta_position.x, a.delta_position.y, a.delta_position.z,
                                a.delta_rotation.x, a.delta_rotation.y, a.delta_rotation.z,
                                a.delta_rotation.w, b.delta_position.x, b.delta_position.y,
                                b.delta_position.z, b.delta_rotation.x, b.delta_rotation.y,
                                b.delta_rotation.z, b.delta_rotation.w};
      for (int k = 0; k < 14; ++k) f[k][i] = values[k];
    }
    const Vec3W pos_a{load(f[0]), load(f[1]), load(f[2])};
    const FloatW rot_a[4] = {load(f[3]), load(f[4]), load(f[5]), load(f[6])};
    const Vec3W pos_b{load(f[7]), load(f[8]), load(f[9])};
    const FloatW rot_b[4] = {load(f[10]), load(f[11]), load(f[12]), load(f[13])};
    const Vec3W dp = pos_b - pos_a;
    const Vec3W n = lane_load(batch.normal);
    for (ContactBatch::Point& bp : batch.points) {
      const Vec3W pa = rotate_w(rot_a, lane_load(bp.anchor_a));
      const Vec3W pb = rotate_w(rot_b, lane_load(bp.anchor_b));
      lane_store(bp.separation, dot(dp + (pb - pa), n) + lane_load(bp.base_separation));
    }
    for (int lane = 0; lane < kLanes; ++lane) {
      if (batch.constraint[lane] == kNoConstraint) continue;
      ContactConstraint& c = scratch.constraints[batch.constraint[lane]];
      for (uint32_t p = 0; p < c.point_count; ++p) {
        c.points[p].separation = batch.points[p].separation[lane];
      }
    }
  }
}

void unpack_batches(WorldScratch& scratch) {
  for (const ContactBatch& batch : scratch.batches) {
    for (int lane = 0; lane < kLanes; ++lane) {
      if (batch.constraint[lane] == kNoConstraint) continue;
      ContactConstraint& c = scratch.constraints[batch.constraint[lane]];
      for (uint32_t p = 0; p < c.point_count; ++p) {
        const ContactBatch::Point& bp = batch.points[p];
        ConstraintPoint& cp = c.points[p];
        cp.normal_impulse = bp.normal_impulse[lane];
        cp.tangent_impulse1 = bp.tangent_impulse1[lane];
        cp.tangent_impulse2 = bp.tangent_impulse2[lane];
        cp.max_normal_impulse = bp.max_normal_impulse[lane];
      }
    }
  }
}

}  // namespace rwd::sim::d3
