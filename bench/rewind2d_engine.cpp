// SPDX-License-Identifier: MIT
#include "rewind2d_engine.h"

#include <algorithm>
#include <cstdint>
#include <string>

namespace rwd::bench {

namespace {

using fixed::Fx;
using fixed::Vec2;

Fx milli(int32_t v) {
  return Fx::ratio(v, 1000);
}

// Measurement only: the lane itself has no floating point.
double to_double(Fx v) {
  return static_cast<double>(v.raw()) / 65536.0;
}

}  // namespace

Rewind2DEngine::Rewind2DEngine(int substeps, int relax_iterations, uint32_t threads) {
  config_.substeps = substeps;
  config_.relax_iterations = relax_iterations;
  if (threads > 1) pool_ = std::make_unique<sim::ThreadPool>(threads);
}

std::string Rewind2DEngine::settings() const {
  std::string s = "substeps=" + std::to_string(config_.substeps) +
                  " relax=" + std::to_string(config_.relax_iterations);
  if (pool_ != nullptr) s += " threads=" + std::to_string(pool_->threads());
  return s;
}

bool Rewind2DEngine::is_default() const {
  const sim2d::World2DConfig d;
  return config_.substeps == d.substeps && config_.relax_iterations == d.relax_iterations &&
         pool_ == nullptr;
}

bool Rewind2DEngine::build(const Scene2D& scene, std::string& error) {
  sim2d::World2DConfig config = config_;
  config.tick_hz = 60;
  // Every body kept awake in both engines, so they do the same work.
  config.enable_sleep = false;
  config.gravity = Vec2{Fx(), milli(scene.gravity)};
  // Joints share the body capacity (create_joint refuses beyond it).
  config.max_bodies =
      static_cast<uint32_t>(std::max(scene.bodies.size(), scene.joints.size())) + 16;
  // A setting the world refuses is reported, never run under the defaults.
  if (const auto s = sim2d::World2D::validate_config(config); !s.ok()) {
    error = "rewind: " + s.message();
    return false;
  }
  world_ = std::make_unique<sim2d::World2D>(config);
  world_->set_thread_pool(pool_.get());
  ids_.clear();
  for (const BodyDesc2D& b : scene.bodies) {
    const Vec2 centre{milli(b.cx), milli(b.cy)};
    auto shape = b.radius > 0 ? sim2d::make_circle(milli(b.radius), centre)
                              : sim2d::make_box(milli(b.hx), milli(b.hy), centre, Fx());
    if (!shape.ok()) {
      error = std::string("rewind: ") + (b.radius > 0 ? "circle" : "box") + " refused";
      return false;
    }
    sim2d::BodyDef2D def;
    def.kind = b.kind == Kind2D::kStatic      ? sim2d::BodyKind2D::kStatic
               : b.kind == Kind2D::kKinematic ? sim2d::BodyKind2D::kKinematic
                                              : sim2d::BodyKind2D::kDynamic;
    def.shape = *shape;
    def.position = Vec2{milli(b.x), milli(b.y)};
    def.linear_velocity = Vec2{milli(b.vx), milli(b.vy)};
    def.angular_velocity = milli(b.angular_velocity);
    def.density = milli(b.density > 0 ? b.density : scene.density);
    def.awake = b.awake;
    def.material.friction = milli(scene.friction);
    def.material.restitution = Fx();
    auto id = world_->create_body(def);
    if (!id.ok()) {
      error = "rewind: body " + std::to_string(ids_.size()) + " refused: " + id.status().message();
      return false;
    }
    ids_.push_back(*id);
  }
  for (const RevoluteDesc2D& j : scene.joints) {
    sim2d::JointDef2D def;
    def.type = sim2d::JointType2D::kRevolute;
    def.body_a = ids_[j.a];
    def.body_b = ids_[j.b];
    def.anchor_a = def.anchor_b = Vec2{milli(j.x), milli(j.y)};
    if (auto id = world_->create_joint(def); !id.ok()) {
      error = "rewind: joint refused: " + id.status().message();
      return false;
    }
  }
  return true;
}

Pose2D Rewind2DEngine::pose(uint32_t index) const {
  const sim2d::BodyId2D id = ids_[index];
  const Vec2 p = world_->position(id);
  return {to_double(p.x), to_double(p.y), to_double(world_->angle(id))};
}

bool Rewind2DEngine::raycast(double x0, double y0, double x1, double y1, double& fraction) const {
  // Measurement code: the ray comes in as floating point and is rounded to
  // the lane's Q16.16 grid (its values are within the Fx range).
  auto fx = [](double v) { return Fx::from_raw(static_cast<int32_t>(v * 65536.0)); };
  const auto hit = world_->raycast({fx(x0), fx(y0)}, {fx(x1 - x0), fx(y1 - y0)});
  if (!hit) return false;
  fraction = to_double(hit->fraction);
  return true;
}

}  // namespace rwd::bench
