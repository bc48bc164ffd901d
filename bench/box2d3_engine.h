// SPDX-License-Identifier: MIT
#pragma once
// Box2D v3 (an optional source tree, REWIND_BOX2D3_DIR) behind the Engine2D
// interface, for side-by-side measurements. Box2D v3's headers share their
// names with Box2D 2.4's (<box2d/box2d.h>), so this header includes neither:
// the world lives behind a pointer to a type only box2d3_engine.cpp knows,
// and that file alone sees Box2D v3's include directory.
#include <memory>

#include "engine2d.h"

namespace rwd::bench {

class Box2D3Engine final : public Engine2D {
 public:
  /// b2World_Step's substep count (Box2D v3's recommended 4).
  explicit Box2D3Engine(int substeps);
  ~Box2D3Engine() override;
  Box2D3Engine(const Box2D3Engine&) = delete;
  Box2D3Engine& operator=(const Box2D3Engine&) = delete;

  std::string name() const override { return "box2d3"; }
  std::string settings() const override;
  bool is_default() const override { return substeps_ == 4; }
  bool build(const Scene2D& scene, std::string& error) override;
  bool add_wave(const Scene2D& scene, uint32_t wave, std::string& error) override;
  void remove_wave(uint32_t wave) override;
  void step() override;
  Pose2D pose(uint32_t index) const override;
  Pose2D wave_pose(uint32_t wave, uint32_t index) const override;
  bool raycast(double x0, double y0, double x1, double y1, double& fraction) const override;

 private:
  struct World;  // the b2WorldId and the scene's b2BodyIds
  int substeps_;
  std::unique_ptr<World> world_;
};

}  // namespace rwd::bench
