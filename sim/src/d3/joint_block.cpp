// SPDX-License-Identifier: MIT
// The joint row block and the groups solved against it (joint_block.h):
// an L D L^T factorization of at most six rows, and Schur complements of
// at most three. Every loop runs in row order, so the arithmetic is the
// same on every build.
#include "d3/joint_block.h"

#include <type_traits>

#include "d3/joint_tree.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// A pivot below this share of its diagonal means the row depends on the
// ones before it (or neither body can move along it): it is left out.
constexpr float kPivotShare = 1e-6f;

// An extra row the base already holds (or nothing can move along) has no
// Schur complement left: what is left of its diagonal is rounding, below
// this share of its own diagonal K_ee (float rounding leaves about 1e-6
// of it; a row the base does not hold keeps far more: a small bob a
// metre from its pivot, the least of the usual cases, keeps 1e-3). It
// is left out rather than given a huge mass: a twist limit solved
// against a tree that holds the opposite twist limit took impulses a
// hundred thousand times too large.
constexpr float kExtraShare = 1e-5f;

float clamp_impulse(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

}  // namespace

void invert_schur(float (*sm)[3], const float* own, int m, float (*out)[3]) {
  for (int k = 0; k < m; ++k) {
    if (!(own[k] > 0.0f && sm[k][k] > kExtraShare * own[k])) {
      for (int l = 0; l < 3; ++l) sm[k][l] = sm[l][k] = 0.0f;
    }
  }
  // Padded with ones on the unused diagonal; inverse_symmetric leaves the
  // zeroed rows zero.
  const Mat3 inv = inverse_symmetric(Mat3{{sm[0][0], sm[0][1], sm[0][2]},
                                          {sm[1][0], sm[1][1], sm[1][2]},
                                          {sm[2][0], sm[2][1], sm[2][2]}});
  const Vec3 cols[3] = {inv.c0, inv.c1, inv.c2};
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) out[k][l] = k < m && l < m ? component(cols[k], l) : 0.0f;
  }
}

float row_velocity(const JointRow& r, const SolverBody& a, const SolverBody& b) {
  return dot(r.linear, b.linear_velocity - a.linear_velocity) +
         dot(r.angular_b, b.angular_velocity) - dot(r.angular_a, a.angular_velocity);
}

void apply_row(const JointRow& r, SolverBody& a, SolverBody& b, float lambda) {
  a.linear_velocity -= r.linear * (lambda * a.inv_mass);
  a.angular_velocity -= a.inv_inertia * (r.angular_a * lambda);
  b.linear_velocity += r.linear * (lambda * b.inv_mass);
  b.angular_velocity += b.inv_inertia * (r.angular_b * lambda);
}

namespace {

// Calls f with the row count as a constant for the counts joints have, so
// the loops over rows unroll; the arithmetic is the same either way.
template <class F>
void with_rows(int n, F&& f) {
  switch (n) {
    case 1:
      f(std::integral_constant<int, 1>{});
      return;
    case 2:
      f(std::integral_constant<int, 2>{});
      return;
    case 3:
      f(std::integral_constant<int, 3>{});
      return;
    case 4:
      f(std::integral_constant<int, 4>{});
      return;
    case 5:
      f(std::integral_constant<int, 5>{});
      return;
    case 6:
      f(std::integral_constant<int, 6>{});
      return;
    default:
      f(n);
      return;
  }
}

}  // namespace

void RowBlock::factor(const SolverBody& a, const SolverBody& b) {
  mass_sum_ = a.inv_mass + b.inv_mass;
  with_rows(n_, [&](auto n) {
    for (int i = 0; i < n; ++i) {
      ia_[i] = a.inv_inertia * rows_[i].angular_a;
      ib_[i] = b.inv_inertia * rows_[i].angular_b;
    }
    for (int i = 0; i < n; ++i) {
      const float kii = mass_sum_ * dot(rows_[i].linear, rows_[i].linear) +
                        dot(rows_[i].angular_a, ia_[i]) + dot(rows_[i].angular_b, ib_[i]);
      float di = kii;
      for (int k = 0; k < i; ++k) di -= l_[i][k] * l_[i][k] * d_[k];
      kept_[i] = kii > 0.0f && di > kPivotShare * kii;
      d_[i] = kept_[i] ? di : 0.0f;
      for (int j = i + 1; j < n; ++j) {
        if (!kept_[i]) {
          l_[j][i] = 0.0f;
          continue;
        }
        float kji = mass_sum_ * dot(rows_[j].linear, rows_[i].linear) +
                    dot(rows_[j].angular_a, ia_[i]) + dot(rows_[j].angular_b, ib_[i]);
        for (int k = 0; k < i; ++k) kji -= l_[j][k] * l_[i][k] * d_[k];
        l_[j][i] = kji / d_[i];
      }
    }
  });
}

