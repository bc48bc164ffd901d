// SPDX-License-Identifier: MIT
#pragma once
// Steps one scene on several engines in the same process, taking turns in
// short blocks of ticks, so that a noisy shared machine slows every engine
// alike and their ratio stays meaningful. Measures each engine's ms/step
// and the scene's accuracy figures.
#include <memory>
#include <string>
#include <vector>

#include "engine2d.h"
#include "scene2d.h"

namespace rwd::bench {

struct Run2DResult {
  double ms_per_step = 0;  ///< mean wall time of step() over the timed ticks
  /// Pyramids: the largest distance (m) of a top box from where it started,
  /// after warm-up and timed ticks.
  double top_drift_m = 0;
  /// Pyramids: the largest distance (m) of a top box from its start at any
  /// timed tick. A tall pyramid sways and breathes; this catches the
  /// extremes, which the end pose alone may miss.
  double top_peak_m = 0;
  /// Pyramids: the largest distance (m) of any dynamic box from its start.
  double max_displacement_m = 0;
  /// Joint grid and rain: the widest opening (m) of a joint at the end:
  /// the distance between its anchor as each of its two bodies carries it
  /// (0 for a joint that holds).
  double max_opening_m = 0;
  /// Tumbler: dynamic boxes whose centre left the container; rain: ragdoll
  /// parts below the lowest floor (y < -1 m) at the end.
  int escaped = 0;
  uint64_t checksum = 0;  ///< Engine2D::checksum() at the end
  std::string error;      ///< non-empty: the engine refused the scene
};

/// Ticks each engine takes before the next one steps.
inline constexpr int kBlockTicks = 10;

/// Builds `scene` on every engine and runs them in turns of kBlockTicks.
std::vector<Run2DResult> run_lockstep(const Scene2D& scene,
                                      const std::vector<std::unique_ptr<Engine2D>>& engines);

}  // namespace rwd::bench
