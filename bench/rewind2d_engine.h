// SPDX-License-Identifier: MIT
#pragma once
// Rewind's 2D lane (fixed point) behind the Engine2D interface.
#include <memory>
#include <vector>

#include "engine2d.h"
#include "rewind/core/thread_pool.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::bench {

class Rewind2DEngine final : public Engine2D {
 public:
  /// Substeps and relax iterations of World2DConfig; the rest stays
  /// default. With `threads` above 1 the world collides its pairs on a pool
  /// of that many threads (World2D::set_thread_pool: the same results).
  Rewind2DEngine(int substeps, int relax_iterations, uint32_t threads = 1);

  std::string name() const override { return "rewind"; }
  std::string settings() const override;
  bool is_default() const override;
  bool build(const Scene2D& scene, std::string& error) override;
  bool add_wave(const Scene2D& scene, uint32_t wave, std::string& error) override;
  void remove_wave(uint32_t wave) override;
  void step() override { world_->step(); }
  Pose2D pose(uint32_t index) const override;
  Pose2D wave_pose(uint32_t wave, uint32_t index) const override {
    return pose_of(wave_ids_[wave][index]);
  }
  uint64_t checksum() const override { return world_->checksum(); }
  bool raycast(double x0, double y0, double x1, double y1, double& fraction) const override;

 private:
  Pose2D pose_of(sim2d::BodyId2D id) const;
  // Creates the bodies and joints; false with `error` set on a refusal.
  bool add(const Scene2D& scene, const std::vector<BodyDesc2D>& bodies,
           const std::vector<RevoluteDesc2D>& joints, std::vector<sim2d::BodyId2D>& ids,
           std::string& error);

  sim2d::World2DConfig config_;
  std::unique_ptr<rwd::ThreadPool> pool_;  // null: one thread; outlives world_
  std::unique_ptr<sim2d::World2D> world_;
  std::vector<sim2d::BodyId2D> ids_;
  std::vector<std::vector<sim2d::BodyId2D>> wave_ids_;  // per wave added
};

}  // namespace rwd::bench