void RowBlock::solve(const float* rhs, float* x) const {
  with_rows(n_, [&](auto n) {
    float z[kMaxBlockRows];
    for (int i = 0; i < n; ++i) {
      float v = rhs[i];
      for (int k = 0; k < i; ++k) v -= l_[i][k] * z[k];
      z[i] = kept_[i] ? v : 0.0f;
    }
    for (int i = n - 1; i >= 0; --i) {
      if (!kept_[i]) {
        x[i] = 0.0f;
        continue;
      }
      float v = z[i] / d_[i];
      for (int k = i + 1; k < n; ++k) v -= l_[k][i] * x[k];
      x[i] = v;
    }
  });
}

float RowBlock::velocity(int i, const SolverBody& a, const SolverBody& b) const {
  return row_velocity(rows_[i], a, b);
}

void RowBlock::coupling(const JointRow& other, float* out) const {
  with_rows(n_, [&](auto n) {
    for (int i = 0; i < n; ++i) {
      out[i] = mass_sum_ * dot(rows_[i].linear, other.linear) + dot(ia_[i], other.angular_a) +
               dot(ib_[i], other.angular_b);
    }
  });
}

void RowBlock::apply(SolverBody& a, SolverBody& b, const float* lambda) const {
  Vec3 linear{};
  Vec3 angular_a{};
  Vec3 angular_b{};
  with_rows(n_, [&](auto n) {
    for (int i = 0; i < n; ++i) {
      linear += rows_[i].linear * lambda[i];
      angular_a += rows_[i].angular_a * lambda[i];
      angular_b += rows_[i].angular_b * lambda[i];
    }
  });
  a.linear_velocity -= linear * a.inv_mass;
  a.angular_velocity -= a.inv_inertia * angular_a;
  b.linear_velocity += linear * b.inv_mass;
  b.angular_velocity += b.inv_inertia * angular_b;
}

