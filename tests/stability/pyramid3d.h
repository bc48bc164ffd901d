// SPDX-License-Identifier: MIT
#pragma once
// The catalogue's base-N box pyramid (rewind/scenes) on Rewind at a given
// substep count and tick rate, sleep off so that the solver itself is
// measured rather than a sleeping island: how fast the fastest box moves
// once the pyramid has settled, and when (if ever) a box first moves at
// 1 m/s after the first second, the sign that it is falling apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace rwd::scenes::test {

struct PyramidRun {
  float settled_max_speed = 0.0f;  ///< m/s, fastest box from `settle_s` to the end
  float falling_at_s = -1.0f;      ///< first time after 1 s a box moves at 1 m/s; -1: never
  std::string error;
};

inline PyramidRun run_pyramid(int base, int substeps, float seconds, float settle_s = 2.0f,
                              int ticks_per_second = 60) {
  PyramidRun out;
  auto scene = make_scene("pyramid", base);
  if (!scene) {
    out.error = "no pyramid of base " + std::to_string(base);
    return out;
  }
  sim::WorldConfig config;
  config.substeps = substeps;
  config.enable_sleep = false;
  RewindEngine engine(config);
  WorldSpec world = scene->world();
  world.tick_seconds = 1.0f / static_cast<float>(ticks_per_second);
  engine.reset(world, scene->body_capacity());
  if (!scene->build(engine, out.error)) return out;
  const int ticks = static_cast<int>(seconds * static_cast<float>(ticks_per_second) + 0.5f);
  const int settle = static_cast<int>(settle_s * static_cast<float>(ticks_per_second) + 0.5f);
  for (int t = 0; t < ticks; ++t) {
    engine.step();
    float fastest = 0.0f;
    for (BodyHandle b = 0; b < scene->body_capacity(); ++b) {
      float v = sim::length(engine.linear_velocity(b));
      if (std::isnan(v)) v = 1e9f;  // a NaN speed counts as falling apart
      if (v > fastest) fastest = v;
    }
    if (t >= settle && fastest > out.settled_max_speed) out.settled_max_speed = fastest;
    if (t >= ticks_per_second && fastest > 1.0f && out.falling_at_s < 0.0f) {
      out.falling_at_s = static_cast<float>(t + 1) / static_cast<float>(ticks_per_second);
    }
  }
  return out;
}

inline void report_pyramid(int base, int substeps, int ticks_per_second, const PyramidRun& r) {
  std::printf("[ measured ] pyramid %d, substeps %d at %d Hz ticks: settled max speed %g m/s, ",
              base, substeps, ticks_per_second, static_cast<double>(r.settled_max_speed));
  if (r.falling_at_s < 0.0f) {
    std::printf("standing\n");
  } else {
    std::printf("falling apart at %g s\n", static_cast<double>(r.falling_at_s));
  }
}

}  // namespace rwd::scenes::test
