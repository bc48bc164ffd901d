// SPDX-License-Identifier: MIT
// World3D: the public surface. Validates every argument before touching
// state and keeps scratch apart from state (the step's stages:
// world3d_step.cpp).
#include "rewind/sim/world3d.h"

#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/mass_frame.h"
#include "d3/pipeline.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "d3/world_scratch.h"

namespace rwd::sim {

using d3::is_live;

namespace {

Status invalid(const char* what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}
Status not_found() {
  return Status::Error(ErrorCode::kNotFound, "unknown or stale body id");
}

// Values enter the canonical grid like every other outside value; then,
// field by field, a value the rule refuses (before or because of the
// quantization, e.g. a tick so short it rounds to zero) takes its default.
WorldConfig on_grid(const WorldConfig& c) {
  WorldConfig q = c;
  q.gravity = quantize(c.gravity);
  q.tick_seconds = quantize(c.tick_seconds);
  q.contact_hertz = quantize(c.contact_hertz);
  q.contact_damping_ratio = quantize(c.contact_damping_ratio);
  q.contact_push_max_mps = quantize(c.contact_push_max_mps);
  q.restitution_threshold_mps = quantize(c.restitution_threshold_mps);
  q.linear_slop_m = quantize(c.linear_slop_m);
  q.speculative_distance_m = quantize(c.speculative_distance_m);
  q.sleep_threshold_mps = quantize(c.sleep_threshold_mps);
  q.time_to_sleep_s = quantize(c.time_to_sleep_s);
  q.bounds_lower = quantize(c.bounds_lower);
  q.bounds_upper = quantize(c.bounds_upper);
  return q;
}

WorldConfig sanitize(const WorldConfig& c) {
  const WorldConfig q = on_grid(c);
  const WorldConfig d = on_grid(WorldConfig{});  // valid, and on the grid
  WorldConfig out = d;
  auto keep = [&](auto WorldConfig::*field) {
    WorldConfig probe = d;
    probe.*field = q.*field;
    if (d3::check_config(probe).ok()) out.*field = q.*field;
  };
  keep(&WorldConfig::gravity);
  // The tick and its substeps together decide the substep's length: both,
  // or each alone against the other's default.
  WorldConfig timing = d;
  timing.tick_seconds = q.tick_seconds;
  timing.substeps = q.substeps;
  if (d3::check_config(timing).ok()) {
    out.tick_seconds = q.tick_seconds;
    out.substeps = q.substeps;
  } else {
    keep(&WorldConfig::tick_seconds);  // with the default substeps
    timing = d;
    timing.tick_seconds = out.tick_seconds;
    timing.substeps = q.substeps;
    if (d3::check_config(timing).ok()) out.substeps = q.substeps;
  }
  keep(&WorldConfig::relax_iterations);
  keep(&WorldConfig::contact_hertz);
  keep(&WorldConfig::contact_damping_ratio);
  keep(&WorldConfig::contact_push_max_mps);
  keep(&WorldConfig::restitution_threshold_mps);
  keep(&WorldConfig::linear_slop_m);
  keep(&WorldConfig::speculative_distance_m);
  keep(&WorldConfig::enable_sleep);
  keep(&WorldConfig::sleep_threshold_mps);
  keep(&WorldConfig::time_to_sleep_s);
  keep(&WorldConfig::max_bodies);
  // The bounds are one value: both corners or neither.
  WorldConfig probe = d;
  probe.bounds_lower = q.bounds_lower;
  probe.bounds_upper = q.bounds_upper;
  if (d3::check_config(probe).ok()) {
    out.bounds_lower = q.bounds_lower;
    out.bounds_upper = q.bounds_upper;
  }
  return out;
}

Quat quantize(Quat q) {
  return {sim::quantize(q.x), sim::quantize(q.y), sim::quantize(q.z), sim::quantize(q.w)};
}

}  // namespace

Result<std::unique_ptr<World3D>> World3D::create(const WorldConfig& config,
                                                 std::shared_ptr<GeometryStore> geometry) {
  if (Status status = validate_config(config); !status.ok()) return status;
  return std::make_unique<World3D>(config, std::move(geometry));
}

World3D::World3D(const WorldConfig& config, std::shared_ptr<GeometryStore> geometry)
    : geometry_(geometry != nullptr ? std::move(geometry) : std::make_shared<GeometryStore>()),
      scratch_(std::make_unique<WorldScratch>()) {
  state_.config = sanitize(config);
  scratch_->store = geometry_.get();
}
World3D::~World3D() = default;
World3D::World3D(World3D&&) noexcept = default;
World3D& World3D::operator=(World3D&&) noexcept = default;

Status World3D::validate_config(const WorldConfig& c) {
  return d3::check_config(c);
}

// --- geometry ---------------------------------------------------------------

GeometryStore& World3D::geometry() {
  return *geometry_;
}
const GeometryStore& World3D::geometry() const {
  return *geometry_;
}
std::shared_ptr<GeometryStore> World3D::shared_geometry() const {
  return geometry_;
}

// --- bodies -----------------------------------------------------------------

Result<BodyId> World3D::create_body(const BodyDef& def) {
  const WorldConfig& config = state_.config;
  const GeometryStore& store = *geometry_;
  if (Status s = d3::check_body_def(config, store, def); !s.ok()) return s;
  if (state_.live_count >= config.max_bodies) {
    return Status::Error(ErrorCode::kCapacity, "world is full (max_bodies)");
  }
  // The body is built aside, quantized, and held to the same rule a
  // snapshot is; the world changes only once it passes.
  BodyInfo info;
  info.alive = 1;
  info.generation = 1;  // the real one is set below
  info.enabled = 1;
  info.kind = def.kind;
  info.sensor = def.sensor ? 1 : 0;
  info.awake = def.kind == BodyKind::kStatic ? 0 : 1;
  info.shape = def.shape;
  info.shape.radius = quantize(def.shape.radius);
  info.shape.half_extents = quantize(def.shape.half_extents);
  info.shape.half_height = quantize(def.shape.half_height);
  d3::shape_ops(def.shape.type).canonical(info.shape, store);
  info.material = {quantize(def.material.friction), quantize(def.material.restitution),
                   quantize(def.material.rolling_resistance)};
  info.layer = def.layer;
  info.mask = def.mask;
  info.user_data = def.user_data;
  info.density = quantize(def.density);
  info.linear_damping = quantize(def.linear_damping);
  info.angular_damping = quantize(def.angular_damping);
  info.gravity_scale = quantize(def.gravity_scale);
  info.lock_rotation = def.lock_rotation;
  info.continuous = def.continuous ? 1 : 0;
  info.event_mask = def.contact_events ? def.event_mask : kEventNone;
  BodySim sim;
  d3::authored_to_mass(d3::mass_frame(info.shape, store), quantize(def.position),
                       quantize(normalize(def.rotation)), sim.position, sim.rotation);
  if (def.kind != BodyKind::kStatic) {
    sim.linear_velocity = quantize(def.linear_velocity);
    sim.angular_velocity =
        d3::without_locked_axes(def.lock_rotation, quantize(def.angular_velocity));
  }
  // Quantizing can round a tiny size to zero or nudge a value over a limit.
  if (!d3::check_body(config, store, info, sim).ok()) {
    return invalid(
        "shape, density or pose leaves the valid range on the canonical grid (a hull's centre "
        "of mass must lie inside the world bounds too)");
  }
  const BodyMass mass = d3::compute_mass(info.kind, info.shape, store, info.density);
  if (Status s = d3::check_mass(info.kind, mass); !s.ok()) return s;

  uint32_t index = 0;
  if (!state_.free_slots.empty()) {
    index = state_.free_slots.back();
    state_.free_slots.pop_back();
  } else {
    index = static_cast<uint32_t>(state_.infos.size());
    state_.infos.emplace_back();
    state_.sims.emplace_back();
    state_.masses.emplace_back();
  }
  uint32_t generation = state_.infos[index].generation + 1;
  if (generation == 0) generation = 1;  // wrapped: 0 is the null handle
  info.generation = generation;
  state_.infos[index] = info;
  state_.sims[index] = sim;
  state_.masses[index] = mass;
  ++state_.live_count;
  d3::mark_world_edited(*scratch_);
  state_.at_rest = false;
  return BodyId{index, generation};
}

Status World3D::destroy_body(BodyId id) {
  if (!is_live(state_, id)) return not_found();
  destroy_body_joints(id, nullptr);
  // Bodies resting on this one must not float: wake everything it touches.
  // Its cache records stay, so the next step reports their exit events.
  d3::wake_touching(state_, id);
  BodyInfo& info = state_.infos[id.index];
  info.alive = 0;
  info.awake = 0;
  state_.sims[id.index] = BodySim{};
  state_.masses[id.index] = BodyMass{};
  auto& free = state_.free_slots;  // kept descending
  free.insert(std::lower_bound(free.begin(), free.end(), id.index, std::greater<uint32_t>()),
              id.index);
  --state_.live_count;
  d3::mark_world_edited(*scratch_);
  state_.at_rest = false;
  return Status::Ok();
}

Status World3D::destroy_body(BodyId id, std::vector<JointId>& removed_joints) {
  removed_joints.clear();
  if (!is_live(state_, id)) return not_found();
  destroy_body_joints(id, &removed_joints);
  return destroy_body(id);
}

bool World3D::is_valid(BodyId id) const {
  return is_live(state_, id);
}
uint32_t World3D::body_count() const {
  return state_.live_count;
}

void World3D::body_ids(std::vector<BodyId>& out) const {
  out.clear();
  for (uint32_t i = 0; i < state_.infos.size(); ++i) {
    if (state_.infos[i].alive != 0) out.push_back({i, state_.infos[i].generation});
  }
}

BodyKind World3D::kind(BodyId id) const {
  return is_live(state_, id) ? state_.infos[id.index].kind : BodyKind::kStatic;
}
Vec3 World3D::position(BodyId id) const {
  return is_live(state_, id) ? d3::authored_pose(state_, *geometry_, id.index).position : Vec3{};
}
Quat World3D::rotation(BodyId id) const {
  return is_live(state_, id) ? d3::authored_pose(state_, *geometry_, id.index).rotation : Quat{};
}
Vec3 World3D::center_of_mass(BodyId id) const {
  return is_live(state_, id) ? state_.sims[id.index].position : Vec3{};
}
Vec3 World3D::linear_velocity(BodyId id) const {
  return is_live(state_, id) ? state_.sims[id.index].linear_velocity : Vec3{};
}
Vec3 World3D::angular_velocity(BodyId id) const {
  return is_live(state_, id) ? state_.sims[id.index].angular_velocity : Vec3{};
}
float World3D::mass(BodyId id) const {
  return is_live(state_, id) ? state_.masses[id.index].mass : 0.0f;
}
uint64_t World3D::user_data(BodyId id) const {
  return is_live(state_, id) ? state_.infos[id.index].user_data : 0;
}
bool World3D::is_awake(BodyId id) const {
  return is_live(state_, id) && state_.infos[id.index].awake != 0;
}
const Shape* World3D::shape(BodyId id) const {
  return is_live(state_, id) ? &state_.infos[id.index].shape : nullptr;
}

Status World3D::set_transform(BodyId id, Vec3 position, Quat rotation) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(position) || !d3::inside_bounds(state_.config, position)) {
    return invalid("position must be finite and inside the world bounds");
  }
  if (!is_finite(rotation) || length_squared(rotation) < 1e-6f) {
    return invalid("rotation must be a finite, non-zero quaternion");
  }
  Vec3 p;
  Quat q;
  d3::authored_to_mass(d3::mass_frame(state_.infos[id.index].shape, *geometry_), quantize(position),
                       quantize(normalize(rotation)), p, q);
  if (!d3::inside_bounds(state_.config, p)) {
    return invalid("position (and a hull's centre of mass) must be inside the world bounds");
  }
  // A teleported body may leave sleeping bodies unsupported.
  d3::wake_touching(state_, id);
  BodySim& sim = state_.sims[id.index];
  sim.position = p;
  sim.rotation = q;
  d3::wake_body(state_, id.index);
  d3::mark_world_edited(*scratch_);
  state_.at_rest = false;
  return Status::Ok();
}

