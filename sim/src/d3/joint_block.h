// SPDX-License-Identifier: MIT
#pragma once
// A joint's rows solved together. The rows that make a joint what it is
// (a hinge's point and axis, a weld's six) form a block solved as one
// small dense system each pass, so a body hung far from its centre of mass
// obeys its joint in one pass instead of the many a row-by-row sweep
// needs when a lever arm makes the rows fight (a pendulum's pivot inertia
// is m r^2 larger than the inertia about its centre; row by row, each pass
// undoes a little of the last).
//
// The joint's other rows (limits, motors, springs) are solved before the
// block, each against the block held rigid: its effective mass is the
// Schur complement of the block, and the impulse it applies comes with
// the block impulse that leaves the block's rows unmoved. So a limit stops
// a pendulum about its pivot, not about its centre of mass.
//
// A row's impulse lambda applies -linear lambda and -angular_a lambda to A,
// +linear lambda and +angular_b lambda to B; its velocity is
// linear . (v_B - v_A) + angular_b . w_B - angular_a . w_A.
#include <cstddef>
#include <cstdint>

#include "d3/joint_math.h"

namespace rwd::sim {
class WorldScratch;
}

namespace rwd::sim::d3 {

struct SolverBody;

struct JointRow {
  Vec3 linear;
  Vec3 angular_a;
  Vec3 angular_b;
};

/// A linear row along unit `axis` between anchors with lever arms arm_a
/// (on A) and rb (on B).
inline JointRow linear_jacobian(Vec3 axis, Vec3 arm_a, Vec3 rb) {
  return {axis, cross(arm_a, axis), cross(rb, axis)};
}
/// An angular row about unit `axis`.
inline JointRow angular_jacobian(Vec3 axis) {
  return {Vec3{}, axis, axis};
}

/// How one row is driven: a velocity bias toward zero error and the soft
/// step's mass and impulse scales (rigid: no bias, 1, 0).
struct RowTerms {
  float bias = 0.0f;
  float mass_scale = 1.0f;
  float impulse_scale = 0.0f;
};

inline constexpr int kMaxBlockRows = 6;
inline constexpr int kMaxGroupRows = 3;

/// The structural rows of one joint for one pass, factored.
class RowBlock {
 public:
  /// Adds a row; at most kMaxBlockRows.
  void add(const JointRow& row) { rows_[n_++] = row; }
  /// Empties the block for new rows. What an earlier factor() left is not
  /// cleared: factor() rewrites it for the rows added, and nothing reads
  /// it before (clearing 500 bytes a joint each substep was a tenth of a
  /// large joint scene's step).
  void clear() { n_ = 0; }
  int size() const { return n_; }
  const JointRow& row(int i) const { return rows_[i]; }
  /// Builds K = J M^-1 J^T for the bodies and factors it (L D L^T). A
  /// pivot too small to trust (rows neither body can move along) leaves
  /// its row out: it takes no impulse.
  void factor(const SolverBody& a, const SolverBody& b);
  /// x = K^-1 rhs over the rows kept (the rest get 0).
  void solve(const float* rhs, float* x) const;
  /// The velocity of row i.
  float velocity(int i, const SolverBody& a, const SolverBody& b) const;
  /// K column of an outside row: what a unit impulse along `other` does
  /// to each block row's velocity.
  void coupling(const JointRow& other, float* out) const;
  /// Applies impulse lambda[i] along each row.
  void apply(SolverBody& a, SolverBody& b, const float* lambda) const;

 private:
  int n_ = 0;
  JointRow rows_[kMaxBlockRows];
  Vec3 ia_[kMaxBlockRows];  ///< A's inverse inertia times angular_a
  Vec3 ib_[kMaxBlockRows];
  float mass_sum_ = 0.0f;  ///< A's plus B's inverse mass
  float l_[kMaxBlockRows][kMaxBlockRows] = {};
  float d_[kMaxBlockRows] = {};
  bool kept_[kMaxBlockRows] = {};
};

/// Up to M (at most kMaxGroupRows) extra rows solved against a rigid
/// block (see above). M = 1 is a lone limit or motor row, small enough to
/// keep between passes (JointConstraint::extras).
template <int M>
class RowGroupOf {
 public:
  /// `block` must be factored; `block_impulse` (its rows' accumulated
  /// impulses) takes the compensating impulses apply() adds. m <= M.
  void prepare(const RowBlock& block, const JointRow* rows, int m, const SolverBody& a,
               const SolverBody& b);
  int size() const { return m_; }
  /// The group's row velocities.
  void velocity(const SolverBody& a, const SolverBody& b, float* out) const;
  /// x = S^-1 rhs, S the block's Schur complement for these rows.
  void solve(const float* rhs, float* x) const;
  /// Applies impulses delta[k] along the group's rows, with the block
  /// impulse that holds the block's rows where they were.
  void apply(const RowBlock& block, SolverBody& a, SolverBody& b, const float* delta,
             float* block_impulse) const;

