// SPDX-License-Identifier: MIT
// World2D: construction, bodies and their accessors and setters. The step
// lives in world2d_step.cpp, the state's bytes in world2d_serialize.cpp.
#include "rewind/sim2d/world2d.h"

#include <algorithm>
#include <string>
#include <utility>

#include "body_mass2d.h"
#include "body_math2d.h"
#include "fx_check.h"
#include "pipeline2d.h"
#include "rewind/fixed/trig.h"
#include "step_scratch2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

bool inside_bounds(const World2DConfig& config, V2 point) {
  return point.x >= w_from(config.bounds_lower.x) && point.x <= w_from(config.bounds_upper.x) &&
         point.y >= w_from(config.bounds_lower.y) && point.y <= w_from(config.bounds_upper.y);
}

Status check_def(const BodyDef2D& def, const World2DConfig& config) {
  if (def.kind != BodyKind2D::kStatic && def.kind != BodyKind2D::kKinematic &&
      def.kind != BodyKind2D::kDynamic) {
    return invalid("body kind must be static, kinematic or dynamic");
  }
  if (Status s = validate_shape(def.shape); !s.ok()) return s;
  if (def.shape.type == ShapeType2D::kSegment && def.kind == BodyKind2D::kDynamic) {
    return invalid("a segment has no area: only static and kinematic bodies may use it");
  }
  if (def.shape.type == ShapeType2D::kChainSegment && def.kind == BodyKind2D::kDynamic) {
    return invalid("a chain segment has no area: only static and kinematic bodies may use it");
  }
  if (!in_range(def.density, Fx::epsilon(), 30000_fx))
    return invalid("density must be in (0, 30000] kg/m^2");
  if (!in_range(def.linear_damping, Fx(), 1000_fx))
    return invalid("linear_damping must be in [0, 1000] 1/s");
  if (!in_range(def.angular_damping, Fx(), 1000_fx))
    return invalid("angular_damping must be in [0, 1000] 1/s");
  if (!in_range(def.gravity_scale, -100_fx, 100_fx))
    return invalid("gravity_scale must be in [-100, 100]");
  if (!in_range(def.material.friction, Fx(), 10_fx))
    return invalid("material.friction must be in [0, 10]");
  if (!in_range(def.material.restitution, Fx(), 1_fx))
    return invalid("material.restitution must be in [0, 1]");
  if (!in_range(def.material.rolling_resistance, Fx(), 1_fx)) {
    return invalid("material.rolling_resistance must be in [0, 1]");
  }
  if (!def.awake && def.kind == BodyKind2D::kDynamic &&
      (def.linear_velocity != Vec2{} || def.angular_velocity != Fx())) {
    return invalid("a body created asleep must have zero velocities (a sleeping body has none)");
  }
  const Fx speed_cap = config.max_linear_speed;
  if (!in_range(def.linear_velocity.x, -speed_cap, speed_cap) ||
      !in_range(def.linear_velocity.y, -speed_cap, speed_cap)) {
    return invalid("linear_velocity must be within the world's max_linear_speed");
  }
  return Status::Ok();
}

// Frees every live joint `lost(joint)` says lost a body; a freed slot keeps
// its generation, so old handles stay stale.
template <class Lost>
void free_joints(World2DState& state, Lost lost) {
  for (JointRecord2D& j : state.joints) {
    if (!(j.flags & kJointLive) || !lost(j)) continue;
    JointRecord2D freed;
    freed.generation = j.generation;
    j = freed;
    --state.live_joints;
  }
}

// Frees body slot `id` the same way.
void free_body(World2DState& state, BodyId2D id) {
  BodyRecord2D freed;
  freed.generation = id.generation;
  state.bodies[id.index] = freed;
  --state.live_bodies;
}

}  // namespace

Result<std::unique_ptr<World2D>> World2D::create(const World2DConfig& config) {
  if (Status status = validate_config(config); !status.ok()) return status;
  return std::make_unique<World2D>(config);
}

World2D::World2D(const World2DConfig& config) : scratch_(std::make_unique<StepScratch2D>()) {
  state_.config = validate_config(config).ok() ? config : World2DConfig{};
}

World2D::~World2D() = default;
World2D::World2D(World2D&&) noexcept = default;
World2D& World2D::operator=(World2D&&) noexcept = default;

