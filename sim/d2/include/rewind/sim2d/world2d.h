// SPDX-License-Identifier: MIT
#pragma once
// The 2D lane: a rigid-body world in fixed point. Public values are Q16.16
// (Fx); the step works in Q32.32 integers and never touches floating
// point, so the same calls give the same bits on every compiler and
// machine. The world is a value: all of it lives in World2DState (flat
// arrays), so save/restore are bulk copies and restore-then-step equals
// continuing-to-step bit for bit.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/fixed/rot2.h"
#include "rewind/sim2d/body2d.h"
#include "rewind/sim2d/contact_event2d.h"
#include "rewind/sim2d/joint2d.h"
#include "rewind/sim2d/query2d.h"
#include "rewind/sim2d/shape2d.h"
#include "rewind/sim2d/world2d_config.h"
#include "rewind/sim2d/world2d_state.h"

namespace rwd {
// Declared only: the step's files never include the hasher or the dump
// (they name floating-point types for float lanes), which keeps the 2D
// step checkable for floating point (tests sim2d_no_float_*).
class StateHasher;
struct BodyField;
class ThreadPool;  // rewind/core/thread_pool.h
}  // namespace rwd

namespace rwd::sim2d {

/// Diagnostics of the last step: not state, not in the checksum.
struct StepStats2D {
  uint32_t broadphase_pairs = 0;   ///< pairs whose bounds overlap
  uint32_t touching_contacts = 0;  ///< pairs with at least one manifold point
  uint32_t contact_points = 0;     ///< manifold points the solver worked on
  uint32_t solver_iterations = 0;  ///< substeps x (1 solve + relax passes)
};

namespace detail {
class StepScratch2D;  // per-step working memory; not state
}

class World2D {
 public:
  /// An empty world with `config` exactly as given, or kInvalidArgument
  /// naming the first field validate_config() refuses (nothing is
  /// repaired). What a game or tool should call.
  static Result<std::unique_ptr<World2D>> create(const World2DConfig& config);
  /// An empty world; an invalid config is replaced by the defaults, where
  /// create() refuses it.
  explicit World2D(const World2DConfig& config = {});
  ~World2D();
  World2D(World2D&&) noexcept;
  World2D& operator=(World2D&&) noexcept;
  World2D(const World2D&) = delete;
  World2D& operator=(const World2D&) = delete;

  /// Every field of `config` in range, or kInvalidArgument naming the first
  /// that is not.
  static Status validate_config(const World2DConfig& config);
  /// Portable bytes of a config (little-endian, field by field).
  static void encode_config(const World2DConfig& config, std::vector<uint8_t>& out);
  /// encode_config()'s bytes back; kCorrupt for malformed or invalid ones.
  static Result<World2DConfig> decode_config(std::span<const uint8_t> bytes);
  /// (name, value) pairs in encode_config()'s order, values exact decimals
  /// with units ("gravity", "(0, -10) m/s^2").
  static std::vector<std::pair<std::string, std::string>> describe_config(
      const World2DConfig& config);

  // --- bodies -------------------------------------------------------------

  /// Creates a body; kInvalidArgument (naming the field) or kCapacity leave
  /// the world unchanged. Segments may only be static or kinematic.
  Result<BodyId2D> create_body(const BodyDef2D& def);
  /// Destroys a body and its contacts; kNotFound for unknown or stale ids.
  Status destroy_body(BodyId2D id);
  /// Destroys every listed body, with their contacts and joints, in one
  /// pass over the world's contacts and joints (destroy_body makes one per
  /// body): the same state, bit for bit, as destroy_body on each in list
  /// order. kNotFound for an unknown or stale id and kInvalidArgument for
  /// one listed twice, naming the entry, and then nothing is destroyed.
  Status destroy_bodies(std::span<const BodyId2D> ids);
  bool is_valid(BodyId2D id) const;
  uint32_t body_count() const;
  /// Live body ids in ascending index order; `out` is replaced.
  void body_ids(std::vector<BodyId2D>& out) const;

