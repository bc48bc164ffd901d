// SPDX-License-Identifier: MIT
#pragma once
// The joint stages of the solver, run beside the contact stages in the same
// substeps (contact_solver.cpp): prepare once a tick, then per substep warm
// start, solve with the soft bias, and relax without it after the move;
// after the substeps, store the impulses and break what exceeded its
// threshold.
//
// A joint's structural rows (what makes it a hinge or a weld) are built
// where the bodies stand and factored as one block (joint_block.h) at the
// start of each substep, for its warm start and solve, and again after
// its move, for the relax: every pass reads and applies along the rows
// its factors were built for. (Rows factored once a tick disagree with
// the bodies as they turn; rows held for the tick apply a light link's
// heavy load at a lever that has moved on and spin it. Either way a heavy
// load on light links flies apart.) Joints that join bodies into a tree (chains, ropes of links,
// bridges, ragdolls) have all their structural rows solved together, as
// one exact sparse system over the tree (joint_tree.cpp), so a light link
// holding a heavy load neither stretches nor waits on many passes for the
// load to travel the chain; the other joints are solved one after
// another, in slot order. Each joint type is a row of the table in
// joint_solver.cpp, written in its own file (joint_<type>.cpp).
#include <cstdint>
#include <vector>

#include "d3/joint_block.h"
#include "d3/joint_math.h"
#include "d3/solver_body.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim {
class WorldScratch;
}

