// SPDX-License-Identifier: MIT
#pragma once
// The 3D lane: IEEE float32 rigid bodies, TGS-Soft solver. The world is a
// value: all persistent state lives in WorldState (flat arrays of trivially
// copyable records, no pointers), so save/restore are bulk copies and
// restore-then-step equals continuing-to-step bit for bit.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rewind/core/state_hasher.h"
#include "rewind/core/status.h"
#include "rewind/core/thread_pool.h"
#include "rewind/sim/body.h"
#include "rewind/sim/body_event.h"
#include "rewind/sim/body_record.h"
#include "rewind/sim/contact_event.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/joint.h"
#include "rewind/sim/query.h"
#include "rewind/sim/scheduled_query.h"
#include "rewind/sim/world_config.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim {

/// Diagnostics of the last step (not state, not checksummed).
struct StepStats {
  uint32_t awake_bodies = 0;
  uint32_t broadphase_pairs = 0;
  uint32_t touching_manifolds = 0;
  uint32_t contact_points = 0;
  /// Manifolds carried forward from their last computation because their
  /// bodies barely moved relative to each other (no shape collision run).
  uint32_t reused_manifolds = 0;
  /// Wall time of each stage, microseconds; all zero unless
  /// World3D::set_stage_timing(true) (the clock is read only then).
  struct StageTimes {
    double broadphase_us = 0.0;   ///< candidate pairs
    double narrowphase_us = 0.0;  ///< manifolds, the contact cache
    double events_us = 0.0;       ///< waking touched islands, contact events
    double solver_us = 0.0;       ///< constraints, substeps, write back
    double sleep_us = 0.0;        ///< islands falling asleep
  } times;
};

class WorldScratch;  // per-step working memory; not state

class World3D {
 public:
  /// An empty world with `config` exactly as given, or kInvalidArgument
  /// naming the first field validate_config() refuses (nothing is
  /// repaired). The world reads hulls and other registered geometry from
  /// `geometry` (a new, empty store when null); worlds that share a store
  /// share its ids. What a game or tool should call.
  static Result<std::unique_ptr<World3D>> create(const WorldConfig& config,
                                                 std::shared_ptr<GeometryStore> geometry = nullptr);
  /// Creates an empty world, replacing each invalid field of `config` with
  /// its default; create() refuses such a config instead.
  explicit World3D(const WorldConfig& config = {},
                   std::shared_ptr<GeometryStore> geometry = nullptr);
  ~World3D();
  World3D(const World3D&) = delete;
  World3D& operator=(const World3D&) = delete;
  World3D(World3D&&) noexcept;
  World3D& operator=(World3D&&) noexcept;

  /// Checks every field of a config for range and finiteness.
  static Status validate_config(const WorldConfig& config);
  /// Portable encoding of a config (little-endian, field by field): the
  /// bytes every snapshot embeds, and what a replay records so a verifier
  /// can tell whether it runs the world the match ran.
  static void encode_config(const WorldConfig& config, std::vector<uint8_t>& out);
  /// Reads encode_config()'s bytes; kCorrupt for malformed bytes or a config
  /// validate_config() refuses.
  static Result<WorldConfig> decode_config(std::span<const uint8_t> bytes);
  /// `config` as readable (name, value) pairs in encode_config()'s order,
  /// names as in WorldConfig, values as the shortest text that reads back
  /// to the same float, with units where they help ("gravity",
  /// "(0, -9.81, 0) m/s^2"). For replay tools and reports.
  static std::vector<std::pair<std::string, std::string>> describe_config(
      const WorldConfig& config);

  // --- geometry -----------------------------------------------------------

  /// The store this world's hull shapes refer to: register geometry here
  /// (GeometryStore::add_hull) before making bodies of it.
  GeometryStore& geometry();
  const GeometryStore& geometry() const;
  std::shared_ptr<GeometryStore> shared_geometry() const;

  // --- bodies -------------------------------------------------------------

  /// Creates a body. Rejects non-finite or out-of-range values and full
  /// worlds with a Status; the world is unchanged on error.
  Result<BodyId> create_body(const BodyDef& def);
  /// Destroys a body, its contacts (exit events are emitted on the next
  /// step) and its joints. Unknown or stale ids are kNotFound.
  Status destroy_body(BodyId id);
  /// The same, reporting the ids of the joints that went with the body
  /// into `removed_joints` (cleared first), in slot order.
  Status destroy_body(BodyId id, std::vector<JointId>& removed_joints);
  bool is_valid(BodyId id) const;
  /// Number of live bodies.
  uint32_t body_count() const;
  /// Live body ids in ascending index order.
  void body_ids(std::vector<BodyId>& out) const;

