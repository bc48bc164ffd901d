// SPDX-License-Identifier: MIT
// Letting go of a tree's held limits that would pull (joint_tree.h): the
// released rows' columns of K^-1, and the weights of them that zero the
// released rows' impulses while leaving every other row's velocity (or, in
// the projection, its displacement) as the exact solve left it.
#include "d3/joint_solver.h"
#include "d3/joint_tree.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

void release_tree_limits(WorldScratch& s, const JointTree& tree, float* total, float* step) {
  std::vector<JointConstraint>& joints = s.joint_constraints;
  const size_t rows = s.tree_rhs.size();
  uint32_t released[kMaxReleased];
  int m = 0;
  // A few rounds: releasing rows moves the impulses of the others, which
  // may then pull in turn.
  for (int round = 0; round < 3 && m < kMaxReleased; ++round) {
    const int before = m;
    for (uint32_t k = tree.joint_begin; k < tree.joint_end && m < kMaxReleased; ++k) {
      const JointConstraint& c = joints[s.tree_joints[k]];
      for (int i = 0; i < c.block.size() && m < kMaxReleased; ++i) {
        const uint32_t at = c.tree_row + static_cast<uint32_t>(i);
        if (c.row_kind[i] == kRowStructure || !(total[at] < 0.0f)) continue;
        bool seen = false;
        for (int q = 0; q < m; ++q) seen = seen || released[q] == at;
        if (seen) continue;
        // Its column of K^-1: the impulses that change its row's velocity
        // by one and no other row's.
        for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
          const JointConstraint& o = joints[s.tree_joints[q]];
          for (int r = 0; r < o.block.size(); ++r) {
            s.tree_rhs[o.tree_row + static_cast<uint32_t>(r)] = 0.0f;
          }
        }
        s.tree_rhs[at] = 1.0f;
        solve_tree(s, tree);
        float* column = s.tree_release.data() + static_cast<size_t>(m) * rows;
        for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
          const JointConstraint& o = joints[s.tree_joints[q]];
          for (int r = 0; r < o.block.size(); ++r) {
            const uint32_t row = o.tree_row + static_cast<uint32_t>(r);
            column[row] = s.tree_lambda[row];
          }
        }
        released[m++] = at;
      }
    }
    if (m == before) break;
    // The weights t that zero every released row: (K^-1)_RR t = -total_R.
    float w[kMaxReleased * kMaxReleased];
    float t[kMaxReleased];
    const uint32_t n = static_cast<uint32_t>(m);
    for (uint32_t r = 0; r < n; ++r) {
      for (uint32_t c = 0; c < n; ++c) {
        w[r * n + c] = s.tree_release[static_cast<size_t>(c) * rows + released[r]];
      }
      t[r] = -total[released[r]];
    }
    solve_dense_spd(w, n, t);
    for (uint32_t q = tree.joint_begin; q < tree.joint_end; ++q) {
      const JointConstraint& o = joints[s.tree_joints[q]];
      for (int r = 0; r < o.block.size(); ++r) {
        const uint32_t row = o.tree_row + static_cast<uint32_t>(r);
        float v = 0.0f;
        for (uint32_t k = 0; k < n; ++k) {
          v += s.tree_release[static_cast<size_t>(k) * rows + row] * t[k];
        }
        total[row] += v;
        if (step != nullptr) step[row] += v;
      }
    }
  }
}

}  // namespace rwd::sim::d3
