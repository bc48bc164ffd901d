// SPDX-License-Identifier: MIT
#pragma once
// The sweep: run a target at every setting of a grid, keep what meets the
// budget, and pick the cheapest of those by measured time. Errors are
// deterministic but times are not (shared machines, caches, frequency
// scaling), so the cheapest passing settings of the first pass and the
// default are timed again, round-robin so that a slow spell hits them
// alike, and the pick is the lowest median.
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/tune/budget.h"
#include "rewind/tune/solver_setting.h"
#include "rewind/tune/tune_target.h"

namespace rwd::tune {

struct SweepPlan {
  std::vector<SolverSetting> grid;  ///< in the order to run them
  Budget budget;
  int finalists = 5;  ///< cheapest passing settings of the first pass timed again, >= 1
  int repeats = 5;    ///< timed runs of each finalist and of the default, >= 1
};

/// Everything measured at one setting.
struct SettingRun {
  SolverSetting setting;
  bool is_default = false;
  bool in_grid = true;             ///< false for the default setting when the grid lacks it
  std::vector<double> ms_samples;  ///< one per timed run, ms per tick
  double ms_per_step = 0.0;        ///< median of ms_samples
  std::vector<Metric> metrics;     ///< with the budget's limits
  std::string error;               ///< the run could not be made
  bool pass = false;               ///< no error, and every metric meets its limit
  double worst_overshoot = 0.0;    ///< see overshoot(); <= 0 when passing
};

struct TuneResult {
  /// The grid in sweep order, then the default setting if the grid lacks it.
  std::vector<SettingRun> runs;
  size_t default_run = 0;
  /// The cheapest passing setting, if any passes.
  std::optional<size_t> pick;
  /// When none passes: the setting whose worst metric is nearest its limit.
  std::optional<size_t> closest;
  size_t passing = 0;  ///< passing settings of the grid
  /// The runs timed `repeats` times: the finalists and the default.
  std::vector<size_t> timed;
  /// False if a repeated run measured other metric values than the first
  /// (the step is deterministic, so this would be a bug worth reporting).
  bool repeatable = true;

  const SettingRun& default_setting() const { return runs[default_run]; }
};

/// Runs the sweep. The default setting runs first, so that a --budget
/// naming a metric the target does not have is refused (kInvalidArgument,
/// listing the metrics) before the long part. Progress lines go to
/// `progress` when it is non-null.
Result<TuneResult> tune(TuneTarget& target, const SweepPlan& plan, std::ostream* progress);

/// The median of `values` (the mean of the middle two for an even count); 0
/// for none.
double median(std::vector<double> values);

}  // namespace rwd::tune
