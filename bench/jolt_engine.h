// SPDX-License-Identifier: MIT
#pragma once
// Jolt Physics (v5, single precision, built from the source tree given as
// REWIND_JOLT_DIR) behind the scene Engine interface, for side-by-side
// measurements. Optional and bench/ only: built when REWIND_JOLT_DIR is set
// (REWIND_HAVE_JOLT is then defined for its users). Jolt's headers stay in
// jolt_engine.cpp. The parameter mapping is documented in
// docs/BENCHMARKS.md (written by scripts/charts.py).
#include <memory>
#include <string>

#include "rewind/scenes/engine.h"

namespace rwd::bench {

/// Jolt's solver settings that the charts sweep; the defaults are Jolt's.
struct JoltSettings {
  bool sleep = true;             ///< false: no body is ever put to sleep
  int velocity_iterations = 10;  ///< PhysicsSettings::mNumVelocitySteps
  int position_iterations = 2;   ///< PhysicsSettings::mNumPositionSteps
  int collision_steps = 1;       ///< PhysicsSystem::Update's inCollisionSteps per tick
};

class JoltEngine final : public scenes::Engine {
 public:
  explicit JoltEngine(const JoltSettings& settings = {});
  ~JoltEngine() override;
  JoltEngine(const JoltEngine&) = delete;
  JoltEngine& operator=(const JoltEngine&) = delete;

  std::string name() const override { return "jolt"; }
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
  JoltSettings settings_;
  std::unique_ptr<World> world_;
};

}  // namespace rwd::bench
