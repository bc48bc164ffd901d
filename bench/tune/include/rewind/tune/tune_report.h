// SPDX-License-Identifier: MIT
#pragma once
// What rewind-tune prints: the human report, the same facts as one JSON
// object, and the whole sweep as CSV (one row per setting and metric).
#include <ostream>

#include "rewind/tune/tuner.h"

namespace rwd::tune {

/// Exit codes of rewind-tune.
inline constexpr int kExitFound = 0;       ///< a setting meets the budget
inline constexpr int kExitNonePasses = 1;  ///< no setting of the grid does
inline constexpr int kExitUsage = 2;       ///< bad flags, names, values or output paths
inline constexpr int kExitOutputFailed =
    3;  ///< the sweep ran but the CSV or chart could not be written

int exit_code(const TuneResult& result);

/// The report: target, grid, budget, the pick (or the closest setting),
/// the default's cost and the ratio, every metric at the pick, and the
/// WorldConfig fields to set.
void print_text(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
                std::ostream& out);
/// The same as one JSON object on one line; NaN and unlimited limits are
/// null. within_noise: the pick's and the default's timed runs overlap.
void print_json(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
                std::ostream& out);
/// Header and one row per (setting, metric); a setting that could not run
/// has one row with metric "error".
void write_csv(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
               std::ostream& out);

}  // namespace rwd::tune
