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

// Where a pose puts a point given in the world at `made` (the body's
// pose when the joint was made).
void carry(const Pose2D& made, const Pose2D& now, double x, double y, double& ox, double& oy) {
  const double lx0 = x - made.x, ly0 = y - made.y;
  const double c0 = std::cos(made.angle), s0 = std::sin(made.angle);
  const double lx = c0 * lx0 + s0 * ly0, ly = -s0 * lx0 + c0 * ly0;
  const double c = std::cos(now.angle), s = std::sin(now.angle);
  ox = now.x + c * lx - s * ly;
  oy = now.y + s * lx + c * ly;
}

// A joint's opening: the distance between its anchor as body a carries it
// and as body b carries it (0 for a joint that holds).
double opening(const RevoluteDesc2D& j, const Pose2D& made_a, const Pose2D& made_b,
               const Pose2D& now_a, const Pose2D& now_b) {
  double ax = 0, ay = 0, bx = 0, by = 0;
  carry(made_a, now_a, j.x / 1000.0, j.y / 1000.0, ax, ay);
  carry(made_b, now_b, j.x / 1000.0, j.y / 1000.0, bx, by);
  return std::hypot(ax - bx, ay - by);
}

// `ticks`: how many ticks ran (the waves before them were added).
void measure(const Scene2D& scene, const Engine2D& engine, const std::vector<Pose2D>& start,
             int ticks, Run2DResult& r) {
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
    r.max_opening_m = std::max(
        r.max_opening_m, opening(j, start[j.a], start[j.b], engine.pose(j.a), engine.pose(j.b)));
  }
  // The waves still in the world: their joints' opening, and their bodies
  // that fell below the scene (y < -1 m: through the lowest floor).
  std::vector<bool> live(scene.waves.size(), false);
  for (uint32_t w = 0; w < scene.waves.size() && scene.waves[w].tick < ticks; ++w) {
    live[w] = true;
    for (uint32_t gone : scene.waves[w].removes) live[gone] = false;
  }
  for (uint32_t w = 0; w < scene.waves.size(); ++w) {
    if (!live[w]) continue;
    const Wave2D& wave = scene.waves[w];
    auto made = [&wave](uint32_t i) {
      return Pose2D{wave.bodies[i].x / 1000.0, wave.bodies[i].y / 1000.0, 0.0};
    };
    for (const RevoluteDesc2D& j : wave.joints) {
      r.max_opening_m = std::max(
          r.max_opening_m,
          opening(j, made(j.a), made(j.b), engine.wave_pose(w, j.a), engine.wave_pose(w, j.b)));
    }
    for (uint32_t i = 0; i < wave.bodies.size(); ++i) {
      if (wave.bodies[i].kind == Kind2D::kDynamic && engine.wave_pose(w, i).y < -1.0) ++r.escaped;
    }
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
  std::vector<uint32_t> next_wave(n, 0);
  const int total = scene.warmup_ticks + scene.timed_ticks;
  for (int tick = 0; tick < total; tick += kBlockTicks) {
    const int block = std::min(kBlockTicks, total - tick);
    for (size_t e = 0; e < n; ++e) {
      if (!results[e].error.empty()) continue;
      for (int k = 0; k < block; ++k) {
        const bool timed = tick + k >= scene.warmup_ticks;
        const auto t0 = Clock::now();
        // A wave's removals and additions count as the tick's work, as in
        // Box2D's rain benchmark.
        uint32_t& w = next_wave[e];
        for (; w < scene.waves.size() && scene.waves[w].tick <= tick + k; ++w) {
          for (uint32_t r : scene.waves[w].removes) engines[e]->remove_wave(r);
          if (!engines[e]->add_wave(scene, w, results[e].error)) break;
        }
        if (!results[e].error.empty()) break;
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
    measure(scene, *engines[e], start[e], total, results[e]);
    results[e].checksum = engines[e]->checksum();
  }
  return results;
}

}  // namespace rwd::bench
