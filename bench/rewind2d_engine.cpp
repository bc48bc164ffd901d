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
  if (threads > 1) pool_ = std::make_unique<rwd::ThreadPool>(threads);
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
  // Joints share the body capacity (create_joint refuses beyond it): the
  // most bodies or joints alive at once, waves included.
  size_t bodies = scene.bodies.size(), joints = scene.joints.size();
  size_t most = std::max(bodies, joints);
  for (const Wave2D& w : scene.waves) {
    for (uint32_t r : w.removes) {
      bodies -= scene.waves[r].bodies.size();
      joints -= scene.waves[r].joints.size();
    }
    bodies += w.bodies.size();
    joints += w.joints.size();
    most = std::max({most, bodies, joints});
  }
  config.max_bodies = static_cast<uint32_t>(most) + 16;
  // A setting the world refuses is reported, never run under the defaults.
  if (const auto s = sim2d::World2D::validate_config(config); !s.ok()) {
    error = "rewind: " + s.message();
    return false;
  }
  world_ = std::make_unique<sim2d::World2D>(config);
  world_->set_thread_pool(pool_.get());
  ids_.clear();
  wave_ids_.assign(scene.waves.size(), {});
  return add(scene, scene.bodies, scene.joints, ids_, error);
}

bool Rewind2DEngine::add_wave(const Scene2D& scene, uint32_t wave, std::string& error) {
  const Wave2D& w = scene.waves[wave];
  return add(scene, w.bodies, w.joints, wave_ids_[wave], error);
}

void Rewind2DEngine::remove_wave(uint32_t wave) {
  // One pass over the world's contacts and joints for the whole wave.
  (void)world_->destroy_bodies(wave_ids_[wave]);
  wave_ids_[wave].clear();
}

bool Rewind2DEngine::add(const Scene2D& scene, const std::vector<BodyDesc2D>& bodies,
                         const std::vector<RevoluteDesc2D>& joints,
                         std::vector<sim2d::BodyId2D>& ids, std::string& error) {
  const size_t first = ids.size();
  for (const BodyDesc2D& b : bodies) {
    const Vec2 centre{milli(b.cx), milli(b.cy)};
    const bool capsule = b.radius > 0 && b.capsule_y0 != b.capsule_y1;
    auto shape = capsule        ? sim2d::make_capsule(Vec2{centre.x, milli(b.capsule_y0)},
                                                      Vec2{centre.x, milli(b.capsule_y1)}, milli(b.radius))
                 : b.radius > 0 ? sim2d::make_circle(milli(b.radius), centre)
                                : sim2d::make_box(milli(b.hx), milli(b.hy), centre, Fx());
    if (!shape.ok()) {
      error = "rewind: shape refused: " + shape.status().message();
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
    def.linear_damping = milli(b.linear_damping);
    def.layer = b.layer;
    def.mask = b.mask;
    def.material.friction = milli(b.friction >= 0 ? b.friction : scene.friction);
    def.material.restitution = Fx();
    auto id = world_->create_body(def);
    if (!id.ok()) {
      error = "rewind: body " + std::to_string(ids.size()) + " refused: " + id.status().message();
      return false;
    }
    ids.push_back(*id);
  }
  for (const RevoluteDesc2D& j : joints) {
    sim2d::JointDef2D def;
    def.type = sim2d::JointType2D::kRevolute;
    def.body_a = ids[first + j.a];
    def.body_b = ids[first + j.b];
    def.anchor_a = def.anchor_b = Vec2{milli(j.x), milli(j.y)};
    def.reference_angle = milli(j.reference);
    def.enable_limit = j.limit;
    def.lower = milli(j.lower);
    def.upper = milli(j.upper);
    def.enable_motor = j.friction_torque > 0;
    def.max_motor = milli(j.friction_torque);
    def.enable_spring = j.hertz > 0;
    if (j.hertz > 0) {
      def.hertz = milli(j.hertz);
      def.damping_ratio = milli(j.damping_ratio);
    }
    if (auto id = world_->create_joint(def); !id.ok()) {
      error = "rewind: joint refused: " + id.status().message();
      return false;
    }
  }
  return true;
}

Pose2D Rewind2DEngine::pose(uint32_t index) const {
  return pose_of(ids_[index]);
}

Pose2D Rewind2DEngine::pose_of(sim2d::BodyId2D id) const {
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
