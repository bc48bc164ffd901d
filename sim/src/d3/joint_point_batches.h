// SPDX-License-Identifier: MIT
#pragma once
// Point joints (JointConstraint::point) coloured into batches and solved in
// the solver's lanes (wide_float.h), as the contacts are (contact_batches.h).
//
// Colouring: each point joint, in slot order, takes the first of
// kColorCount colours in which neither of its movable bodies has a point
// joint yet; joints of one colour share no movable body, so the lanes of a
// batch can be solved at once with the result of solving them one after
// another. Batches are solved colour by colour; a joint that finds no
// colour stays on the scalar path (joint_point.cpp). The order depends
// only on the joint list, never on the lane count or the instruction set,
// and every lane computes with IEEE single-precision operations alone, so
// SSE2, NEON and plain arrays give the same bits.
#include <cstdint>

#include "d3/wide_float.h"

namespace rwd::sim {
class WorldScratch;
struct WorldState;
}  // namespace rwd::sim

namespace rwd::sim::d3 {

inline constexpr uint32_t kNoPointJoint = 0xFFFFFFFFu;

/// kLanes point joints, structure of arrays. An empty lane names the
/// immovable body 0 on both sides and is never written back.
struct alignas(16) PointBatch {
  // Left unset when made (the batch is a kilobyte, made afresh each tick):
  // build_point_batches() sets what it packs for every lane, and
  // refresh_point_batches() every lane of the rest before any pass reads
  // them.
  PointBatch() {}          // NOLINT(modernize-use-equals-default): = default would zero it
  uint32_t joint[kLanes];  ///< index into scratch.joint_constraints, or kNoPointJoint
  uint32_t body_a[kLanes];
  uint32_t body_b[kLanes];
  uint8_t movable_a[kLanes];
  uint8_t movable_b[kLanes];
  /// What its lanes are (kPointBare, kPointBall, kPointHinge:
  /// joint_angular_batches.h), and for an angular kind its part batch's
  /// index (in scratch.ball_parts or scratch.hinge_parts).
  uint8_t kind;
  uint32_t part;
  alignas(16) float anchor_a[3][kLanes];  ///< from A's centre, world frame, tick start
  alignas(16) float anchor_b[3][kLanes];
  alignas(16) float delta_center[3][kLanes];
  // Refreshed at each substep's start: the lever arms, what a unit
  // impulse does to each body's angular velocity (inverse inertia times
  // [r]x, row-major), and the inverse effective mass (symmetric).
  alignas(16) float ra[3][kLanes];
  alignas(16) float rb[3][kLanes];
  alignas(16) float turn_a[9][kLanes];
  alignas(16) float turn_b[9][kLanes];
  alignas(16) float inv_k[6][kLanes];  ///< xx, xy, xz, yy, yz, zz
  alignas(16) float mass_a[kLanes];
  alignas(16) float mass_b[kLanes];  ///< inverse masses
  alignas(16) float impulse[3][kLanes];
  alignas(16) float tick_impulse[3][kLanes];  ///< impulse summed over the tick's substeps
};

/// Colours this tick's point joints and packs them (after prepare_joints
/// has marked them), each batch with joints of one kind (a bare point, a
/// ball joint's or a hinge's angular part with it); marks the packed ones
/// JointConstraint::batched.
void build_point_batches(const WorldState& state, WorldScratch& scratch);
/// The stages of joint_point.cpp and joint_angular.cpp over the batches.
/// A batch's lanes' angular parts are refreshed after their points (against
/// the point's inverse mass just made); their warm start, passes and the
/// hinges' projection are stages of their own, run before the joints'
/// structure (the angular parts of every batch, then the trees, the other
/// joints and the points), the order the scalar path keeps. (Each batch's
/// angular parts just before its points, colour by colour, spares a gather
/// and a scatter a pass, but a ragdoll pile then settled later, a nudged
/// one not within 8 s: measured, not explained.)
void refresh_point_batches(WorldScratch& scratch);
void warm_start_point_batches(WorldScratch& scratch);
/// The batches' angular parts' warm start (with the scalar path's, before
/// any structure's).
void warm_start_angular_batches(WorldScratch& scratch);
/// `contacted_only`: only the joints with a body a contact acts on (the
/// second pass after the contacts, joint_solver.h); the others' bodies and
/// impulses are left exactly as they are.
void solve_point_batches(WorldScratch& scratch, bool use_bias, bool contacted_only = false);
/// The batches' angular parts' passes (same `contacted_only`), before the
/// points'.
void solve_angular_batches(WorldScratch& scratch, bool use_bias, bool contacted_only = false);
void project_point_batches(WorldScratch& scratch);
/// The batched hinges' axes and limits brought back (before any point's
/// projection).
void project_angular_batches(WorldScratch& scratch);
/// Adds each lane's impulses to their sums over the tick (once a substep,
/// as sum_joint_impulses() does for the other joints).
void sum_point_batches(WorldScratch& scratch);
/// Writes the batches' impulses and their sums over the tick back to their
/// joints, once the tick's `substeps` are done (before the impulses are
/// stored and the breaks checked).
void store_point_batches(WorldScratch& scratch, int substeps);

}  // namespace rwd::sim::d3
