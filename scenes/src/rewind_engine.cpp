// SPDX-License-Identifier: MIT
// BodySpec maps onto BodyDef one to one: Rewind's own combine rules
// (friction by geometric mean, restitution by maximum) and damping (a rate
// in 1/s, applied per substep as 1 / (1 + h c)) are what BodySpec means.
#include "rewind/scenes/rewind_engine.h"

#include <algorithm>
#include <sstream>

namespace rwd::scenes {

RewindEngine::RewindEngine(const sim::WorldConfig& config, uint32_t threads) : config_(config) {
  if (threads > 1) pool_ = std::make_unique<rwd::ThreadPool>(threads);
}

std::string RewindEngine::settings() const {
  std::ostringstream out;
  out << "substeps=" << config_.substeps << " relax=" << config_.relax_iterations
      << " hertz=" << config_.contact_hertz;
  if (!config_.enable_sleep) out << " sleep=off";
  if (pool_ != nullptr) out << " threads=" << pool_->threads();
  return out.str();
}

void RewindEngine::reset(const WorldSpec& world, uint32_t body_capacity) {
  sim::WorldConfig config = config_;
  config.gravity = world.gravity;
  config.tick_seconds = world.tick_seconds;
  config.bounds_lower = world.bounds_lower;
  config.bounds_upper = world.bounds_upper;
  config.max_bodies = std::max(config.max_bodies, body_capacity);
  world_ = std::make_unique<sim::World3D>(config);
  world_->set_thread_pool(pool_.get());
  ids_.clear();
}

bool RewindEngine::add_hull(std::span<const Vec3> points, sim::GeometryId& out,
                            std::string& error) {
  auto id = world_->geometry().add_hull(points);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  out = *id;
  return true;
}

bool RewindEngine::add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                                std::string& error) {
  auto id = world_->geometry().add_compound(children);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  out = *id;
  return true;
}

bool RewindEngine::add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                            sim::GeometryId& out, std::string& error) {
  auto id = world_->geometry().add_mesh(vertices, indices);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  out = *id;
  return true;
}

bool RewindEngine::add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                    std::span<const float> heights, sim::GeometryId& out,
                                    std::string& error) {
  auto id = world_->geometry().add_height_field(rows, cols, scale, heights);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  out = *id;
  return true;
}

bool RewindEngine::add_body(const BodySpec& spec, BodyHandle& out, std::string& error) {
  sim::BodyDef def;
  def.kind = spec.kind;
  def.shape = spec.shape;
  def.position = spec.position;
  def.rotation = spec.rotation;
  def.linear_velocity = spec.linear_velocity;
  def.angular_velocity = spec.angular_velocity;
  def.density = spec.density;
  def.linear_damping = spec.linear_damping;
  def.angular_damping = spec.angular_damping;
  def.material.friction = spec.friction;
  def.material.restitution = spec.restitution;
  def.material.rolling_resistance = spec.rolling_resistance;
  def.continuous = spec.continuous;
  auto id = world_->create_body(def);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  out = static_cast<BodyHandle>(ids_.size());
  ids_.push_back(*id);
  return true;
}

void RewindEngine::step() {
  world_->step();
}

Vec3 RewindEngine::position(BodyHandle body) const {
  return world_->position(ids_[body]);
}
Quat RewindEngine::rotation(BodyHandle body) const {
  return world_->rotation(ids_[body]);
}
Vec3 RewindEngine::linear_velocity(BodyHandle body) const {
  return world_->linear_velocity(ids_[body]);
}
Vec3 RewindEngine::angular_velocity(BodyHandle body) const {
  return world_->angular_velocity(ids_[body]);
}
bool RewindEngine::enabled(BodyHandle body) const {
  return world_->is_enabled(ids_[body]);
}

void RewindEngine::apply_impulse(BodyHandle body, Vec3 impulse_ns, Vec3 world_point) {
  // A refused impulse (disabled body, speed limit) leaves the body as it
  // was; the scene's metrics show the consequence.
  (void)world_->apply_linear_impulse(ids_[body], impulse_ns, world_point);
}

void RewindEngine::set_velocity(BodyHandle body, Vec3 linear_mps, Vec3 angular_radps) {
  (void)world_->set_linear_velocity(ids_[body], linear_mps);
  (void)world_->set_angular_velocity(ids_[body], angular_radps);
}

uint32_t RewindEngine::awake_count() const {
  uint32_t awake = 0;
  for (sim::BodyId id : ids_) {
    if (world_->kind(id) == BodyKind::kDynamic && world_->is_awake(id)) ++awake;
  }
  return awake;
}

}  // namespace rwd::scenes