Result<BodyId2D> World2D::create_body(const BodyDef2D& def) {
  if (Status s = check_def(def, state_.config); !s.ok()) return s;
  BodyRecord2D body;
  body.kind = def.kind;
  body.flags = kBodyLive | kBodyEnabled;
  // Asleep from the start is the state a settled body reaches (flag clear,
  // no velocity): everything that wakes one wakes it.
  if (def.awake || def.kind != BodyKind2D::kDynamic) body.flags |= kBodyAwake;
  if (def.sensor) body.flags |= kBodySensor;
  if (def.trigger) body.flags |= kBodyTrigger;
  if (def.lock_rotation) body.flags |= kBodyLockRotation;
  if (def.continuous && def.kind == BodyKind2D::kDynamic) body.flags |= kBodyContinuous;
  body.layer = def.layer;
  body.mask = def.mask;
  body.user_data = def.user_data;
  body.shape = def.shape;
  body.z = def.z;
  body.linear_damping = def.linear_damping;
  body.angular_damping = def.angular_damping;
  body.gravity_scale = def.gravity_scale;
  body.material = def.material;
  if (def.kind == BodyKind2D::kDynamic) {
    const MassData2 mass = compute_mass(def.shape, w_from(def.density));
    if (Status s = check_mass_range(mass, def.lock_rotation); !s.ok()) return s;
    set_mass(body, mass);
  }
  body.rotation = rotation_from_angle(def.angle);
  body.center = v_from(def.position) + rotate(body.rotation, body.local_center);
  if (!inside_bounds(state_.config, body.center)) {
    return invalid("the body's centre of mass must lie inside the world bounds");
  }
  if (def.kind != BodyKind2D::kStatic) {
    body.velocity = v_from(def.linear_velocity);
    if (!(body.flags & kBodyLockRotation)) body.angular_velocity = w_from(def.angular_velocity);
  }

  // Lowest free slot first, so ids depend only on the calls made.
  auto& bodies = state_.bodies;
  // Lowest free slot; with none free (the usual case while a scene is
  // built) the scan is skipped.
  uint32_t index = state_.live_bodies == bodies.size() ? static_cast<uint32_t>(bodies.size()) : 0;
  while (index < bodies.size() && (bodies[index].flags & kBodyLive)) ++index;
  if (index == bodies.size()) {
    if (state_.live_bodies >= state_.config.max_bodies) {
      return Status::Error(ErrorCode::kCapacity, "the world holds max_bodies bodies already");
    }
    bodies.emplace_back();
  }
  // A slot's generation outlives its body, so stale handles never match.
  const uint32_t generation =
      bodies[index].generation == UINT32_MAX ? 1 : bodies[index].generation + 1;
  body.generation = generation;
  bodies[index] = body;
  ++state_.live_bodies;
  ++body_edits_;
  return BodyId2D{index, generation};
}

Status World2D::destroy_body(BodyId2D id) {
  if (!is_valid(id)) return Status::Error(ErrorCode::kNotFound, "no such body");
  drop_contacts_of(state_, id.index);
  free_joints(state_, [&](const JointRecord2D& j) { return j.a == id.index || j.b == id.index; });
  free_body(state_, id);
  ++body_edits_;
  return Status::Ok();
}

Status World2D::destroy_bodies(std::span<const BodyId2D> ids) {
  // Each body's turn in the list; checked whole before anything changes.
  std::vector<uint32_t> turn_of(state_.bodies.size(), UINT32_MAX);
  for (uint32_t k = 0; k < ids.size(); ++k) {
    const BodyId2D id = ids[k];
    if (!is_valid(id)) {
      return Status::Error(ErrorCode::kNotFound,
                           "no such body (entry " + std::to_string(k) + "); nothing destroyed");
    }
    if (turn_of[id.index] != UINT32_MAX) {
      return Status::Error(
          ErrorCode::kInvalidArgument,
          "a body listed twice (entry " + std::to_string(k) + "); nothing destroyed");
    }
    turn_of[id.index] = k;
  }
  const auto turns = static_cast<uint32_t>(ids.size());
  drop_contacts_of(state_, turn_of, turns);
  free_joints(state_, [&](const JointRecord2D& j) {
    return turn_of[j.a] != UINT32_MAX || turn_of[j.b] != UINT32_MAX;
  });
  for (const BodyId2D id : ids) free_body(state_, id);
  body_edits_ += turns;
  return Status::Ok();
}

bool World2D::is_valid(BodyId2D id) const {
  return id.generation != 0 && id.index < state_.bodies.size() &&
         (state_.bodies[id.index].flags & kBodyLive) &&
         state_.bodies[id.index].generation == id.generation;
}

uint32_t World2D::body_count() const {
  return state_.live_bodies;
}

void World2D::body_ids(std::vector<BodyId2D>& out) const {
  out.clear();
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    if (state_.bodies[i].flags & kBodyLive) out.push_back({i, state_.bodies[i].generation});
  }
}

