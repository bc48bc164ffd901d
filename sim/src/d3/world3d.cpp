// SPDX-License-Identifier: MIT
// World3D: the public surface. Validates every argument before touching
// state, owns the step pipeline's order, and keeps scratch apart from state.
#include "rewind/sim/world3d.h"

#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
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

bool finite_in(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

WorldConfig sanitize(const WorldConfig& c) {
  WorldConfig d;
  WorldConfig out = c;
  if (!is_finite(c.gravity) || std::fabs(c.gravity.x) > 1e4f || std::fabs(c.gravity.y) > 1e4f ||
      std::fabs(c.gravity.z) > 1e4f) {
    out.gravity = d.gravity;
  }
  if (!(c.tick_seconds > 0.0f && c.tick_seconds <= 0.1f)) out.tick_seconds = d.tick_seconds;
  if (c.substeps < 1 || c.substeps > 64) out.substeps = d.substeps;
  if (c.relax_iterations < 0 || c.relax_iterations > 16) out.relax_iterations = d.relax_iterations;
  if (!finite_in(c.contact_hertz, 1e-3f, 1e4f)) out.contact_hertz = d.contact_hertz;
  if (!finite_in(c.contact_damping_ratio, 0.0f, 1e4f)) {
    out.contact_damping_ratio = d.contact_damping_ratio;
  }
  if (!finite_in(c.contact_push_max_mps, 0.0f, 1e4f)) {
    out.contact_push_max_mps = d.contact_push_max_mps;
  }
  if (!finite_in(c.restitution_threshold_mps, 0.0f, 1e4f)) {
    out.restitution_threshold_mps = d.restitution_threshold_mps;
  }
  if (!finite_in(c.linear_slop_m, 0.0f, 1.0f)) out.linear_slop_m = d.linear_slop_m;
  if (!finite_in(c.speculative_distance_m, 0.0f, 10.0f)) {
    out.speculative_distance_m = d.speculative_distance_m;
  }
  if (!finite_in(c.sleep_threshold_mps, 0.0f, 1e4f))
    out.sleep_threshold_mps = d.sleep_threshold_mps;
  if (!finite_in(c.time_to_sleep_s, 0.0f, 1e6f)) out.time_to_sleep_s = d.time_to_sleep_s;
  if (c.max_bodies < 1 || c.max_bodies > (1u << 24)) out.max_bodies = d.max_bodies;
  // Values enter the canonical grid like every other outside value.
  out.gravity = quantize(out.gravity);
  out.tick_seconds = quantize(out.tick_seconds);
  out.contact_hertz = quantize(out.contact_hertz);
  out.contact_damping_ratio = quantize(out.contact_damping_ratio);
  out.contact_push_max_mps = quantize(out.contact_push_max_mps);
  out.restitution_threshold_mps = quantize(out.restitution_threshold_mps);
  out.linear_slop_m = quantize(out.linear_slop_m);
  out.speculative_distance_m = quantize(out.speculative_distance_m);
  out.sleep_threshold_mps = quantize(out.sleep_threshold_mps);
  out.time_to_sleep_s = quantize(out.time_to_sleep_s);
  return out;
}

Quat quantize(Quat q) {
  return {sim::quantize(q.x), sim::quantize(q.y), sim::quantize(q.z), sim::quantize(q.w)};
}

}  // namespace

World3D::World3D(const WorldConfig& config) : scratch_(std::make_unique<WorldScratch>()) {
  state_.config = sanitize(config);
}
World3D::~World3D() = default;
World3D::World3D(World3D&&) noexcept = default;
World3D& World3D::operator=(World3D&&) noexcept = default;

