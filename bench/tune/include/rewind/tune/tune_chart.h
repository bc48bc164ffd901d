// SPDX-License-Identifier: MIT
#pragma once
// The error-against-cost chart of a sweep, drawn by gnuplot (gnuplot-nox,
// as for scripts/charts.sh): one panel per metric, each setting a point at
// its ms/step, the budget as a dashed line, the default and the pick marked.
#include <string>

#include "rewind/core/status.h"
#include "rewind/tune/tuner.h"

namespace rwd::tune {

/// True when a gnuplot executable is on PATH.
bool gnuplot_available();

/// The gnuplot script that draws `result` into `svg_path`.
std::string chart_script(const TuneTarget& target, const TuneResult& result,
                         const std::string& svg_path);

/// Runs gnuplot on chart_script(). kIo when gnuplot cannot be started or
/// fails (its own message goes to stderr).
Status write_chart(const TuneTarget& target, const TuneResult& result, const std::string& svg_path);

}  // namespace rwd::tune