#define REWIND_BODY_OR(value)      \
  if (!is_valid(id)) return value; \
  const BodyRecord2D& body = state_.bodies[id.index]

BodyKind2D World2D::kind(BodyId2D id) const {
  REWIND_BODY_OR(BodyKind2D::kStatic);
  return body.kind;
}
Vec2 World2D::position(BodyId2D id) const {
  REWIND_BODY_OR(Vec2());
  return v_to_fx(origin_transform(body).p);
}
Fx World2D::angle(BodyId2D id) const {
  return rotation(id).angle();
}
fixed::Rot2 World2D::rotation(BodyId2D id) const {
  REWIND_BODY_OR(fixed::Rot2());
  return {w_to_fx(body.rotation.c), w_to_fx(body.rotation.s)};
}
Vec2 World2D::center_of_mass(BodyId2D id) const {
  REWIND_BODY_OR(Vec2());
  return v_to_fx(body.center);
}
Vec2 World2D::linear_velocity(BodyId2D id) const {
  REWIND_BODY_OR(Vec2());
  return v_to_fx(body.velocity);
}
Fx World2D::angular_velocity(BodyId2D id) const {
  REWIND_BODY_OR(Fx());
  return w_to_fx(body.angular_velocity);
}
fixed::FxWide World2D::mass(BodyId2D id) const {
  REWIND_BODY_OR(fixed::FxWide());
  return fixed::FxWide::from_raw(body_mass(body));
}
fixed::FxWide World2D::rotational_inertia(BodyId2D id) const {
  REWIND_BODY_OR(fixed::FxWide());
  return fixed::FxWide::from_raw(body_inertia(body));
}
Fx World2D::z(BodyId2D id) const {
  REWIND_BODY_OR(Fx());
  return body.z;
}
uint64_t World2D::user_data(BodyId2D id) const {
  REWIND_BODY_OR(0);
  return body.user_data;
}
const Shape2D* World2D::shape(BodyId2D id) const {
  REWIND_BODY_OR(nullptr);
  return &body.shape;
}
bool World2D::is_awake(BodyId2D id) const {
  REWIND_BODY_OR(false);
  return body.kind == BodyKind2D::kDynamic && (body.flags & kBodyAwake) != 0;
}
bool World2D::is_enabled(BodyId2D id) const {
  REWIND_BODY_OR(false);
  return (body.flags & kBodyEnabled) != 0;
}

#undef REWIND_BODY_OR

namespace {

Status not_found() {
  return Status::Error(ErrorCode::kNotFound, "no such body");
}

// Bodies a velocity, force or impulse may act on.
Status check_movable(const BodyRecord2D& body, bool kinematic_too) {
  if (!(body.flags & kBodyEnabled)) return invalid("the body is disabled");
  if (body.kind == BodyKind2D::kDynamic) return Status::Ok();
  if (kinematic_too && body.kind == BodyKind2D::kKinematic) return Status::Ok();
  return invalid(kinematic_too ? "only dynamic and kinematic bodies have a velocity"
                               : "only dynamic bodies take forces and impulses");
}

}  // namespace

Status World2D::set_transform(BodyId2D id, Vec2 position, Fx angle) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  const Rot rotation = rotation_from_angle(angle);
  const V2 center = v_from(position) + rotate(rotation, body.local_center);
  if (!inside_bounds(state_.config, center)) {
    return invalid("the body's centre of mass must lie inside the world bounds");
  }
  body.rotation = rotation;
  body.center = center;
  wake(body);
  ++body_edits_;
  return Status::Ok();
}

Status World2D::set_linear_velocity(BodyId2D id, Vec2 velocity) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, true); !s.ok()) return s;
  const Fx cap = state_.config.max_linear_speed;
  if (!in_range(velocity.x, -cap, cap) || !in_range(velocity.y, -cap, cap)) {
    return invalid("velocity must be within the world's max_linear_speed");
  }
  body.velocity = v_from(velocity);
  wake(body);
  return Status::Ok();
}

Status World2D::set_angular_velocity(BodyId2D id, Fx velocity) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, true); !s.ok()) return s;
  if (!(body.flags & kBodyLockRotation)) body.angular_velocity = w_from(velocity);
  wake(body);
  return Status::Ok();
}

Status World2D::apply_linear_impulse(BodyId2D id, Vec2 impulse, Vec2 world_point) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, false); !s.ok()) return s;
  const V2 p = v_from(impulse);
  const V2 r = v_from(world_point) - body.center;
  body.velocity = clamp_speed(vmul_add(body.velocity, body.inv_mass, p), state_.config);
  body.angular_velocity += wmul(body.inv_inertia, vcross(r, p));
  wake(body);
  return Status::Ok();
}

