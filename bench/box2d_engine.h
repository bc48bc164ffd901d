// SPDX-License-Identifier: MIT
#pragma once
// Box2D 2.4 (Debian's libbox2d-dev) behind the Engine2D interface, for
// side-by-side measurements. Lives in bench/ only.
#include <memory>
#include <vector>

#include "engine2d.h"

class b2World;
class b2Body;

namespace rwd::bench {

class Box2DEngine final : public Engine2D {
 public:
  /// b2World::Step's iteration counts (Box2D's defaults: 8 and 3).
  /// `continuous`: b2World::SetContinuousPhysics (Box2D's default, on).
  Box2DEngine(int velocity_iterations, int position_iterations, bool continuous = true);
  ~Box2DEngine() override;
  Box2DEngine(const Box2DEngine&) = delete;
  Box2DEngine& operator=(const Box2DEngine&) = delete;

  std::string name() const override { return "box2d"; }
  std::string settings() const override;
  bool is_default() const override { return velocity_ == 8 && position_ == 3 && continuous_; }
  /// Refuses scenes with joint springs or capsules (Box2D 2.4.1 has
  /// neither), and so those with waves (only the rain has them).
  bool build(const Scene2D& scene, std::string& error) override;
  bool add_wave(const Scene2D& scene, uint32_t wave, std::string& error) override;
  void remove_wave(uint32_t /*wave*/) override {}
  void step() override;
  Pose2D pose(uint32_t index) const override;
  /// Never called: build() refuses every scene with waves.
  Pose2D wave_pose(uint32_t /*wave*/, uint32_t /*index*/) const override { return {}; }
  bool raycast(double x0, double y0, double x1, double y1, double& fraction) const override;

 private:
  int velocity_;
  int position_;
  bool continuous_;
  std::unique_ptr<b2World> world_;
  std::vector<b2Body*> bodies_;  // per scene body; grouped bodies share one
};

}  // namespace rwd::bench
