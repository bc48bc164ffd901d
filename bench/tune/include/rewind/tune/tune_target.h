// SPDX-License-Identifier: MIT
#pragma once
// What rewind-tune tunes: a built-in scene or a built-in game, behind one
// interface so the sweep, the pick and the reports do not care which.
#include <string>
#include <vector>

#include "rewind/core/tick.h"
#include "rewind/scenes/scene.h"
#include "rewind/tune/solver_setting.h"

namespace rwd::tune {

/// One run of a target at one setting.
struct Measurement {
  /// Wall time per tick of the timed part of the run, milliseconds.
  double ms_per_step = 0.0;
  /// Errors with the target's own limits (before the user's budget).
  std::vector<scenes::Metric> metrics;
  /// Non-empty when the run could not be made (a scene the engine refused).
  std::string error;
};

class TuneTarget {
 public:
  virtual ~TuneTarget() = default;
  /// "scene" or "game".
  virtual std::string kind() const = 0;
  /// Catalogue or registry name, e.g. "stack", "crates".
  virtual std::string name() const = 0;
  /// The scene's size, or the game's player count.
  virtual int size() const = 0;
  /// One line saying what is run and what is measured, for reports.
  virtual std::string description() const = 0;
  /// The setting the scene or game runs with when nobody tunes it.
  virtual SolverSetting default_setting() const = 0;
  /// Ticks a measured run steps (for progress and reports).
  virtual Tick ticks() const = 0;
  /// Runs once at `setting`. Metrics are deterministic (the same setting
  /// gives the same values); only the time varies from run to run.
  virtual Measurement measure(const SolverSetting& setting) = 0;
};

}  // namespace rwd::tune