Status World2D::apply_angular_impulse(BodyId2D id, Fx impulse) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, false); !s.ok()) return s;
  body.angular_velocity += wmul(body.inv_inertia, w_from(impulse));
  wake(body);
  return Status::Ok();
}

Status World2D::apply_force(BodyId2D id, Vec2 force) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, false); !s.ok()) return s;
  body.force += v_from(force);
  wake(body);
  return Status::Ok();
}

Status World2D::apply_force_at(BodyId2D id, Vec2 force, Vec2 world_point) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, false); !s.ok()) return s;
  const V2 f = v_from(force);
  body.force += f;
  body.torque += vcross(v_from(world_point) - body.center, f);
  wake(body);
  return Status::Ok();
}

Status World2D::apply_torque(BodyId2D id, Fx torque) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (Status s = check_movable(body, false); !s.ok()) return s;
  body.torque += w_from(torque);
  wake(body);
  return Status::Ok();
}

Status World2D::set_continuous(BodyId2D id, bool continuous) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  if (body.kind != BodyKind2D::kDynamic) return invalid("only dynamic bodies sweep continuously");
  if (continuous) {
    body.flags |= kBodyContinuous;
  } else {
    body.flags &= static_cast<uint8_t>(~kBodyContinuous);
  }
  return Status::Ok();
}

bool World2D::is_continuous(BodyId2D id) const {
  return is_valid(id) && (state_.bodies[id.index].flags & kBodyContinuous) != 0;
}

Status World2D::wake_body(BodyId2D id) {
  if (!is_valid(id)) return not_found();
  wake(state_.bodies[id.index]);
  return Status::Ok();
}

Status World2D::set_user_data(BodyId2D id, uint64_t user_data) {
  if (!is_valid(id)) return not_found();
  state_.bodies[id.index].user_data = user_data;
  return Status::Ok();
}

Status World2D::set_z(BodyId2D id, Fx z) {
  if (!is_valid(id)) return not_found();
  state_.bodies[id.index].z = z;
  return Status::Ok();
}

Status World2D::set_enabled(BodyId2D id, bool enabled) {
  if (!is_valid(id)) return not_found();
  BodyRecord2D& body = state_.bodies[id.index];
  ++body_edits_;
  if (enabled) {
    body.flags |= kBodyEnabled;
    wake(body);
    return Status::Ok();
  }
  body.flags &= static_cast<uint8_t>(~kBodyEnabled);
  body.velocity = {};
  body.angular_velocity = 0;
  body.force = {};
  body.torque = 0;
  drop_contacts_of(state_, id.index);
  return Status::Ok();
}

const StepStats2D& World2D::stats() const {
  return stats_;
}
void World2D::set_thread_pool(rwd::ThreadPool* pool) {
  scratch_->pool = pool;
}

const World2DConfig& World2D::config() const {
  return state_.config;
}
uint64_t World2D::step_count() const {
  return state_.step_count;
}
const World2DState& World2D::state() const {
  return state_;
}

void World2D::save(World2DState& out) const {
  out.config = state_.config;
  out.step_count = state_.step_count;
  out.live_bodies = state_.live_bodies;
  out.bodies.assign(state_.bodies.begin(), state_.bodies.end());
  out.contacts.assign(state_.contacts.begin(), state_.contacts.end());
  out.pending_exits.assign(state_.pending_exits.begin(), state_.pending_exits.end());
  out.live_joints = state_.live_joints;
  out.joints.assign(state_.joints.begin(), state_.joints.end());
}

void World2D::restore(const World2DState& in) {
  state_.config = in.config;
  state_.step_count = in.step_count;
  state_.live_bodies = in.live_bodies;
  state_.bodies.assign(in.bodies.begin(), in.bodies.end());
  state_.contacts.assign(in.contacts.begin(), in.contacts.end());
  state_.pending_exits.assign(in.pending_exits.begin(), in.pending_exits.end());
  state_.live_joints = in.live_joints;
  state_.joints.assign(in.joints.begin(), in.joints.end());
  scratch_->events.clear();
  stats_ = {};
  ++body_edits_;
}

bool World2D::perturb_for_drill() {
  for (size_t i = state_.bodies.size(); i-- > 0;) {
    BodyRecord2D& body = state_.bodies[i];
    if ((body.flags & kBodyLive) && body.kind == BodyKind2D::kDynamic) {
      body.center.x += kWOne / 1024;
      ++body_edits_;
      return true;
    }
  }
  return false;
}

}  // namespace rwd::sim2d
