// SPDX-License-Identifier: MIT
// What every joint type shares: where its frames are within a substep,
// impulses applied at its anchors, the rows it is built from (the point,
// three linear rows; the orientation, three angular rows), and how a row
// is driven. Each row solves for the impulse that brings its velocity
// error, plus a bias toward zero position error, to zero: with the bias
// softened by the joint's spring-damper while solving, without it while
// relaxing (so the correction never stays behind as velocity), and always
// softened for a spring. Limits are one-sided and speculative: a gap still
// open may close within the substep, no more.
#include "d3/joint_solver.h"
#include "d3/joint_tree.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

JointFrames joint_frames(const JointConstraint& c, const SolverBody& a, const SolverBody& b) {
  JointFrames f;
  f.ra = rotate(a.delta_rotation, c.anchor_a);
  f.rb = rotate(b.delta_rotation, c.anchor_b);
  f.d = (b.delta_position - a.delta_position) + c.delta_center + (f.rb - f.ra);
  if (!c.orients) return f;
  f.qa = a.delta_rotation * c.rotation_a;
  f.qb = b.delta_rotation * c.rotation_b;
  f.fa = a.delta_rotation * c.frame_a;
  f.fb = b.delta_rotation * c.frame_b;
  return f;
}

Vec3 anchor_velocity(const SolverBody& a, const SolverBody& b, Vec3 ra, Vec3 rb) {
  const Vec3 va = a.linear_velocity + cross(a.angular_velocity, ra);
  const Vec3 vb = b.linear_velocity + cross(b.angular_velocity, rb);
  return vb - va;
}

void apply_linear(SolverBody& a, SolverBody& b, Vec3 ra, Vec3 rb, Vec3 p) {
  a.linear_velocity -= p * a.inv_mass;
  a.angular_velocity -= a.inv_inertia * cross(ra, p);
  b.linear_velocity += p * b.inv_mass;
  b.angular_velocity += b.inv_inertia * cross(rb, p);
}

int point_rows(const JointFrames& f, JointRow* out) {
  out[0] = linear_jacobian({1.0f, 0.0f, 0.0f}, f.ra, f.rb);
  out[1] = linear_jacobian({0.0f, 1.0f, 0.0f}, f.ra, f.rb);
  out[2] = linear_jacobian({0.0f, 0.0f, 1.0f}, f.ra, f.rb);
  return 3;
}

int orientation_rows(JointRow* out) {
  out[0] = angular_jacobian({1.0f, 0.0f, 0.0f});
  out[1] = angular_jacobian({0.0f, 1.0f, 0.0f});
  out[2] = angular_jacobian({0.0f, 0.0f, 1.0f});
  return 3;
}

JointFrames start_frames(const JointConstraint& c) {
  JointFrames f;
  f.qa = c.rotation_a;
  f.qb = c.rotation_b;
  f.ra = c.anchor_a;
  f.rb = c.anchor_b;
  f.d = c.delta_center + (c.anchor_b - c.anchor_a);
  f.fa = c.frame_a;
  f.fb = c.frame_b;
  return f;
}

namespace {

bool is_linear(const JointRow& r) {
  return !(r.linear == Vec3{});
}

}  // namespace

float& limit_impulse(JointConstraint& c, uint8_t kind) {
  return kind == kRowLower ? c.lower_impulse
                           : (kind == kRowUpper ? c.upper_impulse : c.cone_impulse);
}

float limit_impulse(const JointConstraint& c, uint8_t kind) {
  return kind == kRowLower ? c.lower_impulse
                           : (kind == kRowUpper ? c.upper_impulse : c.cone_impulse);
}

uint8_t held_limits(const JointConstraint& c) {
  uint8_t held = 0;
  for (int i = 0; i < c.block.size(); ++i) held |= static_cast<uint8_t>(1u << c.row_kind[i]);
  return static_cast<uint8_t>(held & ~1u);
}

void gather_impulses(const JointConstraint& c, float* acc) {
  for (int i = 0; i < c.block.size(); ++i) {
    const JointRow& r = c.block.row(i);
    if (c.row_kind[i] != kRowStructure) {
      acc[i] = limit_impulse(c, c.row_kind[i]);
    } else {
      acc[i] = is_linear(r) ? dot(c.linear_impulse, r.linear) : dot(c.angular_impulse, r.angular_b);
    }
  }
}