Status World3D::validate_config(const WorldConfig& c) {
  if (!is_finite(c.gravity) || std::fabs(c.gravity.x) > 1e4f || std::fabs(c.gravity.y) > 1e4f ||
      std::fabs(c.gravity.z) > 1e4f) {
    return invalid("gravity must be finite, |g| <= 1e4 m/s^2");
  }
  if (!(c.tick_seconds > 0.0f && c.tick_seconds <= 0.1f)) {
    return invalid("tick_seconds must be in (0, 0.1]");
  }
  if (c.substeps < 1 || c.substeps > 64) return invalid("substeps must be in [1, 64]");
  if (c.relax_iterations < 0 || c.relax_iterations > 16) {
    return invalid("relax_iterations must be in [0, 16]");
  }
  if (!finite_in(c.contact_hertz, 1e-3f, 1e4f))
    return invalid("contact_hertz must be in [1e-3, 1e4]");
  if (!finite_in(c.contact_damping_ratio, 0.0f, 1e4f)) {
    return invalid("contact_damping_ratio must be in [0, 1e4]");
  }
  if (!finite_in(c.contact_push_max_mps, 0.0f, 1e4f)) {
    return invalid("contact_push_max_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.restitution_threshold_mps, 0.0f, 1e4f)) {
    return invalid("restitution_threshold_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.linear_slop_m, 0.0f, 1.0f)) return invalid("linear_slop_m must be in [0, 1]");
  if (!finite_in(c.speculative_distance_m, 0.0f, 10.0f)) {
    return invalid("speculative_distance_m must be in [0, 10]");
  }
  if (!finite_in(c.sleep_threshold_mps, 0.0f, 1e4f)) {
    return invalid("sleep_threshold_mps must be in [0, 1e4]");
  }
  if (!finite_in(c.time_to_sleep_s, 0.0f, 1e6f))
    return invalid("time_to_sleep_s must be in [0, 1e6]");
  if (c.max_bodies < 1 || c.max_bodies > (1u << 24))
    return invalid("max_bodies must be in [1, 2^24]");
  return Status::Ok();
}

// --- bodies -----------------------------------------------------------------

Result<BodyId> World3D::create_body(const BodyDef& def) {
  Status s = d3::validate_body_def(def);
  if (!s.ok()) return s;
  if (state_.live_count >= state_.config.max_bodies) {
    return Status::Error(ErrorCode::kCapacity, "world is full (max_bodies)");
  }
  BodyDef q = def;
  q.shape.radius = quantize(def.shape.radius);
  q.shape.half_extents = quantize(def.shape.half_extents);
  q.position = quantize(def.position);
  q.rotation = quantize(normalize(def.rotation));
  q.linear_velocity = quantize(def.linear_velocity);
  q.angular_velocity = quantize(def.angular_velocity);
  q.density = quantize(def.density);
  q.linear_damping = quantize(def.linear_damping);
  q.angular_damping = quantize(def.angular_damping);
  q.gravity_scale = quantize(def.gravity_scale);
  q.material.friction = quantize(def.material.friction);
  q.material.restitution = quantize(def.material.restitution);
  // Quantizing can round a tiny size to zero: validate again.
  s = d3::validate_shape(q.shape);
  if (!s.ok() || !(q.density > 0.0f)) return invalid("shape or density too small for the grid");
  BodyMass mass = d3::compute_mass(q.kind, q.shape, q.density);
  if (q.kind == BodyKind::kDynamic &&
      !(std::isfinite(mass.mass) && mass.mass > 0.0f && std::isfinite(mass.inv_mass) &&
        is_finite(mass.inv_inertia_local))) {
    return invalid("degenerate mass: shape too small or density too extreme");
  }

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
  BodyInfo& info = state_.infos[index];
  uint32_t generation = info.generation + 1;
  if (generation == 0) generation = 1;  // wrapped: 0 is the null handle
  info.generation = generation;
  info.alive = 1;
  info.kind = q.kind;
  info.sensor = q.sensor ? 1 : 0;
  info.awake = q.kind == BodyKind::kStatic ? 0 : 1;
  info.shape = q.shape;
  if (q.shape.type == ShapeType::kSphere) info.shape.half_extents = {};
  if (q.shape.type == ShapeType::kBox) info.shape.radius = 0.0f;
  info.material = q.material;
  info.layer = q.layer;
  info.mask = q.mask;
  info.user_data = q.user_data;
  info.density = q.density;
  info.linear_damping = q.linear_damping;
  info.angular_damping = q.angular_damping;
  info.gravity_scale = q.gravity_scale;
  BodySim& sim = state_.sims[index];
  sim = BodySim{};
  sim.position = q.position;
  sim.rotation = q.rotation;
  sim.linear_velocity = q.kind == BodyKind::kStatic ? Vec3{} : q.linear_velocity;
  sim.angular_velocity = q.kind == BodyKind::kStatic ? Vec3{} : q.angular_velocity;
  state_.masses[index] = mass;
  ++state_.live_count;
  d3::mark_passive_dirty(*scratch_);
  return BodyId{index, generation};
}

Status World3D::destroy_body(BodyId id) {
  if (!is_live(state_, id)) return not_found();
  // Bodies resting on this one must not float: wake everything it touches.
  // Its cache records stay, so the next step reports their exit events.
  d3::wake_touching(state_, *scratch_, id);
  BodyInfo& info = state_.infos[id.index];
  info.alive = 0;
  info.awake = 0;
  state_.sims[id.index] = BodySim{};
  state_.masses[id.index] = BodyMass{};
  auto& free = state_.free_slots;  // kept descending
  free.insert(std::lower_bound(free.begin(), free.end(), id.index, std::greater<uint32_t>()),
              id.index);
  --state_.live_count;
  d3::mark_passive_dirty(*scratch_);
  return Status::Ok();
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
  return is_live(state_, id) ? state_.sims[id.index].position : Vec3{};
}
Quat World3D::rotation(BodyId id) const {
  return is_live(state_, id) ? state_.sims[id.index].rotation : Quat{};
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
  if (!is_finite(position) || std::fabs(position.x) >= d3::kMaxCoordinate ||
      std::fabs(position.y) >= d3::kMaxCoordinate || std::fabs(position.z) >= d3::kMaxCoordinate) {
    return invalid("position must be finite, |x| < 1e5 m");
  }
  if (!is_finite(rotation) || length_squared(rotation) < 1e-6f) {
    return invalid("rotation must be a finite, non-zero quaternion");
  }
  BodySim& sim = state_.sims[id.index];
  sim.position = quantize(position);
  sim.rotation = quantize(normalize(rotation));
  d3::wake_body(state_, *scratch_, id.index);
  // A teleported body may leave sleeping bodies unsupported.
  d3::wake_touching(state_, *scratch_, id);
  d3::mark_passive_dirty(*scratch_);
  return Status::Ok();
}

Status World3D::set_linear_velocity(BodyId id, Vec3 velocity_mps) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(velocity_mps) || length_squared(velocity_mps) > d3::kMaxSpeed * d3::kMaxSpeed) {
    return invalid("velocity must be finite, at most 1e4 m/s");
  }
  if (state_.infos[id.index].kind == BodyKind::kStatic) {
    return invalid("static bodies cannot move");
  }
  state_.sims[id.index].linear_velocity = quantize(velocity_mps);
  d3::wake_body(state_, *scratch_, id.index);
  return Status::Ok();
}

Status World3D::set_angular_velocity(BodyId id, Vec3 velocity_radps) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(velocity_radps) ||
      length_squared(velocity_radps) > d3::kMaxSpeed * d3::kMaxSpeed) {
    return invalid("angular velocity must be finite, at most 1e4 rad/s");
  }
  if (state_.infos[id.index].kind == BodyKind::kStatic) {
    return invalid("static bodies cannot rotate");
  }
  state_.sims[id.index].angular_velocity = quantize(velocity_radps);
  d3::wake_body(state_, *scratch_, id.index);
  return Status::Ok();
}