namespace {

// Velocity, impulse and force setters act on moving bodies only; a disabled
// body is frozen until the game enables it again.
Status check_movable(const WorldState& state, BodyId id, bool dynamic_only, const char* what) {
  const BodyInfo& info = state.infos[id.index];
  if (info.kind == BodyKind::kStatic || (dynamic_only && info.kind != BodyKind::kDynamic)) {
    return Status::Error(ErrorCode::kInvalidArgument, what);
  }
  if (info.enabled == 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "body is disabled (it left the world bounds or was disabled): "
                         "enable it first");
  }
  return Status::Ok();
}

bool speed_ok(Vec3 v) {
  return is_finite(v) && length_squared(v) <= d3::kMaxSpeed * d3::kMaxSpeed;
}

}  // namespace

Status World3D::set_linear_velocity(BodyId id, Vec3 velocity_mps) {
  if (!is_live(state_, id)) return not_found();
  if (!speed_ok(velocity_mps)) return invalid("velocity must be finite, at most 1e4 m/s");
  if (Status s = check_movable(state_, id, false, "static bodies cannot move"); !s.ok()) return s;
  const Vec3 v = quantize(velocity_mps);
  if (!speed_ok(v)) return invalid("velocity must be finite, at most 1e4 m/s");
  state_.sims[id.index].linear_velocity = v;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::set_angular_velocity(BodyId id, Vec3 velocity_radps) {
  if (!is_live(state_, id)) return not_found();
  if (!speed_ok(velocity_radps)) {
    return invalid("angular velocity must be finite, at most 1e4 rad/s");
  }
  if (Status s = check_movable(state_, id, false, "static bodies cannot rotate"); !s.ok()) {
    return s;
  }
  const Vec3 w =
      d3::without_locked_axes(state_.infos[id.index].lock_rotation, quantize(velocity_radps));
  if (!speed_ok(w)) return invalid("angular velocity must be finite, at most 1e4 rad/s");
  state_.sims[id.index].angular_velocity = w;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::apply_linear_impulse(BodyId id, Vec3 impulse, Vec3 world_point) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(impulse) || !is_finite(world_point)) {
    return invalid("impulse and point must be finite");
  }
  if (Status s = check_movable(state_, id, true, "impulses only move dynamic bodies"); !s.ok()) {
    return s;
  }
  Vec3 j = quantize(impulse);
  Vec3 p = quantize(world_point);
  BodySim& sim = state_.sims[id.index];
  const BodyMass& m = state_.masses[id.index];
  Vec3 dv = j * m.inv_mass;
  const uint8_t locks = state_.infos[id.index].lock_rotation;
  Vec3 dw = d3::lock_inverse_inertia(locks, d3::world_inverse_inertia(m, sim.rotation)) *
            cross(p - sim.position, j);
  Vec3 v = sim.linear_velocity + dv;
  Vec3 w = sim.angular_velocity + dw;
  if (!speed_ok(v) || !speed_ok(w)) return invalid("impulse would exceed the speed limit");
  sim.linear_velocity = v;
  sim.angular_velocity = w;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::apply_force(BodyId id, Vec3 force_n) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(force_n)) return invalid("force must be finite");
  if (Status s = check_movable(state_, id, true, "forces only move dynamic bodies"); !s.ok()) {
    return s;
  }
  Vec3 f = state_.sims[id.index].force + quantize(force_n);
  if (!is_finite(f) || length_squared(f) > d3::kMaxForce * d3::kMaxForce) {
    return invalid("force too large (> 1e12 N)");
  }
  state_.sims[id.index].force = f;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::set_rotation_lock(BodyId id, uint8_t locks) {
  if (!is_live(state_, id)) return not_found();
  if (locks > kLockRotationAll) return invalid("locks must be kLockRotation* bits (0 to 7)");
  state_.infos[id.index].lock_rotation = locks;
  BodySim& sim = state_.sims[id.index];
  sim.angular_velocity = d3::without_locked_axes(locks, sim.angular_velocity);
  if (d3::is_simulated(state_.infos[id.index])) d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::apply_torque(BodyId id, Vec3 torque_nm) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(torque_nm)) return invalid("torque must be finite");
  if (Status s = check_movable(state_, id, true, "torques only turn dynamic bodies"); !s.ok()) {
    return s;
  }
  const Vec3 t = state_.sims[id.index].torque + quantize(torque_nm);
  if (!is_finite(t) || length_squared(t) > d3::kMaxTorque * d3::kMaxTorque) {
    return invalid("torque too large (> 1e12 N m)");
  }
  state_.sims[id.index].torque = t;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::apply_force_at(BodyId id, Vec3 force_n, Vec3 world_point) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(force_n) || !is_finite(world_point)) {
    return invalid("force and point must be finite");
  }
  if (Status s = check_movable(state_, id, true, "forces only move dynamic bodies"); !s.ok()) {
    return s;
  }
  // Both sums are checked before either is kept: a refused call changes
  // nothing.
  BodySim& sim = state_.sims[id.index];
  const Vec3 f_in = quantize(force_n);
  const Vec3 f = sim.force + f_in;
  const Vec3 t = sim.torque + cross(quantize(world_point) - sim.position, f_in);
  if (!is_finite(f) || length_squared(f) > d3::kMaxForce * d3::kMaxForce) {
    return invalid("force too large (> 1e12 N)");
  }
  if (!is_finite(t) || length_squared(t) > d3::kMaxTorque * d3::kMaxTorque) {
    return invalid("torque too large (> 1e12 N m)");
  }
  sim.force = f;
  sim.torque = t;
  d3::wake_body(state_, id.index);
  return Status::Ok();
}