  // Accessors return zero values for invalid ids.
  //
  // A body's position and rotation are those of the frame its shape was
  // authored in (for a hull, the frame of its points); it turns about its
  // centre of mass, and its linear velocity is that of the centre of mass.
  // For spheres, boxes and capsules the two points are the same.
  BodyKind kind(BodyId id) const;
  Vec3 position(BodyId id) const;
  Quat rotation(BodyId id) const;
  /// The centre of mass in the world, m.
  Vec3 center_of_mass(BodyId id) const;
  Vec3 linear_velocity(BodyId id) const;
  Vec3 angular_velocity(BodyId id) const;
  float mass(BodyId id) const;  ///< kg; 0 for static and kinematic
  uint64_t user_data(BodyId id) const;
  bool is_awake(BodyId id) const;
  const Shape* shape(BodyId id) const;

  /// False for disabled bodies (see set_enabled) and invalid ids.
  bool is_enabled(BodyId id) const;

  // Setters validate (finite values, live id), quantize, and wake the body.
  // Velocity, impulse and force setters refuse disabled bodies.

  /// Teleports a body; the position must lie inside the world bounds. A
  /// disabled body stays disabled (move it, then enable it).
  Status set_transform(BodyId id, Vec3 position, Quat rotation);
  /// Test hook for desync drills: moves the highest-index dynamic body 1 mm
  /// along +x (small enough to look like a real float divergence, big
  /// enough to matter), like set_transform(). The same state is perturbed
  /// the same way. Returns false, changing nothing, when there is no
  /// dynamic body or set_transform() refuses the move (the world bounds).
  bool perturb_for_drill();
  Status set_linear_velocity(BodyId id, Vec3 velocity_mps);
  Status set_angular_velocity(BodyId id, Vec3 velocity_radps);
  /// Applies an impulse (N*s) at a world point to a dynamic body.
  Status apply_linear_impulse(BodyId id, Vec3 impulse, Vec3 world_point);
  /// Adds a force (N) at the centre of mass for the next step only.
  Status apply_force(BodyId id, Vec3 force_n);
  /// Adds a force (N) at a world point for the next step only: the force,
  /// and its torque about the centre of mass.
  Status apply_force_at(BodyId id, Vec3 force_n, Vec3 world_point);
  /// Adds a torque (N m, world frame) for the next step only. A body turns
  /// only about the axes it is not locked on.
  Status apply_torque(BodyId id, Vec3 torque_nm);
  /// Sets the world axes the body never turns about (kLockRotation* bits,
  /// body.h); its angular velocity about them becomes zero. Works on any
  /// live body, disabled ones included (they stay disabled).
  Status set_rotation_lock(BodyId id, uint8_t locks);
  Status set_user_data(BodyId id, uint64_t user_data);
  /// Turns continuous collision on or off for a body (BodyDef::continuous);
  /// it acts on dynamic bodies.
  Status set_continuous(BodyId id, bool continuous);
  bool is_continuous(BodyId id) const;
  /// Which of the body's events are reported in events() (kEvent* bits,
  /// event_mask.h; BodyDef::event_mask); takes effect on the next step. Bits
  /// outside kEventAll are kInvalidArgument.
  Status set_event_mask(BodyId id, EventMask mask);
  /// The body's event mask (kEventNone for an invalid id).
  EventMask event_mask(BodyId id) const;
  /// The boolean form of set_event_mask(): true asks for every event
  /// (kEventAll), false for none (kEventNone).
  Status set_contact_events(BodyId id, bool report);
  /// Takes a body out of the simulation (false) or puts it back (true). A
  /// disabled body keeps its pose, has no velocity, no contacts (they end
  /// with exit events on the next step), is not found by queries and is
  /// never woken. The step disables bodies that leave the world bounds
  /// (BodyEventType::kLeftBounds); enabling wakes the body where it stands.
  Status set_enabled(BodyId id, bool enabled);

  // --- joints -------------------------------------------------------------