  // Accessors give zero values for invalid ids. The position is the body
  // origin's; a dynamic body turns about its centre of mass, a kinematic
  // one about its origin.
  BodyKind2D kind(BodyId2D id) const;
  Vec2 position(BodyId2D id) const;
  /// rad in [-pi, pi]
  Fx angle(BodyId2D id) const;
  fixed::Rot2 rotation(BodyId2D id) const;
  Vec2 center_of_mass(BodyId2D id) const;
  Vec2 linear_velocity(BodyId2D id) const;
  Fx angular_velocity(BodyId2D id) const;
  /// kg, Q32.32 (up to kMaxBodyMass2D; to_fx() saturates at 32,768 kg):
  /// the inverse of the inverse mass the solver uses, so area x density
  /// to a fraction below mass / 2^32 kg (body2d.h). 0 for static and
  /// kinematic bodies.
  fixed::FxWide mass(BodyId2D id) const;
  /// kg m^2 about the centre of mass, Q32.32 (up to kMaxBodyInertia2D),
  /// likewise the inverse of what the solver uses. 0 for static and
  /// kinematic bodies and for a locked rotation.
  fixed::FxWide rotational_inertia(BodyId2D id) const;
  Fx z(BodyId2D id) const;
  uint64_t user_data(BodyId2D id) const;
  const Shape2D* shape(BodyId2D id) const;
  bool is_enabled(BodyId2D id) const;
  /// A dynamic body that is simulated this step (false while it sleeps,
  /// and for static and kinematic bodies).
  bool is_awake(BodyId2D id) const;

  // Setters check the id (kNotFound) and the values (kInvalidArgument) and
  // change nothing on error. Velocity, force and impulse setters act on
  // dynamic bodies; velocities also on kinematic ones.
  /// Teleports the body origin; the centre of mass must stay in bounds.
  Status set_transform(BodyId2D id, Vec2 position, Fx angle);
  Status set_linear_velocity(BodyId2D id, Vec2 velocity);
  Status set_angular_velocity(BodyId2D id, Fx velocity);
  /// N s at a world point (m).
  Status apply_linear_impulse(BodyId2D id, Vec2 impulse, Vec2 world_point);
  /// N m s.
  Status apply_angular_impulse(BodyId2D id, Fx impulse);
  /// N at the centre of mass, for the next step only.
  Status apply_force(BodyId2D id, Vec2 force);
  /// N at a world point, for the next step only (force and its torque).
  Status apply_force_at(BodyId2D id, Vec2 force, Vec2 world_point);
  /// N m, for the next step only.
  Status apply_torque(BodyId2D id, Fx torque);
  /// Turns continuous collision on or off (BodyDef2D::continuous); acts on
  /// dynamic bodies.
  Status set_continuous(BodyId2D id, bool continuous);
  bool is_continuous(BodyId2D id) const;
  /// Wakes a sleeping dynamic body (no-op otherwise). Every setter above
  /// and every touch by a moving body wakes a body too.
  Status wake_body(BodyId2D id);
  Status set_user_data(BodyId2D id, uint64_t user_data);
  Status set_z(BodyId2D id, Fx z);
  /// Takes a body out of the simulation (false) or puts it back (true); a
  /// disabled body keeps its pose, has no velocity and no contacts.
  Status set_enabled(BodyId2D id, bool enabled);

  // --- joints -------------------------------------------------------------

  /// Creates a joint between two live bodies; kInvalidArgument naming the
  /// field, kNotFound for a stale body or kCapacity (max_bodies joints)
  /// leave the world unchanged. A joint between two static or kinematic
  /// bodies is accepted and kept (saved, hashed, queried, destroyed like
  /// any) but moves nothing: its impulses and joint_force() stay zero and
  /// it never breaks; kinematic bodies keep the velocities you give them.
  Result<JointId2D> create_joint(const JointDef2D& def);
  /// Destroys a joint; destroying a body destroys its joints too.
  Status destroy_joint(JointId2D id);
  bool is_valid(JointId2D id) const;
  uint32_t joint_count() const;
  /// True once the joint exceeded its break_impulse; it then stays in place,
  /// acting on nothing, until destroyed.
  bool is_joint_broken(JointId2D id) const;
  /// The force (N) the joint's linear part applied to body_b in the last
  /// substep of the last step; zero for invalid ids.
  Vec2 joint_force(JointId2D id) const;
  /// Revolute and wheel: rad/s; prismatic: m/s. Wakes both bodies.
  Status set_motor_speed(JointId2D id, Fx speed);
  /// Grab joints: the world point body_b is pulled toward; wakes body_b.
  Status set_grab_target(JointId2D id, Vec2 target);

  // --- stepping -----------------------------------------------------------

  /// Advances the world by 1 / config().tick_hz seconds.
  void step();
  /// Contact events of the last step, ordered by (a.index, b.index). Not
  /// state: restore() clears them.
  std::span<const ContactEvent2D> events() const;
  const StepStats2D& stats() const;
  /// Lets step() collide its pairs on `pool`'s threads; null (the
  /// default) steps on the calling thread alone. The result is the same
  /// bit for bit for any pool and none (each pair's manifold is its own;
  /// the solver's sweep stays in one order on the stepping thread). Not
  /// state. The pool must outlive the world or be replaced first.
  void set_thread_pool(rwd::ThreadPool* pool);
  const World2DConfig& config() const;
  uint64_t step_count() const;

