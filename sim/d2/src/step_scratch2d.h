// SPDX-License-Identifier: MIT
#pragma once
// Working memory of one step: rebuilt from the state every step, so it is
// never saved, restored or hashed. Kept between steps only so its buffers
// stop allocating once they have grown.
#include <cstdint>
#include <utility>
#include <vector>

#include "manifold2.h"
#include "rewind/core/thread_pool.h"
#include "rewind/sim2d/contact_event2d.h"
#include "rewind/sim2d/world2d_state.h"
#include "shape_bounds2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// A body as the solver sees it during one step.
struct SolverBody2D {
  V2 v;
  W w = 0;
  V2 dp;   ///< translation of the centre of mass since the step began
  Rot dq;  ///< rotation since the step began
  W inv_mass = 0;
  W inv_inertia = 0;
};

/// A moving body's integration over one substep, the same every substep of
/// a step (solve_step2d.cpp).
struct BodyMotion2D {
  uint32_t body = 0;
  bool dynamic = false;    ///< gravity, forces and damping apply
  V2 dv;                   ///< velocity gained: gravity and force
  W dw = 0;                ///< angular velocity gained: torque
  W linear_keep = kWOne;   ///< velocity kept through damping
  W angular_keep = kWOne;  ///< angular velocity kept through damping
};

/// A spring-damper softening of a rigid constraint (soft step): the
/// fraction of the position error fed back per second, and how much of
/// the rigid impulse and of the accumulated impulse the solve applies.
struct Softness2D {
  W bias_rate = 0;
  W mass_scale = kWOne;
  W impulse_scale = 0;
};

/// One contact point as the solver sees it. Everything a pass reads is a
/// scalar fixed at the step's start, so a pass does no division and no
/// vector rotation: velocities along the normal and tangent are sums of
/// four products, and the separation is tracked through the bodies' moves
/// and turns as a sum of six.
struct ContactConstraintPoint2D {
  // The anchors (from each centre of mass at the step's start) as lever
  // arms: r x n turns a spin into speed along the normal, r x t along the
  // tangent, and r . n with r x n gives how far a turn (c, s) moves the
  // anchor along the normal (c r.n + s r x n).
  W rn_a = 0;
  W rn_b = 0;
  W rt_a = 0;
  W rt_b = 0;
  W rd_a = 0;
  W rd_b = 0;
  // Spin gained per unit of impulse: inverse inertia times the lever.
  W spin_n_a = 0;
  W spin_n_b = 0;
  W spin_t_a = 0;
  W spin_t_b = 0;
  W adjusted_separation = 0;  ///< separation minus (rb - ra) . normal
  W normal_mass = 0;
  W tangent_mass = 0;
  W normal_impulse = 0;
  W tangent_impulse = 0;
  W max_normal_impulse = 0;  ///< largest single push this step (restitution)
  W relative_velocity = 0;   ///< normal approach speed at the step's start
};

struct ContactConstraint2D {
  uint32_t a = 0;
  uint32_t b = 0;
  uint32_t contact = 0;  ///< index into the state's contacts
  int count = 0;
  bool block = false;  ///< both normal rows solved together (see k11..)
  V2 normal;
  // An impulse P along the normal changes A's velocity by -P move_a and
  // B's by P move_b (n / m each); along the tangent, by their quarter turns.
  V2 move_a;
  V2 move_b;
  W friction = 0;
  W restitution = 0;
  W rolling_resistance = 0;
  W rolling_mass = 0;
  W rolling_impulse = 0;
  Softness2D softness;
  ContactConstraintPoint2D points[2];
  /// Two-point manifolds: the normal rows' effective-mass matrix K and,
  /// when it is well enough conditioned to solve both points together
  /// (block), its inverse.
  W k11 = 0;
  W k12 = 0;
  W k22 = 0;
  W inv_k11 = 0;
  W inv_k12 = 0;
  W inv_k22 = 0;
};