  /// Creates a joint (joint.h). A definition that names a missing body,
  /// the same body twice, non-finite or zero-length axes, anchors out of
  /// range, a minimum above a maximum or limits out of range is refused
  /// with a message naming the field (kInvalidArgument; kNotFound for
  /// unknown bodies), and so is a full world (kCapacity: max_bodies
  /// joints); the world is unchanged then. Wakes both bodies.
  Result<JointId> create_joint(const JointDef& def);
  /// Destroys a joint and wakes its bodies. Unknown ids are kNotFound.
  Status destroy_joint(JointId id);
  bool is_valid(JointId id) const;
  /// Number of live joints (broken ones included).
  uint32_t joint_count() const;
  /// Live joint ids in ascending slot order.
  void joint_ids(std::vector<JointId>& out) const;
  /// The joint's type, or kBall for an invalid id.
  JointType joint_type(JointId id) const;
  /// The joint's bodies (body_a null for a joint held to the world).
  BodyId joint_body_a(JointId id) const;
  BodyId joint_body_b(JointId id) const;
  /// True once the joint exceeded its break_impulse (sticky).
  bool is_joint_broken(JointId id) const;
  /// What the joint did in the last substep, as force and torque on body_b
  /// (zero for invalid or broken joints).
  JointReaction joint_reaction(JointId id) const;
  /// The joint's coordinate as its limits read it: a hinge's angle and a
  /// ball's twist (rad, relative to creation), a prismatic's translation
  /// (m), a distance or spring joint's length (m), a grab's distance to
  /// its target (m); 0 for a weld or an invalid id.
  float joint_position(JointId id) const;
  /// A ball joint's swing of axis_b away from axis_a, rad in [0, pi].
  float joint_swing(JointId id) const;
  /// Hinge and prismatic motors: on or off, target speed (rad/s or m/s,
  /// |speed| <= 1e4) and largest torque or force (N m or N, >= 0).
  Status set_joint_motor(JointId id, bool enabled, float speed, float max_torque_or_force);
  /// Ball motors: target angular velocity of B relative to A (rad/s,
  /// world axes) and the largest torque (N m, >= 0).
  Status set_joint_motor_velocity(JointId id, bool enabled, Vec3 velocity_radps,
                                  float max_torque_nm);
  /// Hinge and prismatic springs: the target angle (rad) or translation (m).
  Status set_joint_spring_target(JointId id, float target);
  /// Ball orientation springs: the target orientation of B's authored
  /// frame in A's (q_A^-1 q_B; normalized).
  Status set_joint_spring_rotation(JointId id, Quat target);
  /// Grab joints: the world point body_b's anchor is pulled toward (inside
  /// the world bounds). Wakes body_b.
  Status set_grab_target(JointId id, Vec3 target);
  /// Joints that broke in the last step, in slot order. Not state:
  /// restore() clears them.
  std::span<const JointId> broken_joints() const;

  // --- stepping -----------------------------------------------------------

  /// Advances the world by config().tick_seconds.
  void step();
  /// Contact events of the last step, ordered by (a.index, b.index), each
  /// reported when either body's event mask asks for its type (solid or
  /// sensor; enter, stay or exit; BodyDef::event_mask). The exit of a pair
  /// whose body was destroyed is reported whatever the other's mask.
  std::span<const ContactEvent> events() const;
  /// The answers of the scheduled queries that ran in the last step, in
  /// scheduling order (ascending tickets, whatever their phase). Not state:
  /// restore() clears them.
  std::span<const ScheduledQueryResult> step_queries() const;
  /// Body events of the last step (bodies that left the world bounds),
  /// ordered by body index. Not state: restore() clears them.
  std::span<const BodyEvent> body_events() const;
  const StepStats& stats() const;
  /// Measures each stage's wall time into stats().times (off by default:
  /// a world that does not ask never reads the clock). Not state.
  void set_stage_timing(bool on);
  /// Lets step() cut its independent work (the narrowphase's pairs, the
  /// bodies' integration, each colour of contact batches) across `pool`'s
  /// threads; null (the default) steps on the calling thread alone. The
  /// result is the same bit for bit for any pool and none: the threads
  /// change how long a step takes, never what it computes. Small worlds
  /// gain nothing (each piece of work must be worth a trip to the pool);
  /// worlds of hundreds of bodies do. Not state: a restored or moved world
  /// keeps its pool. The pool must outlive the world or be replaced first.
  void set_thread_pool(ThreadPool* pool);
  const WorldConfig& config() const;
  /// Number of steps taken since creation.
  uint64_t step_count() const;

  // --- queries ------------------------------------------------------------

