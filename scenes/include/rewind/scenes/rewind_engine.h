// SPDX-License-Identifier: MIT
#pragma once
// Rewind's World3D behind the scene Engine interface.
#include <memory>
#include <vector>

#include "rewind/core/thread_pool.h"
#include "rewind/scenes/engine.h"
#include "rewind/sim/world3d.h"

namespace rwd::scenes {

/// Runs scenes on Rewind with the solver settings of `config`; each scene
/// supplies gravity, tick length and world bounds, and max_bodies grows to
/// fit the scene. With `threads` above 1 the worlds step on a pool of that
/// many threads (World3D::set_thread_pool: the same results, sooner).
class RewindEngine final : public Engine {
 public:
  explicit RewindEngine(const sim::WorldConfig& config = {}, uint32_t threads = 1);

  std::string name() const override { return "rewind"; }
  std::string settings() const override;
  void reset(const WorldSpec& world, uint32_t body_capacity) override;
  bool add_hull(std::span<const Vec3> points, sim::GeometryId& out, std::string& error) override;
  bool add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                    std::string& error) override;
  bool add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                sim::GeometryId& out, std::string& error) override;
  bool add_height_field(uint32_t rows, uint32_t cols, Vec3 scale, std::span<const float> heights,
                        sim::GeometryId& out, std::string& error) override;
  bool add_body(const BodySpec& spec, BodyHandle& out, std::string& error) override;
  void step() override;
  Vec3 position(BodyHandle body) const override;
  Quat rotation(BodyHandle body) const override;
  Vec3 linear_velocity(BodyHandle body) const override;
  Vec3 angular_velocity(BodyHandle body) const override;
  bool enabled(BodyHandle body) const override;
  void apply_impulse(BodyHandle body, Vec3 impulse_ns, Vec3 world_point) override;
  void set_velocity(BodyHandle body, Vec3 linear_mps, Vec3 angular_radps) override;
  uint32_t awake_count() const override;

  /// The world of the current scene (for checks a scene does not cover).
  const sim::World3D& world() const { return *world_; }

 private:
  sim::WorldConfig config_;
  std::unique_ptr<rwd::ThreadPool> pool_;  // null: one thread; outlives world_
  std::unique_ptr<sim::World3D> world_;
  std::vector<sim::BodyId> ids_;
};

}  // namespace rwd::scenes