Status World3D::set_enabled(BodyId id, bool enabled) {
  if (!is_live(state_, id)) return not_found();
  BodyInfo& info = state_.infos[id.index];
  if ((info.enabled != 0) == enabled) return Status::Ok();
  if (enabled) {
    info.enabled = 1;
    d3::wake_body(state_, id.index);
  } else {
    // What rested on it must fall; its contacts end (with exit events) on
    // the next step, as a destroyed body's do.
    d3::wake_touching(state_, id);
    d3::disable_body(info, state_.sims[id.index]);
  }
  d3::mark_world_edited(*scratch_);
  state_.at_rest = false;
  return Status::Ok();
}

bool World3D::is_enabled(BodyId id) const {
  return is_live(state_, id) && state_.infos[id.index].enabled != 0;
}

Status World3D::set_continuous(BodyId id, bool continuous) {
  if (!is_live(state_, id)) return not_found();
  state_.infos[id.index].continuous = continuous ? 1 : 0;
  return Status::Ok();
}

Status World3D::set_event_mask(BodyId id, EventMask mask) {
  if (!is_live(state_, id)) return not_found();
  if ((mask & ~kEventAll) != 0) return invalid("event mask must be kEvent* bits (0 to 63)");
  state_.infos[id.index].event_mask = mask;
  return Status::Ok();
}