 private:
  // Written by prepare() for the rows it is given before anything reads
  // them (not zeroed: a group is made on the stack every pass).
  int m_ = 0;
  JointRow rows_[M];
  float y_[M][kMaxBlockRows];  ///< K_bb^-1 K_be, per group row
  float s_[M][M];              ///< the Schur complement, inverted
};
using RowGroup = RowGroupOf<kMaxGroupRows>;

/// The inverse of an extra group's Schur complement S (m x m of a 3 x 3,
/// the rest of `sm` the identity) into `out` (m x m, zeros elsewhere),
/// leaving out the rows whose diagonal kept too small a share of their own
/// diagonal `own` (K_ee) to trust: rows the base holds (joint_block.cpp).
void invert_schur(float (*sm)[3], const float* own, int m, float (*out)[3]);

/// Row velocity of a lone row.
float row_velocity(const JointRow& r, const SolverBody& a, const SolverBody& b);
/// Applies impulse lambda along a lone row.
void apply_row(const JointRow& r, SolverBody& a, SolverBody& b, float lambda);

/// Solves a block's rows toward zero velocity plus bias[i], soft per
/// `soft` when use_bias (rigid otherwise), accumulating into impulse[].
void solve_block(const RowBlock& block, SolverBody& a, SolverBody& b, const float* bias,
                 const JointSoftness& soft, bool use_bias, float* impulse);

/// A one-row group against a joint's own block (a limit, or the axis a
/// motor and spring drive), kept for the passes of a substep that see the
/// same block and the same row (JointConstraint::kept).
struct KeptRow {
  RowGroupOf<1> group;
  bool ready = false;
};
/// Where a joint keeps its one-row groups: slot 0 for the axis of a motor
/// or spring, the limit kinds (kRowLower, kRowUpper, kRowCone) for theirs.
inline constexpr int kKeptRows = 4;
inline constexpr int kKeptAxis = 0;

/// What a joint's extra rows (springs, motors, limits not in its
/// structure) are solved against, held rigid: its own block, or (`tree`
/// set) every structural row of the joint tree it is in, so a spring on a
/// knuckle also moves the wheel hung from it.
struct ExtraBase {
  const RowBlock* block = nullptr;  ///< the joint's own structure
  float* block_impulse = nullptr;   ///< its rows' accumulated impulses
  WorldScratch* scratch = nullptr;  ///< set for a joint in a tree
  uint32_t tree = 0;
  uint32_t joint = 0;   ///< its joint constraint, for a joint in a tree
  uint32_t body_a = 0;  ///< the joint's solver bodies
  uint32_t body_b = 0;
  /// Set for a joint on its own whose bodies stand where its rows were
  /// last refreshed: its one-row groups by slot, made once and kept (see
  /// KeptRow). Null otherwise: each pass makes them anew.
  KeptRow* kept = nullptr;
};

/// One to three extra rows solved together against a rigid base.
class ExtraGroup {
 public:
  /// `slot` (kKeptAxis or a limit kind) names the group among its joint's,
  /// for a tree's reuse of it (prepare_tree_group).
  void prepare(const ExtraBase& base, const JointRow* rows, int m, const SolverBody& a,
               const SolverBody& b, int slot);
  void velocity(const SolverBody& a, const SolverBody& b, float* out) const;
  /// x = S^-1 rhs, S the base's Schur complement for these rows.
  void solve(const float* rhs, float* x) const;
  /// Applies delta[k] along the rows, with the base's compensation.
  void apply(const ExtraBase& base, SolverBody& a, SolverBody& b, const float* delta) const;

 private:
  RowGroup local_;  // against a block
  bool tree_ = false;
  int m_ = 0;
  JointRow rows_[kMaxGroupRows];
  float s_[kMaxGroupRows][kMaxGroupRows] = {};  // against a tree: S^-1
  size_t y_at_ = 0;                             // and its solved couplings
};

/// One extra row against its base: drives its velocity to `speed` plus
/// the terms' bias, its accumulated `impulse` kept in [lo, hi]. A one-sided
/// row (lo 0) that holds no impulse and is not being driven shut costs
/// one velocity read. `slot` (kKeptAxis or a limit kind) names the row's
/// kept group when the base keeps them.
void solve_extra_row(const ExtraBase& base, SolverBody& a, SolverBody& b, const JointRow& row,
                     const RowTerms& t, float speed, float lo, float hi, float& impulse, int slot);

}  // namespace rwd::sim::d3
