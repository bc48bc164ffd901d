// SPDX-License-Identifier: MIT
#pragma once
// Bullet 3 (Debian's libbullet-dev, float32) behind the scene Engine
// interface, for side-by-side measurements. Lives in bench/ only: nothing in
// the engine or its tests links it. The parameter mapping is documented in
// docs/BENCHMARKS.md (written by scripts/charts.py).
#include <memory>
#include <string>

#include "rewind/scenes/engine.h"

namespace rwd::bench {

/// Bullet's solver settings that the charts sweep.
struct BulletSettings {
  int iterations = 10;  ///< btContactSolverInfo::m_numIterations (Bullet's default)
  int substeps = 1;     ///< fixed internal steps per tick
  bool sleep = true;    ///< false: no body is ever deactivated
};

class BulletEngine final : public scenes::Engine {
 public:
  explicit BulletEngine(const BulletSettings& settings = {});
  ~BulletEngine() override;
  BulletEngine(const BulletEngine&) = delete;
  BulletEngine& operator=(const BulletEngine&) = delete;

  std::string name() const override { return "bullet"; }
  std::string settings() const override;
  void reset(const scenes::WorldSpec& world, uint32_t body_capacity) override;
  bool add_hull(std::span<const scenes::Vec3> points, sim::GeometryId& out,
                std::string& error) override;
  bool add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                    std::string& error) override;
  bool add_mesh(std::span<const scenes::Vec3> vertices, std::span<const uint32_t> indices,
                sim::GeometryId& out, std::string& error) override;
  bool add_height_field(uint32_t rows, uint32_t cols, scenes::Vec3 scale,
                        std::span<const float> heights, sim::GeometryId& out,
                        std::string& error) override;
  bool add_body(const scenes::BodySpec& spec, scenes::BodyHandle& out, std::string& error) override;
  void step() override;
  scenes::Vec3 position(scenes::BodyHandle body) const override;
  scenes::Quat rotation(scenes::BodyHandle body) const override;
  scenes::Vec3 linear_velocity(scenes::BodyHandle body) const override;
  scenes::Vec3 angular_velocity(scenes::BodyHandle body) const override;
  bool enabled(scenes::BodyHandle body) const override;
  void apply_impulse(scenes::BodyHandle body, scenes::Vec3 impulse_ns,
                     scenes::Vec3 world_point) override;
  void set_velocity(scenes::BodyHandle body, scenes::Vec3 linear_mps,
                    scenes::Vec3 angular_radps) override;
  uint32_t awake_count() const override;

 private:
  struct World;
  BulletSettings settings_;
  std::unique_ptr<World> world_;
};

}  // namespace rwd::bench