EventMask World3D::event_mask(BodyId id) const {
  return is_live(state_, id) ? state_.infos[id.index].event_mask : kEventNone;
}

Status World3D::set_contact_events(BodyId id, bool report) {
  return set_event_mask(id, report ? kEventAll : kEventNone);
}

bool World3D::is_continuous(BodyId id) const {
  return is_live(state_, id) && state_.infos[id.index].continuous != 0;
}

Status World3D::set_user_data(BodyId id, uint64_t user_data) {
  if (!is_live(state_, id)) return not_found();
  state_.infos[id.index].user_data = user_data;
  return Status::Ok();
}

// --- state ------------------------------------------------------------------

void World3D::save(WorldState& out) const {
  out = state_;
}

void World3D::restore(const WorldState& in) {
  state_ = in;
  // Scratch derived from the old state must not leak into the next step.
  d3::mark_world_edited(*scratch_);
  state_.at_rest = false;
  scratch_->events.clear();
  scratch_->body_events.clear();
  scratch_->broken_joints.clear();
  clear_step_queries();
}

const WorldState& World3D::state() const {
  return state_;
}

uint64_t World3D::checksum() const {
  StateHasher hasher;
  hash(hasher);
  return hasher.digest();
}

void World3D::hash(StateHasher& hasher) const {
  hash_state(state_, hasher);
}

void World3D::dump_bodies(std::vector<BodyRecord>& out) const {
  out.clear();
  for (uint32_t i = 0; i < state_.infos.size(); ++i) {
    const BodyInfo& info = state_.infos[i];
    if (info.alive == 0) continue;
    const BodySim& sim = state_.sims[i];
    BodyRecord r;
    r.id = {i, info.generation};
    r.kind = info.kind;
    r.user_data = info.user_data;
    const d3::AuthoredPose pose = d3::authored_pose(state_, *geometry_, i);
    r.position = pose.position;
    r.rotation = pose.rotation;
    r.linear_velocity = sim.linear_velocity;
    r.angular_velocity = sim.angular_velocity;
    r.awake = info.awake != 0;
    r.enabled = info.enabled != 0;
    out.push_back(r);
  }
}

void World3D::dump_fields(std::vector<BodyField>& out) const {
  std::vector<BodyRecord> records;
  dump_bodies(records);
  out.clear();
  for (const BodyRecord& r : records) append_body_fields(r, out);
}

}  // namespace rwd::sim
