// SPDX-License-Identifier: MIT
#pragma once
// Tree-shaped joint islands solved exactly (joint_tree.cpp).
//
// The structural rows of all joints that join moving bodies into a tree
// (no loop through moving bodies; joints to static bodies or the world
// are leaves) form one sparse system K lambda = r, K = J M^-1 J^T. Rooted
// at a body, the tree is eliminated from its leaves: at each body, the
// rows of the joints below it are eliminated into the joint above it, the
// only one left that shares the body, so nothing fills in beyond what the
// bodies already couple (a multifrontal factorization with one front per
// body). The factors are built for the rows where the bodies stand, at
// the start of each substep (for its warm start and solve) and after its
// move (for the relax): a factor of other rows than those applied is
// amplified by a heavy load on light links until the chain flies apart.
// Each pass is one forward and one backward sweep, linear in the joints.
//
// Why: row by row, a light link holding a heavy load needs many passes for
// the load to travel the chain, and the soft step's spring (the joint
// stiffness is proportional to the effective mass a row sees) lets it
// sag: a 20-link chain holding 100 times a link's mass stretched by 6%.
// Solved as one system, every row sees the whole tree's mass.
#include <cstdint>
#include <vector>

#include "d3/joint_block.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim {
class WorldScratch;
}

namespace rwd::sim::d3 {

/// Trees the row-by-row passes hold well enough are left to them, being
/// cheaper and settle sooner (a pile of ragdolls, ten joints each and
/// parts within 13 times each other's mass, opens by under a centimetre
/// and sleeps sooner than solved exactly): a tree is
/// solved exactly when it has more joints than this or joins two moving
/// bodies more than kRowByRowMassRatio times apart in mass (a chain
/// holding a load, a bridge of many planks).
inline constexpr uint32_t kRowByRowTreeJoints = 12;
inline constexpr float kRowByRowMassRatio = 30.0f;

/// Rows of the joints below one body that one front may hold; a body
/// with more leaves its component to the row-by-row solve.
inline constexpr uint32_t kMaxFrontRows = 36;

/// One body of a joint tree.
struct JointTreeBody {
  uint32_t body = 0;          ///< solver body
  uint32_t parent_joint = 0;  ///< joint constraint above it, or kNoParent (the root)
  uint32_t child_begin = 0;   ///< its child joints: scratch.tree_children[begin, end)
  uint32_t child_end = 0;
  uint32_t front = 0;        ///< rows of its child joints
  uint32_t factor_at = 0;    ///< arena: the front's L (front x front) and D (front)
  uint32_t coupling_at = 0;  ///< arena: Y = F^-1 F_cp (front x parent rows)
};

/// One tree: its bodies root first (breadth first), its joints, its rows.
struct JointTree {
  uint32_t body_begin = 0;  ///< scratch.tree_bodies
  uint32_t body_end = 0;
  uint32_t joint_begin = 0;  ///< scratch.tree_joints (constraint indices, slot order)
  uint32_t joint_end = 0;
  uint32_t row_begin = 0;  ///< its rows, [row_begin, row_end) of the tree rows
  uint32_t row_end = 0;
};

/// Extra rows of a tree joint prepared against the tree's factors
/// (prepare_tree_group). What it holds depends only on the rows, the two
/// bodies' masses and the factors, so the passes between two
/// factorizations (both passes before a substep's move, the relax passes
/// after it) that meet the same rows at the same slot reuse it.
struct TreeExtraGroup {
  uint32_t body_a = 0;
  uint32_t body_b = 0;
  int m = 0;
  JointRow rows[kMaxGroupRows];
  float s_inv[kMaxGroupRows][kMaxGroupRows] = {};
  size_t y_at = 0;  ///< scratch.tree_extra_y: m columns over the tree's rows
};

inline constexpr uint32_t kNoParent = 0xFFFFFFFFu;

/// Finds this tick's trees among scratch.joint_constraints (their rows
/// counted) and marks their joints (JointConstraint::tree, tree_row).
void build_joint_trees(WorldScratch& scratch);
/// Factors every tree for its joints' rows as they stand (their blocks
/// refreshed): at the start of each substep and again after its move.
void factor_joint_trees(WorldScratch& scratch);
/// One pass over tree t: the extra rows of its joints, then its structure
/// solved exactly; soft with the bias, rigid without.
void solve_joint_tree(const std::vector<JointRecord>& joints, WorldScratch& scratch, uint32_t t,
                      bool use_bias);

/// The velocity change of one row per unit impulse along another through
/// one body (`*_on_a`: the row acts on that body as its joint's A).
float tree_row_coupling(const JointRow& r, bool r_on_a, const JointRow& s, bool s_on_a,
                        const SolverBody& body);
/// lambda = K^-1 rhs over tree `tree` (scratch.tree_rhs in, consumed;
/// scratch.tree_lambda out).
void solve_tree(WorldScratch& scratch, const JointTree& tree);

/// Readies one to three extra rows of joint constraint `joint` on solver
/// bodies (a, b) of tree t to be solved against the whole tree held
/// rigid: each row's coupling to the tree's rows, solved through the
/// tree's factors (kept in scratch.tree_extra_y for
/// apply_tree_compensation), and the inverse of their Schur complement
/// into s_inv (m x m of a 3 x 3). Returns where the solved couplings
/// start. `slot` (kKeptAxis or a limit kind, < kKeptRows) names the group
/// among the joint's: the same rows at the same slot since the trees were
/// last factored are not prepared again (TreeExtraGroup).
size_t prepare_tree_group(WorldScratch& scratch, uint32_t t, uint32_t joint, int slot,
                          uint32_t body_a, uint32_t body_b, const JointRow* rows, int m,
                          float (*s_inv)[3]);
/// Applies to tree t's rows the impulses that hold them where they were
/// while the rows prepared at `y_at` take delta[k] (and adds them to the
/// tree's accumulated impulses).
void apply_tree_compensation(WorldScratch& scratch, uint32_t t, size_t y_at, int m,
                             const float* delta);

/// A limit may only push: the held limit rows of tree t whose value in
/// `total` (by tree row: accumulated impulses, or a projection's
/// displacements) is negative are released, brought to zero by the
/// combination of the tree's K^-1 columns for those rows (one exact solve
/// each), which moves no other row of the tree. The combination is added
/// to `total` and, when given, to `step`. At most kMaxReleased rows; the
/// released set grows while releasing one makes another pull.
void release_tree_limits(WorldScratch& scratch, const JointTree& tree, float* total, float* step);
inline constexpr int kMaxReleased = 8;

/// x = A^-1 x for a small symmetric positive semi-definite n x n matrix a
/// (row-major, lower part read and overwritten by its factors), a row
/// whose pivot is too small to trust left out (x zero there).
void solve_dense_spd(float* a, uint32_t n, float* x);

/// Moves the bodies of tree t so its structural rows' position errors
/// vanish (to first order), without touching velocities: one exact solve
/// of K x = -C applied as displacements (post-stabilization).
void project_joint_tree(const std::vector<JointRecord>& joints, WorldScratch& scratch, uint32_t t);

}  // namespace rwd::sim::d3
