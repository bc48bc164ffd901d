// SPDX-License-Identifier: MIT
#pragma once
// Per-step working memory of a World3D. Nothing here is state: what is kept
// from step to step (the broadphase's trees and sweep order) only speeds up
// finding what the state alone decides, and restore() has the trees
// rebuilt, so a restored world steps exactly like the one that was saved. The vectors keep their
// capacity between steps, so a warmed-up world does not allocate.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "d3/aabb_tree.h"
#include "d3/broadphase.h"
#include "d3/compound_contact.h"
#include "d3/contact_batches.h"
#include "d3/joint_angular_batches.h"
#include "d3/joint_point_batches.h"
#include "d3/joint_solver.h"
#include "d3/joint_tree.h"
#include "d3/manifold.h"
#include "d3/solver_body.h"
#include "d3/swept_shape.h"
#include "rewind/core/thread_pool.h"
#include "rewind/sim/body_event.h"
#include "rewind/sim/contact_event.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::d3 {

/// No contact record (an exit event's pair has none this step).
inline constexpr uint32_t kNoRecord = 0xFFFFFFFFu;

/// This step's manifold for one contact record, parallel to
/// WorldState::contacts (the vector may be longer; entries past the
/// contacts are stale). `valid` is 0 for records carried over unchanged
/// because both bodies sleep (their geometry is not needed).
struct ContactGeometry {
  Manifold manifold;
  float friction;
  float restitution;
  uint8_t valid;
};

/// One pair the narrowphase collides this step (narrowphase.cpp): planned
/// in pair order, collided on the step's threads into its own result
/// slots, then gathered into the contact cache in pair order again.
struct PairJob {
  uint32_t a = 0;
  uint32_t b = 0;
  /// Last step's records of the pair in other_contacts (prior_count in a
  /// row), when its bodies are the same ones.
  uint32_t prior = 0;
  uint32_t prior_count = 0;
  uint32_t slot = 0;    ///< first of its result slots (kMaxContactParts for parts)
  uint8_t parts = 0;    ///< 1: collided as parts (a compound on a side)
  uint8_t count = 0;    ///< records it produced (0: the pair is dropped)
  uint8_t carried = 0;  ///< 1: its manifold was carried forward
};

/// How hard overlaps are pushed out: the separating speed per metre of
/// overlap and the fraction of a rigid push-out impulse applied per substep,
/// from a spring-damper of the contact hertz and damping ratio.
struct Softness {
  float bias_rate;   ///< 1/s
  float mass_scale;  ///< (0, 1]
};

struct ConstraintPoint {
  Vec3 anchor_a;  ///< from A's centre at step start, world frame (fixed)
  Vec3 anchor_b;
  float base_separation;    ///< separation minus the anchors' normal offset
  float separation;         ///< metres, as of the last position update
  float relative_velocity;  ///< normal approach speed before the step (restitution)
  float normal_mass;
  float normal_impulse;
  float tangent_impulse1;
  float tangent_impulse2;
  float max_normal_impulse;
  /// N*s: the normal impulse of the whole tick, every substep's and the
  /// bounce's (ContactBatch, apply_restitution).
  float tick_normal_impulse;
};

/// Which body the push-out holds fixed (support_order.cpp).
enum : uint8_t { kPushFixedNone = 0, kPushFixedA = 1, kPushFixedB = 2 };
/// Support level of a body that rests on nothing.
inline constexpr uint32_t kNoSupport = 0xFFFFFFFFu;

struct ContactConstraint {
  uint32_t body_a;  ///< solver body index
  uint32_t body_b;
  uint32_t record;  ///< index into WorldState::contacts
  uint32_t point_count;
  Vec3 normal;
  Vec3 tangent1;
  Vec3 tangent2;
  float friction;
  float restitution;
  Softness softness;
  uint8_t push_fixed;   ///< kPushFixed*: the lower body of the contact, if any
  uint8_t overlapping;  ///< 1 when a point overlapped past the slop at the start of the tick
  /// Where the constraint is packed: scratch.batches[batch], lane `lane`
  /// (its push-out impulses live there).
  uint32_t batch;
  uint32_t lane;
  /// The manifold's normal K matrix (filled when packed into batches,
  /// with the normal masses): coupling[i][j] is the normal velocity
  /// change at point i per unit normal impulse at point j (fixed for the
  /// step, like the anchors and inverse inertias it is built from).
  float coupling[kMaxManifoldPoints][kMaxManifoldPoints];
  ConstraintPoint points[kMaxManifoldPoints];
};

}  // namespace rwd::sim::d3