namespace rwd::sim::d3 {

/// The bodies' current frames within a substep: where the anchors and the
/// joint frames are after the bodies' motion since the tick began.
struct JointFrames {
  Vec3 ra;  ///< anchor on A from A's centre
  Vec3 rb;
  Vec3 d;   ///< anchor B minus anchor A (the point error)
  Quat qa;  ///< A's rotation now
  Quat qb;
  Quat fa;  ///< the joint frame on A now
  Quat fb;
};

/// What a block row is: part of the joint's structure, or one of its
/// limits (whose impulse is kept in lower_impulse, upper_impulse or
/// cone_impulse, and may only push).
enum : uint8_t { kRowStructure = 0, kRowLower = 1, kRowUpper = 2, kRowCone = 3 };

/// One limit of a joint where the bodies stand: its row (oriented so a
/// positive impulse opens the gap) and the gap (rad or m; < 0 crossed).
struct LimitRow {
  JointRow row;
  float gap = 0.0f;
  uint8_t kind = kRowLower;
};
inline constexpr int kMaxLimitRows = 3;

/// What a unit turn impulse does to two bodies' velocities, with the
/// linear impulse at a point joint's anchors that keeps them together
/// (joint_angular.cpp).
struct TurnResponse {
  Vec3 va;  ///< A's linear velocity
  Vec3 wa;  ///< A's angular velocity
  Vec3 vb;
  Vec3 wb;
};

/// One joint as the solver sees it for a tick. Anchors and frames are
/// world-oriented at the start of the tick; each pass turns them by how far
/// the bodies have turned since (their delta rotations), so the joint
/// measures its error from the bodies' motion within the tick.
struct JointConstraint {
  uint32_t record = 0;  ///< index into WorldState::joints
  uint32_t body_a = 0;  ///< solver body (0: the immovable body)
  uint32_t body_b = 0;
  Vec3 anchor_a;      ///< from A's centre, world frame, tick start
  Vec3 anchor_b;      ///< from B's centre
  Vec3 delta_center;  ///< B's centre minus A's, tick start
  Quat rotation_a;    ///< A's mass-frame rotation, tick start
  Quat rotation_b;
  Quat frame_a;  ///< the joint's frame on A in the world, tick start
  Quat frame_b;
  JointSoftness soft;          ///< the structural rows
  JointSoftness spring_soft;   ///< springs (hertz, damping_ratio), weld linear part
  JointSoftness angular_soft;  ///< weld angular part
  float h = 0.0f;              ///< substep, s
  // Impulses of this tick (copied from the record, stored back after).
  Vec3 linear_impulse;
  Vec3 angular_impulse;
  Vec3 motor_impulse;
  Vec3 spring_impulse;
  float axial_impulse = 0.0f;
  float lower_impulse = 0.0f;
  float upper_impulse = 0.0f;
  float cone_impulse = 0.0f;
  /// The structural impulses summed over the tick's substeps (breaking).
  Vec3 tick_linear;
  Vec3 tick_angular;
  /// The structural rows at the tick's start, factored for the bodies.
  RowBlock block;
  /// What each block row is (kRow*) and, for a limit, its gap as of the
  /// rows' refresh (a limit already reached joins the structure: see
  /// refresh_joint_rows).
  uint8_t row_kind[kMaxBlockRows] = {};
  float row_gap[kMaxBlockRows] = {};
  /// Rows the joint's block may grow to (its structure and limits; the
  /// tree reserves that many).
  uint8_t capacity = 0;
  /// The joint reads the bodies' orientations (its frames), not only its
  /// anchors: joint_frames() computes them only then.
  bool orients = true;
  /// The tree the joint is solved in (kNoTree: on its own), and where its
  /// rows start in the tree's row vectors.
  uint32_t tree = 0xFFFFFFFFu;
  uint32_t tree_row = 0;
  /// Where the tree's factorization keeps what the subtree below the
  /// joint adds to its rows (rows x rows, in scratch.tree_arena).
  uint32_t tree_update = 0;
  /// A ball joint with nothing but its point (no limit, motor or spring)
  /// solved on its own: its three rows as one 3 x 3 point constraint
  /// (joint_point.cpp) instead of the general block. The lever arms and
  /// the inverse effective mass are those of the rows' last refresh.
  bool point = false;
  /// A point joint packed into a lane batch (joint_point_batches.h); the
  /// rest (no colour left) stay on the scalar point path.
  bool batched = false;
  /// A ball joint's motor and spring rows (the three relative turns)
  /// against its block, made at the first pass after each refresh of the
  /// block and kept for the substep's other passes: neither the block nor
  /// those rows change between refreshes (joints solved on their own).
  bool orientation_ready = false;
  ExtraGroup orientation;
  Vec3 point_ra;
  Vec3 point_rb;
  Mat3 point_inv_mass;
  /// The frames and the limits where the bodies stood at the rows' last
  /// refresh. The bodies stay there until the substep's move
  /// (WorldScratch::joint_frames_fresh), so the warm start and the passes
  /// before the move read these rather than work them out again.
  JointFrames frames;
  LimitRow limits[kMaxLimitRows];
  uint8_t limit_count = 0;
  /// The one-row groups against the block at those frames (KeptRow), for
  /// a joint solved on its own.
  KeptRow kept[kKeptRows];
  /// A point joint with an angular part (joint_angular.cpp): a ball
  /// joint's cone-twist limit and angular motor solved apart from its
  /// point. The limits are `limits`, with their effective masses against
  /// the point; the motor's inverse effective mass against it is
  /// angular_inv_mass; the point's own inverse effective mass (made at
  /// frames.ra, frames.rb) is angular_point_inv.
  bool angular = false;
  float limit_mass[kMaxLimitRows] = {};
  Mat3 angular_inv_mass;
  Mat3 angular_point_inv;
  /// What a unit impulse of each limit, and of the motor about each world
  /// axis, does to the bodies' velocities (the point held).
  TurnResponse limit_response[kMaxLimitRows];
  TurnResponse motor_response[3];
  /// Bit k: limit k's mass and response are made (joint_angular.cpp).
  uint8_t limit_ready = 0;
  /// A hinge's angular part at the refresh: its axis and angle; the two
  /// turns off the axis, their misalignment (rad), accumulated impulses
  /// and inverse 2 x 2 effective mass against the point (xx, xy, yy);
  /// the axis turn's effective mass; the three turns' responses.
  bool hinge = false;
  Vec3 hinge_axis;
  float hinge_angle = 0.0f;
  Vec3 align_axis[2];
  float align_error[2] = {};
  float align_impulse[2] = {};
  float align_inv[3] = {};
  float axial_mass = 0.0f;
  TurnResponse align_response[2];
  TurnResponse axial_response;
};

inline constexpr uint32_t kNoTree = 0xFFFFFFFFu;

/// The functions of one joint type.
struct JointOps {
  /// Readies the stored impulses for the tick (optional).
  void (*prepare)(const JointRecord& j, JointConstraint& c);
  /// The structural rows at frames `f`, into `out`; their count, 0 when
  /// the type solves itself (`solve`).
  int (*rows)(const JointRecord& j, const JointFrames& f, JointRow* out);
  /// The angular error the structural angular rows drive to zero, at `f`
  /// (a world rotation vector, rad; projected on each row's axis).
  Vec3 (*angular_error)(const JointRecord& j, const JointFrames& f);
  /// The joint's limits where the bodies stand, into `out`; their count
  /// (optional: types without limits).
  int (*limits)(const JointRecord& j, const JointFrames& f, LimitRow* out);
  /// The rows beside the structure and limits (springs, motors), each
  /// against `base` held rigid (optional).
  void (*extras)(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                 const JointFrames& f, bool use_bias, const ExtraBase& base);
  /// Applies the last substep's impulses again: all of them for a type
  /// without structural rows, else those of its springs and motors (the
  /// stage applies the structure's and the limits' along their rows).
  void (*warm_start)(const JointRecord& j, const JointConstraint& c, SolverBody& a, SolverBody& b);
  /// One pass over a joint without structural rows; use_bias false in the
  /// relax pass (optional: types with rows).
  void (*solve)(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                bool use_bias);
};
const JointOps& joint_ops(JointType type);

/// Whether a joint constrains its bodies: live, unbroken, both bodies
/// enabled (a joint to a disabled body waits until it is enabled again).
bool joint_acts(const WorldState& state, const JointRecord& j);

// The stages (joint_solver.cpp), over scratch.joint_constraints.
void prepare_joints(const WorldState& state, WorldScratch& scratch, float h);
/// Rebuilds and refactors the joints' structural rows (and the trees)
/// where the bodies stand: all of them at the start of a substep (the
/// warm start does it first), only the trees' after its move (`trees_only`:
/// a joint solved on its own keeps its rows for the relax, one substep's
/// turn behind, which its well-conditioned block does not notice; a tree's
/// factors must match the rows it applies).
void refresh_joint_rows(const WorldState& state, WorldScratch& scratch, bool trees_only = false);
void warm_start_joints(const WorldState& state, WorldScratch& scratch);
/// `contacted_only`: only the trees and joints with a body a contact acts
/// on (SolverBody::contacted); the others are where the last pass left
/// them.
void solve_joints(const WorldState& state, WorldScratch& scratch, bool use_bias,
                  bool contacted_only = false);
/// Closes what the substep left open of the joints' structure: each tree,
/// and each joint on its own, solved once more for its position errors
/// and its bodies moved by the answer (velocities untouched). A contact
/// that stops a light limb dead while the heavy body it hangs from still
/// moves leaves the joint between them open by that speed times the
/// substep; the soft bias would close it over several substeps, the
/// projection closes it before the next.
void project_joints(const WorldState& state, WorldScratch& scratch);

// Point joints (JointConstraint::point), joint_point.cpp: the same stages
// as the general block, in closed form.
/// Whether a joint solved on its own is solved as a point: a ball joint
/// without a spring (its limit and motor, if any, its angular part).
bool is_point_joint(const JointRecord& j, const JointConstraint& c);
/// Whether a ball joint's limit and motor may be solved apart from its
/// point (no spring; a motor impulse only with a motor).
bool has_angular_part(const JointRecord& j);
/// The angular parts' stages (joint_angular.cpp), over
/// scratch.joint_angular: their rows where the bodies stand (at a
/// substep's start), the warm start, and a pass before the points'.
void refresh_angular_parts(const WorldState& state, WorldScratch& scratch);
void warm_start_angular_parts(const WorldState& state, WorldScratch& scratch);
void solve_angular_parts(const WorldState& state, WorldScratch& scratch, bool use_bias,
                         bool contacted_only);
/// The hinges' turns off their axes brought back into line, and their
/// angles back within their limits (before the points' projection).
void project_angular_parts(const WorldState& state, WorldScratch& scratch);
/// Its lever arms where the bodies stand and its inverse effective mass.
void refresh_point(JointConstraint& c, const SolverBody& a, const SolverBody& b);
void warm_start_point(const JointConstraint& c, SolverBody& a, SolverBody& b);
/// One pass: soft toward zero error with the bias, rigid without.
void solve_point(JointConstraint& c, SolverBody& a, SolverBody& b, bool use_bias);
/// The position projection: the anchors moved together (clamped).
void project_point(const JointConstraint& c, SolverBody& a, SolverBody& b);
/// A position error as the projection takes it, clamped to
/// kMaxProjection (m or rad) so a joint torn far apart is pulled back
/// over several substeps instead of teleporting its bodies.
inline constexpr float kMaxProjection = 0.1f;
inline float clamp_projection(float error) {
  return error > kMaxProjection ? kMaxProjection
                                : (error < -kMaxProjection ? -kMaxProjection : error);
}
/// A limit only pushes: a projection that would pull a held limit shut
/// releases it (see release_block_limits), so it is left where it is
/// while the rest of the block still closes.
void release_pulling_limits(const JointConstraint& c, float* x);
/// Moves bodies a and b by displacements lambda[i] along the block's rows
/// (as impulses would move velocities: -M^-1 J^T to A, + to B).
void displace(const RowBlock& block, const float* lambda, SolverBody& a, SolverBody& b);
/// Adds each joint's structural impulses of the substep to its tick sums.
void sum_joint_impulses(WorldScratch& scratch);
/// Stores the impulses in the records and breaks the joints whose tick
/// sums exceeded their break_impulse (into scratch.broken_joints).
void store_joint_impulses(WorldState& state, WorldScratch& scratch);

// Shared by the joint types (joint_rows.cpp).
JointFrames joint_frames(const JointConstraint& c, const SolverBody& a, const SolverBody& b);
/// Velocity of anchor B relative to anchor A.
Vec3 anchor_velocity(const SolverBody& a, const SolverBody& b, Vec3 ra, Vec3 rb);
/// Angular velocity of B relative to A.
inline Vec3 relative_angular_velocity(const SolverBody& a, const SolverBody& b) {
  return b.angular_velocity - a.angular_velocity;
}
/// Applies a linear impulse p at the anchors: -p to A at ra, +p to B at rb.
void apply_linear(SolverBody& a, SolverBody& b, Vec3 ra, Vec3 rb, Vec3 p);
/// Applies an angular impulse L: -L to A, +L to B.
inline void apply_angular(SolverBody& a, SolverBody& b, Vec3 l) {
  a.angular_velocity -= a.inv_inertia * l;
  b.angular_velocity += b.inv_inertia * l;
}
/// A structural row with position error `error`: soft with the bias,
/// rigid (no bias) in the relax pass.
inline RowTerms structural_terms(const JointSoftness& soft, float error, bool use_bias) {
  if (!use_bias) return {};
  return {soft.bias_rate * error, soft.mass_scale, soft.impulse_scale};
}
/// A one-sided limit whose `gap` must stay >= 0: speculative while open
/// (it may close within the substep, no more), structural once crossed.
inline RowTerms limit_terms(const JointSoftness& soft, float gap, float h, bool use_bias) {
  if (gap > 0.0f) return {gap / h, 1.0f, 0.0f};  // speculative: may close within the substep
  return structural_terms(soft, gap, use_bias);
}
/// A spring toward zero `error`, soft in every pass.
inline RowTerms spring_terms(const JointSoftness& spring, float error) {
  return {spring.bias_rate * error, spring.mass_scale, spring.impulse_scale};
}

/// The point rows: the anchors coincide (three world axes); returns 3.
int point_rows(const JointFrames& f, JointRow* out);
/// The orientation rows: B keeps its frame relative to A's (three world
/// axes); returns 3.
int orientation_rows(JointRow* out);
/// The frames at the tick's start (no motion yet).
JointFrames start_frames(const JointConstraint& c);
/// The structural rows' accumulated impulses from the joint's stored
/// vectors (linear rows from linear_impulse, angular rows from
/// angular_impulse), and back.
void gather_impulses(const JointConstraint& c, float* acc);
void scatter_impulses(JointConstraint& c, const float* acc);
/// A limit's accumulated impulse by kind (kRowLower, kRowUpper, kRowCone).
float& limit_impulse(JointConstraint& c, uint8_t kind);
float limit_impulse(const JointConstraint& c, uint8_t kind);
/// Bits (1 << kind) of the limits the block holds.
uint8_t held_limits(const JointConstraint& c);
/// A limit may only push: a held limit row whose accumulated impulse went
/// below zero is released, its impulse taken back by the block impulse
/// that changes its own row's velocity alone (K^-1 e_r per released row),
/// so the rest of the block keeps the velocities it was solved for.
/// (Taking it back along the limit's row alone would leave the joint's
/// other rows moving by that impulse times their coupling to it: a pulled
/// elbow limit, released so, sets a light forearm spinning against its
/// hinge.)
void settle_held_limits(JointConstraint& c, SolverBody& a, SolverBody& b, float* acc);
/// The release itself: the held limit rows of c's block whose `total`
/// is negative are brought to zero by a combination of K^-1 columns,
/// added to `total` and, when given, to `step`.
void release_block_limits(const JointConstraint& c, float* total, float* step);
/// The limits not in the block, each as a speculative row against it:
/// those at frames `f`, or (`at_refresh`, f being c.frames) the ones the
/// refresh kept.
void solve_free_limits(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                       const JointFrames& f, bool use_bias, const ExtraBase& base,
                       bool at_refresh = false);
/// Applies the free limits' impulses along their rows at the refresh.
void warm_start_free_limits(const JointConstraint& c, SolverBody& a, SolverBody& b);
/// The bias of each block row: its error (the point error along a linear
/// row, the type's angular error about an angular row, a held limit's
/// gap) times rate.
void structural_bias(const JointConstraint& c, const JointFrames& f, Vec3 angular_error, float rate,
                     float* bias);
/// The rotation from frame A to frame B, in the world (the orientation
/// rows' error).
Vec3 orientation_error(const JointFrames& f);

inline constexpr float kUnbounded = 3.0e38f;

}  // namespace rwd::sim::d3