/// What every joint type needs during one step, fixed at its start.
struct JointConstraint2D {
  uint32_t joint = 0;
  uint32_t a = 0;
  uint32_t b = 0;
  V2 frame_a;  ///< anchors from each centre of mass, world axes
  V2 frame_b;
  V2 delta_center;    ///< cB - cA (grab: cB - target)
  W delta_angle = 0;  ///< B's angle - A's - reference, in [-pi, pi]
  V2 axis_a;          ///< prismatic, wheel: the axis in world axes
  W axial_mass = 0;
  W angular_mass = 0;         ///< 1 / (iA + iB), or 0
  Softness2D soft;            ///< the push-out of rigid parts
  Softness2D spring;          ///< springs (distance, prismatic, wheel, grab; weld's linear part)
  Softness2D angular_spring;  ///< weld's angular part, grab's spin damping
  /// Revolute: the inverse of the point's effective-mass matrix at the
  /// step's anchors, [inv_k11 inv_k12; inv_k12 inv_k22]. The bodies turn
  /// little within a step, so every pass uses it (no division in a pass);
  /// the anchors themselves still turn with the bodies.
  W point_inv_k11 = 0;
  W point_inv_k12 = 0;
  W point_inv_k22 = 0;
  /// Revolute: joint_angle() as the pass numbered `angle_positions` saw it
  /// (JointPass2D::positions). A relax pass and the next substep's solve
  /// see the same rotations; the CORDIC behind the angle is the costliest
  /// part of a revolute row, so the second one reuses it.
  W angle = 0;
  uint32_t angle_positions = UINT32_MAX;
};

/// Bounds of one body for the broadphase.
struct BroadphaseItem2D {
  Box2W box;
  uint32_t index = 0;
  bool moves = false;  ///< moving this step (only pairs with one matter)
};

/// A node of the broadphase's tree: a leaf over `count` entries from
/// `first`, or (count 0) an inner node whose children are nodes `first`
/// and `first + 1`.
struct TreeNode2D {
  Box2W box;
  uint32_t first = 0;
  uint32_t count = 0;
  /// Some body under it moves this step: pairs of two nodes without one
  /// (a level's static boxes) are never walked.
  bool moves = false;
};

class StepScratch2D {
 public:
  std::vector<BroadphaseItem2D> broadphase_items;  ///< the tree's items
  std::vector<TreeNode2D> tree;
  std::vector<uint32_t> item_of_body;  ///< each body's item (UINT32_MAX: none)
  uint32_t tree_refits = 0;            ///< steps the tree was refitted since it was built
  std::vector<uint32_t> sort_counts;   ///< the pair sort's buckets
  std::vector<uint64_t> sort_buffer;   ///< the pair sort's other half
  std::vector<std::pair<uint32_t, uint32_t>> tree_stack;  ///< node pairs left to walk
  std::vector<uint64_t> pairs;                            ///< (a << 32) | b, a < b, sorted
  /// pairs[k]'s manifold this step (update_contacts2d.cpp).
  std::vector<Manifold2> manifolds;
  /// The shapes of this step's pairs' polygon and capsule bodies widened to
  /// W (by body index; where widened[i] is 0 the entry is stale and unread).
  std::vector<WideShape2> wide_shapes;
  std::vector<uint8_t> widened;
  /// The threads the narrowphase cuts its pairs across
  /// (World2D::set_thread_pool); null: the stepping thread. Not owned.
  rwd::ThreadPool* pool = nullptr;
  std::vector<SolverBody2D> bodies;  ///< by body index
  std::vector<BodyMotion2D> moving;  ///< the bodies that move this step, by index
  std::vector<ContactConstraint2D> constraints;
  std::vector<JointConstraint2D> joints;  ///< in solve order: colour by colour
  std::vector<JointConstraint2D> joint_spare;
  std::vector<uint32_t> joint_color;       ///< a joint's colour, by position
  std::vector<uint64_t> joint_color_bits;  ///< per colour, one bit per body
  /// (a << 32) | b of joined pairs that must not collide, sorted.
  std::vector<uint64_t> joined_pairs;
  /// The joined pairs in joint order, this step's and the one joined_pairs
  /// was sorted from.
  std::vector<uint64_t> joined_listed;
  std::vector<uint64_t> joined_listed_before;
  /// The contacts being built; swapped with the state's, so both buffers
  /// are reused.
  std::vector<ContactRecord2D> next_contacts;
  // Sleep: the bodies woken this step, the adjacency the wake floods
  // through, and the islands' union-find.
  std::vector<uint32_t> wake_list;
  std::vector<uint32_t> adjacency_offsets;
  std::vector<uint32_t> adjacency_fill;
  std::vector<uint32_t> adjacency;
  std::vector<uint32_t> island_parent;
  std::vector<W> island_sleep;
  /// This step's contact events (World2D::events() reads them).
  std::vector<ContactEvent2D> events;
};

}  // namespace rwd::sim2d::detail