namespace rwd::sim {

/// Declared in world3d.h; defined here so the public header stays small.
class WorldScratch {
 public:
  using Aabb = d3::Aabb;
  using BodyPair = d3::BodyPair;
  using ContactGeometry = d3::ContactGeometry;
  using SolverBody = d3::SolverBody;
  using ContactConstraint = d3::ContactConstraint;

  /// The world's geometry store (hulls and the like), which the stages
  /// that collide shapes read. Not owned: World3D keeps it alive, and its
  /// entries never change, so this is not state either.
  const GeometryStore* store = nullptr;
  /// The threads the step cuts its independent work across
  /// (World3D::set_thread_pool; step_threads.h); null: the stepping thread
  /// alone. Not owned.
  ThreadPool* pool = nullptr;
  /// Counts edits of the world (mark_world_edited), so derived facts about
  /// its bodies can be recomputed only after one.
  uint64_t edit_serial = 1;
  /// Whether some body has rolling resistance, as of edit rolling_serial.
  uint64_t rolling_serial = 0;
  bool rolling_any = false;

  // broadphase (find_pairs.cpp, broadphase.h)
  /// By body index: this step's bounds of every awake body, fattened by
  /// the speculative distance and its reach this tick.
  std::vector<Aabb> aabbs;
  std::vector<uint32_t> active;  ///< awake movable bodies, ascending
  /// wake_touched_islands woke bodies this step: `active` lacks them.
  bool woke_bodies = false;
  /// Pairs, sweep and trees; the queries and continuous collision use it
  /// too (prepare_queries first).
  d3::Broadphase broadphase;
  std::vector<BodyPair> pairs;
  std::vector<uint32_t> query_hits;  ///< one query's candidates
  d3::SweptShape swept;              ///< continuous collision's mover
  d3::SweptShape swept_target;       ///< what a spinning mover is advanced against
  /// A shape query's swept shape: kept here, not made per query, as its
  /// room for a compound's children is 2.5 KB to construct.
  d3::SweptShape cast_shape;
  // body frames (body_storage.h: body_axes)
  /// By body index: the rotation matrix of the body's pose at the start of
  /// this step, valid where axes_step[i] == step_serial. The broadphase
  /// fills it for the awake bodies; the others get theirs when first asked.
  std::vector<Mat3> axes;
  std::vector<uint64_t> axes_step;
  /// Counts step() calls of this scratch, never repeating (unlike the
  /// state's step count, which restore() winds back), so a frame computed
  /// in an earlier step, or for a state since restored, is never taken for
  /// this step's.
  uint64_t step_serial = 0;
  // narrowphase
  /// By body index: where a compound's children stand this step,
  /// child_frames[children_at[i]] on, valid where children_step[i] ==
  /// step_serial (plan_pairs places them for its jobs' compounds).
  std::vector<uint32_t> children_at;
  std::vector<uint64_t> children_step;
  std::vector<d3::ChildFrame> child_frames;
  std::vector<ContactRecord> other_contacts;  ///< last step's cache after the swap
  /// This step kept last step's cache as it was (everything asleep), so
  /// other_contacts was not refreshed and every record continues.
  bool contacts_unchanged = false;
  /// Box pairs whose bounds overlapped but whose shapes an axis kept apart,
  /// sorted by key (a << 32 | b), with that axis: the narrowphase tries it
  /// first next step, and a pair it still separates is skipped (it would
  /// have no points either way, so what is here never changes a result).
  std::vector<uint64_t> separated_keys;
  std::vector<uint8_t> separated_axes;
  std::vector<uint64_t> next_separated_keys;
  std::vector<uint8_t> next_separated_axes;
  std::vector<ContactGeometry> geometry;
  /// The steady cache (contact_cache_steady.cpp): while no body wakes and
  /// the world is not edited, the records the last step did not carry (it
  /// evaluated them: every record with an awake body) are the only ones
  /// this step can change, so it collides against those alone and, when
  /// its records come out with the same keys, writes them back where they
  /// were: a few awake bodies in a level of sleeping ones cost what they
  /// touch, not the whole cache.
  /// steady_serial: edit_serial when the last narrowphase left the cache
  /// (0: unusable); steady_active: that step's awake bodies; steady_records:
  /// the positions of the records it evaluated, ascending.
  uint64_t steady_serial = 0;
  std::vector<uint32_t> steady_active;
  std::vector<uint32_t> steady_records;
  /// This step wrote its records in place (other_contacts then holds only
  /// last step's versions of them, at positions steady_view, ascending).
  bool contacts_in_place = false;
  std::vector<uint32_t> steady_view;
  std::vector<ContactRecord> steady_new;  ///< this step's records of those pairs
  std::vector<ContactGeometry> steady_geometry;
  std::vector<uint32_t> steady_placed;  ///< where a merge put each of steady_new
  /// The touching records of the cache after the last step's events.
  uint32_t last_touching = 0;
  /// The step's pairs to collide, and their results (PairJob::slot).
  std::vector<d3::PairJob> pair_jobs;
  std::vector<ContactRecord> job_records;
  std::vector<ContactGeometry> job_geometry;
  /// The narrowphase's output in pair order: each entry is a record kept
  /// from other_contacts (kKeepOld), a pair a cached axis still separates
  /// (kStillSeparated, its index in separated_keys) or a pair job.
  std::vector<uint32_t> pair_plan;
  // solver
  std::vector<uint32_t> solver_index;  ///< by body index; 0 = immovable
  std::vector<uint32_t> solver_body_ids;
  std::vector<SolverBody> solver_bodies;
  std::vector<ContactConstraint> constraints;
  // joints (joint_solver.cpp)
  std::vector<d3::JointConstraint> joint_constraints;
  std::vector<JointId> broken_joints;  ///< this step's, in slot order
  // point joints in lanes (joint_point_batches.cpp), rebuilt each tick
  std::vector<d3::PointBatch> point_batches;
  std::vector<d3::BallPartBatch> ball_parts;    ///< their angular parts, by kind
  std::vector<d3::HingePartBatch> hinge_parts;  ///< (joint_angular_batches.h)
  std::vector<uint32_t> ball_batches;           ///< the point batches of each angular
  std::vector<uint32_t> hinge_batches;          ///< kind, in order
  std::vector<uint64_t> point_color_bits;       ///< per colour, one bit per solver body
  std::vector<uint32_t> point_color_of;         ///< by joint constraint
  std::vector<uint32_t>
      point_color_start;  ///< batched joints by colour: order[start[c], start[c+1])
  std::vector<uint32_t> point_color_order;
  std::vector<uint32_t> point_color_fill;
  /// The joint constraints not in a lane batch, ascending: the joint
  /// passes walk these and leave the batched ones to the lanes.
  std::vector<uint32_t> joint_general;
  /// The point joints with an angular part (JointConstraint::angular)
  /// not in a lane batch, ascending.
  std::vector<uint32_t> joint_angular;
  d3::JointSoftness point_soft;
  float point_h = 0.0f;  ///< the batched joints' substep
  // joint trees (joint_tree.cpp), rebuilt each tick
  std::vector<d3::JointTree> trees;
  std::vector<d3::JointTreeBody> tree_bodies;
  std::vector<uint32_t> tree_children;  ///< child joints of each tree body
  std::vector<uint32_t> tree_joints;    ///< joints of each tree
  std::vector<float> tree_arena;        ///< updates, then factors and couplings
  uint32_t tree_factor_base = 0;        ///< where the factors start in tree_arena
  std::vector<float> tree_rhs;          ///< by tree row
  std::vector<float> tree_w;
  std::vector<float> tree_lambda;
  std::vector<float> tree_acc;
  std::vector<float> tree_extra_c;  ///< extra rows' couplings to a tree, 3 x rows
  /// The extra groups prepared against the trees' current factors
  /// (joint_tree_extras.cpp), found by joint and slot through
  /// tree_extra_slot; emptied whenever the trees are factored.
  std::vector<d3::TreeExtraGroup> tree_extra_groups;
  std::vector<uint32_t> tree_extra_slot;  ///< by joint * kKeptRows + slot
  /// Their rows' couplings through the factors, per group row over its
  /// tree's rows; tree_extra_used of it in use (it only grows).
  std::vector<float> tree_extra_y;
  size_t tree_extra_used = 0;
  std::vector<float> tree_delta;      ///< a pass's impulses or displacements, by row
  std::vector<float> tree_release;    ///< released limits' K^-1 columns, 8 x rows
  std::vector<uint32_t> tree_parent;  ///< union-find over solver bodies
  std::vector<uint8_t> tree_loop;
  std::vector<uint32_t> tree_count;
  std::vector<float> tree_mass_ratio;
  std::vector<uint8_t> tree_seen;
  std::vector<uint32_t> tree_incidence_start;
  std::vector<uint32_t> tree_incidence;
  std::vector<uint32_t> tree_fill;
  /// Pairs (a << 32 | b, a < b) an intact joint keeps from colliding,
  /// sorted; rebuilt when joint_serial moves past joint_pairs_serial.
  std::vector<uint64_t> joint_pairs;
  uint64_t joint_serial = 1;
  uint64_t joint_pairs_serial = 0;
  // coloured batches (contact_batches.cpp)
  std::vector<uint64_t> color_bits;  ///< per colour, one bit per solver body
  std::vector<uint32_t> color_of;    ///< by constraint
  std::vector<uint32_t> color_start;
  std::vector<uint32_t> color_fill;
  std::vector<uint32_t> colored;  ///< constraint indices by colour
  std::vector<d3::ContactBatch> batches;
  std::vector<uint32_t> batch_start;  ///< first batch of each colour (and of the rest)
  // push-out order (support_order.cpp)
  std::vector<uint32_t> support_level;  ///< by solver body
  std::vector<uint32_t> adjacency_start;
  std::vector<uint32_t> adjacency_fill;
  std::vector<uint32_t> adjacency;
  std::vector<uint32_t> support_queue;
  std::vector<uint32_t> push_key;
  std::vector<uint32_t> push_bucket;
  std::vector<uint32_t> push_order;  ///< constraint indices, lowest support first
  /// Some contact point overlaps past the slop, as of the last separation
  /// update; while none does and nothing has been pushed this tick, the
  /// push-out has nothing to do and is skipped.
  bool overlapping = false;
  /// Some contact point overlaps more than kDeepOverlapSlops slops past the
  /// slop (same source): only then does the push-out from the ground up
  /// have work, and only then is its order computed.
  bool deep_overlap = false;
  bool pushing = false;  ///< the push-out has run this tick
  /// The bodies stand where the joints' rows were last refreshed (from
  /// the refresh at a substep's start to its move): the joints' kept
  /// frames, limits and one-row groups hold (JointConstraint::frames).
  bool joint_frames_fresh = false;
  // islands
  std::vector<uint32_t> island_parent;
  std::vector<float> island_sleep_time;
  std::vector<uint8_t> island_flag;
  // output
  bool stage_timing = false;  ///< World3D::set_stage_timing
  std::vector<ContactEvent> events;
  std::vector<uint32_t> event_records;   ///< per event: its record, or kNoRecord (exits)
  std::vector<uint32_t> pushed_records;  ///< records that touch by the solve's push this tick
  /// Records update_contacts evaluated this step (from this step's pairs,
  /// so every record with an awake body), ascending; the resting ones it
  /// carried are not listed.
  std::vector<uint32_t> evaluated_records;
  /// Records wake_touched_islands refreshed this step (carried resting
  /// records whose bodies it woke), ascending. With evaluated_records,
  /// every record with geometry this step (ContactGeometry::valid).
  std::vector<uint32_t> refreshed_records;
  std::vector<float> record_impulse;  ///< per record: the tick's normal impulse, or -1
  std::vector<BodyEvent> body_events;
  // scheduled queries (scheduled_queries.cpp): by pending query, this
  // step's answer; the hits of all of them in the order they ran, each
  // result's share given by its first and count until the spans are set.
  std::vector<ScheduledQueryResult> query_results;
  std::vector<uint32_t> query_first;
  std::vector<uint32_t> query_count;
  std::vector<RayHit> query_ray_hits;
  std::vector<BodyId> query_bodies;
  std::vector<RayHit> query_ray_scratch;   ///< one raycast_all's hits
  std::vector<BodyId> query_body_scratch;  ///< one overlap's bodies
  StepStats stats;
  /// The stats of the step that found the world at rest, which every
  /// skipped step of the resting world reports again (times zero).
  StepStats rest_stats;
};

}  // namespace rwd::sim
