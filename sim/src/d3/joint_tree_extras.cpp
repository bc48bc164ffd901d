// SPDX-License-Identifier: MIT
// A joint tree's extra rows (springs, motors, limits not in its structure)
// solved against the whole tree held rigid (joint_tree.h): each row's
// coupling to the tree's rows, its Schur complement through the tree's
// factors, and the impulse that keeps the tree's rows where they were.
#include <cstring>

#include "d3/joint_solver.h"
#include "d3/joint_tree.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

namespace {

// K column of an outside row on bodies (body_a, body_b) against every row
// of tree t: the coupling through whichever of those bodies a tree joint
// shares (immovable bodies couple nothing).
void tree_column(const WorldScratch& s, const JointTree& tree, uint32_t body_a, uint32_t body_b,
                 const JointRow& e, float* out) {
  const SolverBody& ba = s.solver_bodies[body_a];
  const SolverBody& bb = s.solver_bodies[body_b];
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    const JointConstraint& c = s.joint_constraints[s.tree_joints[k]];
    for (int i = 0; i < c.block.size(); ++i) {
      const JointRow& r = c.block.row(i);
      float v = 0.0f;
      if (body_a != 0 && (c.body_a == body_a || c.body_b == body_a)) {
        v += tree_row_coupling(r, c.body_a == body_a, e, true, ba);
      }
      if (body_b != 0 && (c.body_a == body_b || c.body_b == body_b)) {
        v += tree_row_coupling(r, c.body_a == body_b, e, false, bb);
      }
      out[c.tree_row + static_cast<uint32_t>(i)] = v;
    }
  }
}

}  // namespace

size_t prepare_tree_group(WorldScratch& s, uint32_t t, uint32_t joint, int slot, uint32_t body_a,
                          uint32_t body_b, const JointRow* rows, int m, float (*s_inv)[3]) {
  const JointTree& tree = s.trees[t];
  uint32_t& found =
      s.tree_extra_slot[static_cast<size_t>(joint) * kKeptRows + static_cast<size_t>(slot)];
  if (found < s.tree_extra_groups.size()) {
    const TreeExtraGroup& g = s.tree_extra_groups[found];
    if (g.m == m && g.body_a == body_a && g.body_b == body_b &&
        std::memcmp(g.rows, rows, sizeof(JointRow) * static_cast<size_t>(m)) == 0) {
      for (int k = 0; k < kMaxGroupRows; ++k) {
        for (int l = 0; l < kMaxGroupRows; ++l) s_inv[k][l] = g.s_inv[k][l];
      }
      return g.y_at;
    }
  }
  const size_t total = s.tree_rhs.size();
  const size_t tree_rows = tree.row_end - tree.row_begin;
  const size_t y_at = s.tree_extra_used;
  s.tree_extra_used += static_cast<size_t>(m) * tree_rows;
  if (s.tree_extra_y.size() < s.tree_extra_used) s.tree_extra_y.resize(s.tree_extra_used);
  s.tree_extra_c.resize(3 * total);
  const SolverBody& ba = s.solver_bodies[body_a];
  const SolverBody& bb = s.solver_bodies[body_b];
  for (int k = 0; k < m; ++k) {
    float* col = s.tree_extra_c.data() + static_cast<size_t>(k) * total;
    tree_column(s, tree, body_a, body_b, rows[k], col);
    // y_k = K^-1 col over the tree's rows.
    for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
      const JointConstraint& c = s.joint_constraints[s.tree_joints[q]];
      for (int i = 0; i < c.block.size(); ++i) {
        s.tree_rhs[c.tree_row + static_cast<uint32_t>(i)] =
            col[c.tree_row + static_cast<uint32_t>(i)];
      }
    }
    solve_tree(s, tree);
    float* y = s.tree_extra_y.data() + y_at + static_cast<size_t>(k) * tree_rows;
    for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
      const JointConstraint& c = s.joint_constraints[s.tree_joints[q]];
      for (int i = 0; i < c.block.size(); ++i) {
        const uint32_t at = c.tree_row + static_cast<uint32_t>(i);
        y[at - tree.row_begin] = s.tree_lambda[at];
      }
    }
  }
  // S = K_ee - col . y, padded to 3 x 3.
  float sm[3][3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  float own[3] = {};
  for (int k = 0; k < m; ++k) {
    const float* y = s.tree_extra_y.data() + y_at + static_cast<size_t>(k) * tree_rows;
    for (int l = 0; l < m; ++l) {
      float v = tree_row_coupling(rows[l], true, rows[k], true, ba) +
                tree_row_coupling(rows[l], false, rows[k], false, bb);
      if (l == k) own[k] = v;
      const float* col = s.tree_extra_c.data() + static_cast<size_t>(l) * total;
      for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
        const JointConstraint& c = s.joint_constraints[s.tree_joints[q]];
        for (int i = 0; i < c.block.size(); ++i) {
          const uint32_t at = c.tree_row + static_cast<uint32_t>(i);
          v -= col[at] * y[at - tree.row_begin];
        }
      }
      sm[k][l] = v;
    }
  }
  invert_schur(sm, own, m, s_inv);
  TreeExtraGroup g;
  g.body_a = body_a;
  g.body_b = body_b;
  g.m = m;
  for (int k = 0; k < m; ++k) g.rows[k] = rows[k];
  for (int k = 0; k < kMaxGroupRows; ++k) {
    for (int l = 0; l < kMaxGroupRows; ++l) g.s_inv[k][l] = s_inv[k][l];
  }
  g.y_at = y_at;
  if (found < s.tree_extra_groups.size()) {
    s.tree_extra_groups[found] = g;  // the slot's rows changed within the pass
  } else {
    found = static_cast<uint32_t>(s.tree_extra_groups.size());
    s.tree_extra_groups.push_back(g);
  }
  return y_at;
}

void apply_tree_compensation(WorldScratch& s, uint32_t t, size_t y_at, int m, const float* delta) {
  const JointTree& tree = s.trees[t];
  const size_t tree_rows = tree.row_end - tree.row_begin;
  const float* y = s.tree_extra_y.data() + y_at;
  float comp[kMaxBlockRows];
  for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
    JointConstraint& c = s.joint_constraints[s.tree_joints[q]];
    bool any = false;
    for (int i = 0; i < c.block.size(); ++i) {
      const size_t at = c.tree_row + static_cast<uint32_t>(i) - tree.row_begin;
      float v = 0.0f;
      for (int k = 0; k < m; ++k) v -= y[static_cast<size_t>(k) * tree_rows + at] * delta[k];
      comp[i] = v;
      any = any || v != 0.0f;
    }
    if (!any) continue;
    c.block.apply(s.solver_bodies[c.body_a], s.solver_bodies[c.body_b], comp);
    for (int i = 0; i < c.block.size(); ++i)
      s.tree_acc[c.tree_row + static_cast<uint32_t>(i)] += comp[i];
  }
}

}  // namespace rwd::sim::d3