void scatter_impulses(JointConstraint& c, const float* acc) {
  Vec3 linear{};
  Vec3 angular{};
  for (int i = 0; i < c.block.size(); ++i) {
    const JointRow& r = c.block.row(i);
    if (c.row_kind[i] != kRowStructure) {
      limit_impulse(c, c.row_kind[i]) = acc[i];
    } else if (is_linear(r)) {
      linear += r.linear * acc[i];
    } else {
      angular += r.angular_b * acc[i];
    }
  }
  c.linear_impulse = linear;
  c.angular_impulse = angular;
}

void release_block_limits(const JointConstraint& c, float* total, float* step) {
  const int n = c.block.size();
  int released[kMaxBlockRows];
  float column[kMaxBlockRows][kMaxBlockRows];
  int m = 0;
  for (int round = 0; round < kMaxLimitRows; ++round) {
    const int before = m;
    for (int i = 0; i < n; ++i) {
      if (c.row_kind[i] == kRowStructure || !(total[i] < 0.0f)) continue;
      bool seen = false;
      for (int q = 0; q < m; ++q) seen = seen || released[q] == i;
      if (seen) continue;
      // Its column of K^-1: the block impulses that change its row's
      // velocity by one and no other row's.
      float unit[kMaxBlockRows] = {};
      unit[i] = 1.0f;
      c.block.solve(unit, column[m]);
      released[m++] = i;
    }
    if (m == before) return;
    // (K^-1)_RR t = -total_R zeroes every released row.
    float w[kMaxBlockRows * kMaxBlockRows];
    float t[kMaxBlockRows];
    for (int r = 0; r < m; ++r) {
      for (int q = 0; q < m; ++q) w[r * m + q] = column[q][released[r]];
      t[r] = -total[released[r]];
    }
    solve_dense_spd(w, static_cast<uint32_t>(m), t);
    for (int i = 0; i < n; ++i) {
      float v = 0.0f;
      for (int q = 0; q < m; ++q) v += column[q][i] * t[q];
      total[i] += v;
      if (step != nullptr) step[i] += v;
    }
  }
}

void settle_held_limits(JointConstraint& c, SolverBody& a, SolverBody& b, float* acc) {
  float step[kMaxBlockRows] = {};
  release_block_limits(c, acc, step);
  bool any = false;
  for (int i = 0; i < c.block.size(); ++i) any = any || step[i] != 0.0f;
  if (any) c.block.apply(a, b, step);
}

void solve_free_limits(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                       const JointFrames& f, bool use_bias, const ExtraBase& base,
                       bool at_refresh) {
  const JointOps& ops = joint_ops(j.type);
  if (ops.limits == nullptr) return;
  LimitRow computed[kMaxLimitRows];
  const LimitRow* limits = at_refresh ? c.limits : computed;
  const int n = at_refresh ? c.limit_count : ops.limits(j, f, computed);
  const uint8_t held = held_limits(c);
  for (int k = 0; k < n; ++k) {
    const LimitRow& l = limits[k];
    if ((held & (1u << l.kind)) != 0) continue;
    solve_extra_row(base, a, b, l.row, limit_terms(c.soft, l.gap, c.h, use_bias), 0.0f, 0.0f,
                    kUnbounded, limit_impulse(c, l.kind), l.kind);
  }
}

void warm_start_free_limits(const JointConstraint& c, SolverBody& a, SolverBody& b) {
  const uint8_t held = held_limits(c);
  for (int k = 0; k < c.limit_count; ++k) {
    if ((held & (1u << c.limits[k].kind)) != 0) continue;
    apply_row(c.limits[k].row, a, b, limit_impulse(c, c.limits[k].kind));
  }
}

void structural_bias(const JointConstraint& c, const JointFrames& f, Vec3 angular_error, float rate,
                     float* bias) {
  for (int i = 0; i < c.block.size(); ++i) {
    const JointRow& r = c.block.row(i);
    float error = 0.0f;
    if (c.row_kind[i] != kRowStructure) {
      error = c.row_gap[i];
    } else {
      error = is_linear(r) ? dot(f.d, r.linear) : dot(angular_error, r.angular_b);
    }
    bias[i] = error * rate;
  }
}

Vec3 orientation_error(const JointFrames& f) {
  return rotation_vector(f.fb * conjugate(f.fa));
}

}  // namespace rwd::sim::d3