Status World3D::apply_linear_impulse(BodyId id, Vec3 impulse, Vec3 world_point) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(impulse) || !is_finite(world_point)) {
    return invalid("impulse and point must be finite");
  }
  if (state_.infos[id.index].kind != BodyKind::kDynamic) {
    return invalid("impulses only move dynamic bodies");
  }
  Vec3 j = quantize(impulse);
  Vec3 p = quantize(world_point);
  BodySim& sim = state_.sims[id.index];
  const BodyMass& m = state_.masses[id.index];
  Vec3 dv = j * m.inv_mass;
  Vec3 dw = d3::world_inverse_inertia(m, sim.rotation) * cross(p - sim.position, j);
  Vec3 v = sim.linear_velocity + dv;
  Vec3 w = sim.angular_velocity + dw;
  if (!is_finite(v) || !is_finite(w) || length_squared(v) > d3::kMaxSpeed * d3::kMaxSpeed ||
      length_squared(w) > d3::kMaxSpeed * d3::kMaxSpeed) {
    return invalid("impulse would exceed the speed limit");
  }
  sim.linear_velocity = v;
  sim.angular_velocity = w;
  d3::wake_body(state_, *scratch_, id.index);
  return Status::Ok();
}

Status World3D::apply_force(BodyId id, Vec3 force_n) {
  if (!is_live(state_, id)) return not_found();
  if (!is_finite(force_n)) return invalid("force must be finite");
  if (state_.infos[id.index].kind != BodyKind::kDynamic) {
    return invalid("forces only move dynamic bodies");
  }
  Vec3 f = state_.sims[id.index].force + quantize(force_n);
  if (!is_finite(f) || length_squared(f) > 1e24f) return invalid("force too large (> 1e12 N)");
  state_.sims[id.index].force = f;
  d3::wake_body(state_, *scratch_, id.index);
  return Status::Ok();
}

Status World3D::set_user_data(BodyId id, uint64_t user_data) {
  if (!is_live(state_, id)) return not_found();
  state_.infos[id.index].user_data = user_data;
  return Status::Ok();
}

// --- stepping ---------------------------------------------------------------

void World3D::step() {
  WorldScratch& s = *scratch_;
  s.stats = StepStats{};
  d3::find_pairs(state_, s);
  d3::update_contacts(state_, s);
  d3::wake_touched_islands(state_, s);
  d3::build_events(state_, s);
  d3::solve(state_, s);
  d3::update_sleep(state_, s);
  ++state_.step_count;
}

std::span<const ContactEvent> World3D::events() const {
  return scratch_->events;
}
const StepStats& World3D::stats() const {
  return scratch_->stats;
}
const WorldConfig& World3D::config() const {
  return state_.config;
}
uint64_t World3D::step_count() const {
  return state_.step_count;
}

// --- state ------------------------------------------------------------------

void World3D::save(WorldState& out) const {
  out = state_;
}

void World3D::restore(const WorldState& in) {
  state_ = in;
  // Scratch derived from the old state must not leak into the next step.
  d3::mark_passive_dirty(*scratch_);
  scratch_->events.clear();
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
    r.position = sim.position;
    r.rotation = sim.rotation;
    r.linear_velocity = sim.linear_velocity;
    r.angular_velocity = sim.angular_velocity;
    r.awake = info.awake != 0;
    out.push_back(r);
  }
}

}  // namespace rwd::sim