  /// The closest hit along the ray, or nullopt. Ties go to the lower index.
  std::optional<RayHit> raycast(const Ray& ray, const QueryFilter& filter = {}) const;
  /// Every hit along the ray, sorted near to far (ties by index).
  void raycast_all(const Ray& ray, const QueryFilter& filter, std::vector<RayHit>& out) const;
  /// Every body whose shape overlaps or touches `shape` placed at
  /// `position` (m) and `rotation`, in index order, into `out` (cleared
  /// first; a reused vector keeps its capacity, so the query does not
  /// allocate once warm). kInvalidArgument, with `out` empty, for a shape
  /// the body rule refuses or a non-finite or zero pose.
  ///
  /// Queries walk trees over the bodies' bounds (rebuilt the first time a
  /// query needs them after a step or an edit) and test each candidate
  /// exactly; they change no state.
  Status overlap(const Shape& shape, Vec3 position, Quat rotation, const QueryFilter& filter,
                 std::vector<BodyId>& out) const;
  /// Sweeps `shape` (a sphere, box, capsule, hull or compound) from
  /// `position`, `rotation` (its authored frame, as a body of it would be
  /// placed) along `translation` (m) and reports the first body it
  /// touches, or nullopt in `out` when none is in the way; ties go to the
  /// lower index. A body the shape starts in touching or overlapping is
  /// hit at distance 0. kInvalidArgument, with `out` empty, for a mesh or
  /// height field, a shape the body rule refuses, or a non-finite or zero
  /// pose or translation. Candidates come from the broadphase (bounds the
  /// shape's bounds meet on the way); allocates nothing once warm.
  Status shape_cast(const Shape& shape, Vec3 position, Quat rotation, Vec3 translation,
                    const QueryFilter& filter, std::optional<ShapeCastHit>& out) const;
  /// Every body the sweep touches, nearest first (ties by index), each at
  /// its first touch, into `out` (cleared first; keeps its capacity).
  Status shape_cast_all(const Shape& shape, Vec3 position, Quat rotation, Vec3 translation,
                        const QueryFilter& filter, std::vector<ShapeCastHit>& out) const;
  /// The body whose surface is nearest `point` within `max_distance` m,
  /// by signed_distance(), or nullopt; ties go to the lower index. A solid
  /// the point is inside counts, at its negative depth; a mesh or a height
  /// field counts when its surface is within `max_distance` on either
  /// side, at its signed distance (so a point deep under a height field
  /// does not find it). A non-finite point or a negative or non-finite
  /// distance finds nothing.
  std::optional<PointHit> nearest_body(Vec3 point, float max_distance,
                                       const QueryFilter& filter = {}) const;
  /// Signed distance (m) from `point` to a body's surface, with the
  /// surface's point nearest it and the unit normal there, pointing the way
  /// the distance grows (outward); nullopt for an unknown id, a non-finite
  /// point or a height field that is all holes. The magnitude is always
  /// the distance to the nearest surface point; the sign says the side:
  /// - a solid (sphere, box, capsule, hull, compound): negative inside.
  /// - a triangle mesh, one- or two-sided: negative behind the surface,
  ///   the side its triangles' normals (counter-clockwise winding) point
  ///   away from; for a closed mesh wound that way, inside. Where the
  ///   nearest point is on an edge or a vertex the side is that of the
  ///   angle-weighted pseudo-normal there (the normals of the triangles
  ///   meeting at it, each weighted by its angle at that point), which
  ///   gets the inside of a closed mesh right at edges and corners too; a
  ///   lone triangle makes every point behind its plane negative.
  ///   Triangles meet where their corners have the same coordinates,
  ///   whether or not they share vertex indices.
  /// - a height field: negative under the surface, that is within its
  ///   footprint (the x, z extent of its samples), over a cell that is not
  ///   a hole, and below the surface's height there; then the magnitude is
  ///   the distance to the nearest surface point (not the height
  ///   difference, on a slope). Beside the footprint and under a hole the
  ///   distance is positive, whatever the height.
  /// A point on the surface reads about 0, of either sign. Meshes and
  /// height fields are searched outward from the point, so the cost grows
  /// with the distance to them (a cell or two of a field, a few tree nodes
  /// of a mesh, for a point near the surface).
  std::optional<PointHit> signed_distance(BodyId id, Vec3 point) const;
  /// The contact manifold of two live bodies as they stand: points whose
  /// separation is at most `max_separation` m (0: touching or overlapping;
  /// in [0, 1000]), or nullopt when there are none, an id is unknown or
  /// both are the same body.
  std::optional<ContactManifold> contact_manifold(BodyId a, BodyId b,
                                                  float max_separation = 0.0f) const;

  // --- scheduled queries --------------------------------------------------
  //
  // A scheduled query runs inside step(): kPrePhysics ones before the
  // step's stages (on the world as the step finds it), kPostPhysics ones
  // after them (as it leaves it), and their answers are in step_queries().
  // Schedules are state (snapshot, checksum, restore, serialize): a
  // kEveryStep query keeps running after a rollback, and a kOnce query
  // made before a save() runs after the matching restore(). The arguments
  // are validated (the world is unchanged on error) and put on the
  // canonical grid, as every outside value is. At most
  // kMaxScheduledQueries are pending at a time (kCapacity).