  // --- the world as a value -----------------------------------------------

  const World2DState& state() const;
  /// Copies the state into `out` (reusing its buffers: no allocation once
  /// they have grown to the world's size).
  void save(World2DState& out) const;
  /// Copies `in` (a state save() made) back.
  void restore(const World2DState& in);
  /// Feeds the canonical fields of the state to `hasher`.
  void hash(rwd::StateHasher& hasher) const;
  static void hash_state(const World2DState& state, rwd::StateHasher& hasher);
  /// XXH3-64 of hash(): the per-tick checksum.
  uint64_t checksum() const;
  /// Every live body's fields (the schema's names) in index order.
  void dump_fields(std::vector<rwd::BodyField>& out) const;
  /// Portable bytes of the whole state (resync snapshots).
  void serialize(std::vector<uint8_t>& out) const;
  /// serialize()'s bytes back; kCorrupt (naming what is wrong) leaves the
  /// world unchanged.
  Status deserialize(std::span<const uint8_t> bytes);
  /// Desync-drill hook: moves the highest-index dynamic body 1/1024 m
  /// along +x. False, changing nothing, when there is none.
  bool perturb_for_drill();

  // --- queries (query2d.h) ------------------------------------------------
  // Read-only: no query changes the state or the checksum, and every result
  // depends on the state alone (ties go to the lower body index). Cost: the
  // first query after a step or an edit builds a bounding-box tree over the
  // enabled bodies (O(n log n), into reused buffers); each query then visits
  // the tree nodes its bounds overlap (about O(log n + candidates)) and runs
  // the exact test on the candidates. A query allocates nothing once `out`
  // and the tree have grown to size. The tree is shared by the queries, so
  // one world must not be queried from two threads at once.

  /// The first body the ray origin..origin + translation enters. A ray
  /// starting inside a shape does not hit it; a zero translation hits
  /// nothing. Segments are hit from either side.
  std::optional<RayHit2D> raycast(Vec2 origin, Vec2 translation,
                                  const QueryFilter2D& filter = {}) const;
  /// Every body the ray enters, near to far (equal fractions by index);
  /// `out` is cleared first.
  void raycast_all(Vec2 origin, Vec2 translation, const QueryFilter2D& filter,
                   std::vector<RayHit2D>& out) const;
  /// Bodies whose shape bounds overlap the box lower..upper (touching
  /// counts), in index order; `out` is cleared first.
  void query_aabb(Vec2 lower, Vec2 upper, const QueryFilter2D& filter,
                  std::vector<BodyId2D>& out) const;
  /// Bodies whose shape overlaps `shape` placed with its origin at
  /// `position`, turned by `angle` rad (exact test; touching does not
  /// count), in index order; `out` is cleared first.
  void overlap(const Shape2D& shape, Vec2 position, Fx angle, const QueryFilter2D& filter,
               std::vector<BodyId2D>& out) const;
  /// The first body `shape` (placed as in overlap()) touches when moved by
  /// `translation` without turning. Found by conservative advancement on
  /// the exact distance, so the shape stops at most 2^-20 m short of
  /// contact, never inside; a body it already overlaps is reported at
  /// fraction 0 only when the move goes further in.
  std::optional<ShapeHit2D> shape_cast(const Shape2D& shape, Vec2 position, Fx angle,
                                       Vec2 translation, const QueryFilter2D& filter = {}) const;
  /// The body whose surface is nearest `point`, if one is within
  /// `max_distance` m (inclusive; 0 when the point is inside it).
  std::optional<NearestBody2D> nearest_body(Vec2 point, Fx max_distance,
                                            const QueryFilter2D& filter = {}) const;
  /// Signed distance (m) from `point` to the body's surface, negative
  /// inside; Fx::max() for an invalid id.
  Fx signed_distance(BodyId2D body, Vec2 point) const;
  /// The smallest signed distance from `point` to any body the filter
  /// passes (negative inside the deepest one); Fx::max() when none.
  Fx signed_distance(Vec2 point, const QueryFilter2D& filter = {}) const;
  /// The lane's own query code reaches the tree through this; the class is
  /// defined only inside the lane's sources (query_cache2d.h).
  class QueryCache;
  const QueryCache& query_cache() const;

 private:
  // The queries' bounds tree: not state, never saved or hashed. Every call
  // that adds, removes, moves, enables or disables a body, or replaces the
  // state, bumps body_edits_; the tree remembers the edit count and step
  // count it was built at and is rebuilt when either moved on.
  uint64_t body_edits_ = 0;
  mutable std::shared_ptr<QueryCache> query_cache_;

  World2DState state_;
  StepStats2D stats_;
  std::unique_ptr<detail::StepScratch2D> scratch_;
};

}  // namespace rwd::sim2d
