// SPDX-License-Identifier: MIT
#include "run2d.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rwd::bench {

namespace {

double distance(const Pose2D& a, const Pose2D& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

void measure(const Scene2D& scene, const Engine2D& engine, const std::vector<Pose2D>& start,
             Run2DResult& r) {
  for (uint32_t top : scene.tops) {
    r.top_drift_m = std::max(r.top_drift_m, distance(engine.pose(top), start[top]));
  }
  if (scene.report_displacement) {
    for (uint32_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].kind != Kind2D::kDynamic) continue;
      r.max_displacement_m = std::max(r.max_displacement_m, distance(engine.pose(i), start[i]));
    }
  }
  for (const RevoluteDesc2D& j : scene.joints) {
    const double rest = distance(start[j.a], start[j.b]);
    r.max_stretch_m =
        std::max(r.max_stretch_m, distance(engine.pose(j.a), engine.pose(j.b)) - rest);
  }
  if (scene.container_wall >= 0) {
    // Into the container's frame: about its pivot, by the wall's angle.
    const Pose2D pivot = engine.pose(static_cast<uint32_t>(scene.container_wall));
    const double c = std::cos(pivot.angle), s = std::sin(pivot.angle);
    const double half = scene.container_half / 1000.0;
    for (uint32_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].kind != Kind2D::kDynamic) continue;
      const Pose2D p = engine.pose(i);
      const double dx = p.x - pivot.x, dy = p.y - pivot.y;
      const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
      if (std::abs(lx) > half || std::abs(ly) > half) ++r.escaped;
    }
  }
}

}  // namespace

std::vector<Run2DResult> run_lockstep(const Scene2D& scene,
                                      const std::vector<std::unique_ptr<Engine2D>>& engines) {
  using Clock = std::chrono::steady_clock;
  const size_t n = engines.size();
  std::vector<Run2DResult> results(n);
  std::vector<std::vector<Pose2D>> start(n);
  for (size_t e = 0; e < n; ++e) {
    if (!engines[e]->build(scene, results[e].error)) continue;
    for (uint32_t i = 0; i < scene.bodies.size(); ++i) start[e].push_back(engines[e]->pose(i));
  }
  std::vector<double> seconds(n, 0.0);
  const int total = scene.warmup_ticks + scene.timed_ticks;
  for (int tick = 0; tick < total; tick += kBlockTicks) {
    const int block = std::min(kBlockTicks, total - tick);
    for (size_t e = 0; e < n; ++e) {
      if (!results[e].error.empty()) continue;
      for (int k = 0; k < block; ++k) {
        const bool timed = tick + k >= scene.warmup_ticks;
        const auto t0 = Clock::now();
        engines[e]->step();
        if (timed) seconds[e] += std::chrono::duration<double>(Clock::now() - t0).count();
        if (timed) {  // outside the timing: poses of the few top boxes
          for (uint32_t top : scene.tops) {
            results[e].top_peak_m =
                std::max(results[e].top_peak_m, distance(engines[e]->pose(top), start[e][top]));
          }
        }
      }
    }
  }
  for (size_t e = 0; e < n; ++e) {
    if (!results[e].error.empty()) continue;
    results[e].ms_per_step = 1000.0 * seconds[e] / std::max(1, scene.timed_ticks);
    measure(scene, *engines[e], start[e], results[e]);
  }
  return results;
}

}  // namespace rwd::bench