  static constexpr uint32_t kMaxScheduledQueries = 1u << 16;

  /// Schedules the closest-hit raycast(). kInvalidArgument for a
  /// non-finite origin or direction, a zero direction, or a negative or
  /// non-finite max_distance.
  Result<QueryTicket> schedule_raycast(const Ray& ray, const QueryFilter& filter, QueryPhase phase,
                                       uint64_t user_tag, QueryRepeat repeat = QueryRepeat::kOnce);
  /// Schedules raycast_all(): every hit, near to far.
  Result<QueryTicket> schedule_raycast_all(const Ray& ray, const QueryFilter& filter,
                                           QueryPhase phase, uint64_t user_tag,
                                           QueryRepeat repeat = QueryRepeat::kOnce);
  /// Schedules overlap() of `shape` at `position`, `rotation` (its
  /// authored frame). kInvalidArgument for a shape the body rule refuses
  /// or a non-finite or zero pose.
  Result<QueryTicket> schedule_overlap(const Shape& shape, Vec3 position, Quat rotation,
                                       const QueryFilter& filter, QueryPhase phase,
                                       uint64_t user_tag, QueryRepeat repeat = QueryRepeat::kOnce);
  /// Removes a pending query; kNotFound for a null, unknown or already
  /// finished ticket.
  Status cancel_query(QueryTicket ticket);
  /// Whether `ticket` names a pending query.
  bool is_scheduled(QueryTicket ticket) const;
  /// Number of pending queries.
  uint32_t scheduled_query_count() const;

  // --- state --------------------------------------------------------------

  /// Bulk copy of all persistent state. No allocation once `out` has grown.
  void save(WorldState& out) const;
  /// Bulk copy back. Subsequent steps equal those of the saved world bit for bit.
  void restore(const WorldState& in);
  const WorldState& state() const;
  /// Feeds the canonical serialization of chosen state fields to `hasher`.
  void hash(StateHasher& hasher) const;
  /// XXH3-64 over the canonical serialization.
  uint64_t checksum() const;
  /// Same as hash() but for a saved state, without restoring it.
  static void hash_state(const WorldState& state, StateHasher& hasher);
  /// Every persisted field of the state as text, one "name = value" line
  /// each in the canonical order (the same description the snapshot, the
  /// reader and the checksum use): config.*, step_count, body[i].* for every
  /// slot, contact[k].* for every cache record, joint[k].* for every joint
  /// slot, then last_query_ticket and query[k].* for every scheduled query.
  /// For forensics; `out` is cleared first.
  void dump_state(std::string& out) const;
  /// Readable dump of every live body in index order.
  void dump_bodies(std::vector<BodyRecord>& out) const;
  /// The same dump as lane-neutral fields (see append_body_fields());
  /// `out` is cleared first.
  void dump_fields(std::vector<BodyField>& out) const;

  /// Portable byte encoding of the full state (little-endian, field by field),
  /// for resync snapshots sent over the network.
  void serialize(std::vector<uint8_t>& out) const;
  /// Replaces the state from serialize()'s bytes. Malformed input (bad sizes,
  /// indices out of range) and any body the state rule refuses (the rule
  /// the step itself keeps: finite values, speeds, poses inside the world
  /// bounds) is kCorrupt, names the body and the reason, and leaves the
  /// world unchanged. Every state step() reaches is accepted.
  Status deserialize(std::span<const uint8_t> bytes);

 private:
  /// Frees every joint on body `id`, adding their ids to `removed`.
  void destroy_body_joints(BodyId id, std::vector<JointId>* removed);
  /// The step's stages, each timed into stats().times.
  void timed_stages();
  /// Adds a validated query to the schedule.
  Result<QueryTicket> add_scheduled_query(const ScheduledQueryRecord& record);
  /// Runs the scheduled queries of `phase` into the step's results.
  void run_scheduled_queries(QueryPhase phase);
  /// Points the step's results at their hits and drops the one-shot
  /// queries, once both phases ran.
  void finish_scheduled_queries();
  /// Forgets the last step's query results (restore, deserialize).
  void clear_step_queries();

  WorldState state_;
  std::shared_ptr<GeometryStore> geometry_;
  std::unique_ptr<WorldScratch> scratch_;
};

/// Snaps an outside value onto the canonical grid (multiples of 2^-20 for
/// values of magnitude < 2^11; otherwise unchanged) so every client starts
/// from the same bits whatever parser produced the value.
float quantize(float value);
Vec3 quantize(Vec3 value);

}  // namespace rwd::sim