template <int M>
void RowGroupOf<M>::prepare(const RowBlock& block, const JointRow* rows, int m, const SolverBody& a,
                            const SolverBody& b) {
  m_ = m;
  const int n = block.size();
  const float mass_sum = a.inv_mass + b.inv_mass;
  float c[M][kMaxBlockRows];
  for (int k = 0; k < m; ++k) {
    rows_[k] = rows[k];
    block.coupling(rows[k], c[k]);
    block.solve(c[k], y_[k]);
  }
  // S = K_ee - K_eb K_bb^-1 K_be.
  float sm[3][3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  float own[3] = {};
  for (int k = 0; k < m; ++k) {
    const Vec3 ia = a.inv_inertia * rows[k].angular_a;
    const Vec3 ib = b.inv_inertia * rows[k].angular_b;
    for (int l = 0; l < m; ++l) {
      float v = mass_sum * dot(rows[l].linear, rows[k].linear) + dot(rows[l].angular_a, ia) +
                dot(rows[l].angular_b, ib);
      if (l == k) own[k] = v;
      for (int i = 0; i < n; ++i) v -= c[l][i] * y_[k][i];
      sm[k][l] = v;
    }
  }
  float inverse[3][3];
  invert_schur(sm, own, m, inverse);
  for (int k = 0; k < M; ++k) {
    for (int l = 0; l < M; ++l) s_[k][l] = inverse[k][l];
  }
}

template <int M>
void RowGroupOf<M>::velocity(const SolverBody& a, const SolverBody& b, float* out) const {
  for (int k = 0; k < m_; ++k) out[k] = row_velocity(rows_[k], a, b);
}

template <int M>
void RowGroupOf<M>::solve(const float* rhs, float* x) const {
  for (int k = 0; k < m_; ++k) {
    float v = 0.0f;
    for (int l = 0; l < m_; ++l) v += s_[l][k] * rhs[l];
    x[k] = v;
  }
}

template <int M>
void RowGroupOf<M>::apply(const RowBlock& block, SolverBody& a, SolverBody& b, const float* delta,
                          float* block_impulse) const {
  const int n = block.size();
  float compensation[kMaxBlockRows] = {};
  for (int k = 0; k < m_; ++k) {
    apply_row(rows_[k], a, b, delta[k]);
    for (int i = 0; i < n; ++i) compensation[i] -= y_[k][i] * delta[k];
  }
  block.apply(a, b, compensation);
  for (int i = 0; i < n; ++i) block_impulse[i] += compensation[i];
}

template class RowGroupOf<1>;
template class RowGroupOf<kMaxGroupRows>;

void solve_block(const RowBlock& block, SolverBody& a, SolverBody& b, const float* bias,
                 const JointSoftness& soft, bool use_bias, float* impulse) {
  const int n = block.size();
  float rhs[kMaxBlockRows] = {};
  for (int i = 0; i < n; ++i) {
    rhs[i] = block.velocity(i, a, b) + (use_bias ? bias[i] : 0.0f);
  }
  float x[kMaxBlockRows] = {};
  block.solve(rhs, x);
  const float mass_scale = use_bias ? soft.mass_scale : 1.0f;
  const float impulse_scale = use_bias ? soft.impulse_scale : 0.0f;
  float lambda[kMaxBlockRows] = {};
  for (int i = 0; i < n; ++i) {
    lambda[i] = -x[i] * mass_scale - impulse[i] * impulse_scale;
    impulse[i] += lambda[i];
  }
  block.apply(a, b, lambda);
}

void ExtraGroup::prepare(const ExtraBase& base, const JointRow* rows, int m, const SolverBody& a,
                         const SolverBody& b, int slot) {
  m_ = m;
  tree_ = base.scratch != nullptr;
  for (int k = 0; k < m; ++k) rows_[k] = rows[k];
  if (!tree_) {
    local_.prepare(*base.block, rows, m, a, b);
    return;
  }
  y_at_ = prepare_tree_group(*base.scratch, base.tree, base.joint, slot, base.body_a, base.body_b,
                             rows, m, s_);
}

void ExtraGroup::velocity(const SolverBody& a, const SolverBody& b, float* out) const {
  for (int k = 0; k < m_; ++k) out[k] = row_velocity(rows_[k], a, b);
}

void ExtraGroup::solve(const float* rhs, float* x) const {
  if (!tree_) {
    local_.solve(rhs, x);
    return;
  }
  for (int k = 0; k < m_; ++k) {
    float v = 0.0f;
    for (int l = 0; l < m_; ++l) v += s_[l][k] * rhs[l];
    x[k] = v;
  }
}

void ExtraGroup::apply(const ExtraBase& base, SolverBody& a, SolverBody& b,
                       const float* delta) const {
  if (base.scratch == nullptr) {
    local_.apply(*base.block, a, b, delta, base.block_impulse);
    return;
  }
  for (int k = 0; k < m_; ++k) apply_row(rows_[k], a, b, delta[k]);
  apply_tree_compensation(*base.scratch, base.tree, y_at_, m_, delta);
}

namespace {

// The impulse step of an extra row whose solve gave x: soft per the terms,
// the accumulated impulse kept in [lo, hi].
float extra_step(const RowTerms& t, float x, float lo, float hi, float& impulse) {
  const float lambda = -x * t.mass_scale - impulse * t.impulse_scale;
  const float next = clamp_impulse(impulse + lambda, lo, hi);
  const float delta = next - impulse;
  impulse = next;
  return delta;
}

}  // namespace

void solve_extra_row(const ExtraBase& base, SolverBody& a, SolverBody& b, const JointRow& row,
                     const RowTerms& t, float speed, float lo, float hi, float& impulse, int slot) {
  const float cdot = row_velocity(row, a, b);
  const float rhs = cdot - speed + t.bias;
  // An open limit holding nothing and not closing within the substep: the
  // solve would clamp its impulse to zero anyway.
  if (lo == 0.0f && impulse == 0.0f && rhs >= 0.0f) return;
  float x = 0.0f;
  if (base.scratch == nullptr) {
    // Against the joint's own block: made here, or kept from the pass
    // before at the same rows.
    RowGroupOf<1> made;
    const RowGroupOf<1>* group = &made;
    if (base.kept != nullptr) {
      KeptRow& kept = base.kept[slot];
      if (!kept.ready) {
        kept.group.prepare(*base.block, &row, 1, a, b);
        kept.ready = true;
      }
      group = &kept.group;
    } else {
      made.prepare(*base.block, &row, 1, a, b);
    }
    group->solve(&rhs, &x);
    const float delta = extra_step(t, x, lo, hi, impulse);
    if (delta != 0.0f) group->apply(*base.block, a, b, &delta, base.block_impulse);
    return;
  }
  ExtraGroup group;
  group.prepare(base, &row, 1, a, b, slot);
  group.solve(&rhs, &x);
  const float delta = extra_step(t, x, lo, hi, impulse);
  if (delta != 0.0f) group.apply(base, a, b, &delta);
}

}  // namespace rwd::sim::d3
