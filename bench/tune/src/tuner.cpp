// SPDX-License-Identifier: MIT
#include "rewind/tune/tuner.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace rwd::tune {
namespace {

// The same values, NaN matching NaN: a fallen stack measures NaN every time.
bool same_values(const std::vector<Metric>& a, const std::vector<Metric>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const bool both_nan = std::isnan(a[i].value) && std::isnan(b[i].value);
    if (!both_nan && a[i].value != b[i].value) return false;
  }
  return true;
}

void judge(SettingRun& run, const Budget& budget) {
  budget.apply(run.metrics);
  run.pass = run.error.empty() && std::all_of(run.metrics.begin(), run.metrics.end(),
                                              [](const Metric& m) { return meets(m); });
  run.worst_overshoot =
      run.error.empty() ? worst_overshoot(run.metrics) : std::numeric_limits<double>::infinity();
}

// "pass", or the metric furthest over its limit.
std::string verdict(const SettingRun& run) {
  if (!run.error.empty()) return "error: " + run.error;
  if (run.pass) return "pass";
  const Metric* worst = nullptr;
  for (const Metric& m : run.metrics) {
    if (!meets(m) && (worst == nullptr || overshoot(m) > overshoot(*worst))) worst = &m;
  }
  std::ostringstream out;
  out << "FAIL";
  if (worst != nullptr) {
    // NaN is how a scene says it could not measure (a stack that fell).
    out << " (" << worst->name << " ";
    if (std::isnan(worst->value)) {
      out << "n/a";
    } else {
      out << std::setprecision(4) << worst->value << " " << worst->unit;
    }
    out << ")";
  }
  return out.str();
}

// Times the cheapest passing settings of the first pass (the finalists)
// and the default again, round-robin, and records which were timed.
template <class Say>
void retime(TuneTarget& target, const SweepPlan& plan, TuneResult& result, Say& say) {
  std::vector<size_t> passing;
  for (size_t i = 0; i < result.runs.size(); ++i) {
    if (result.runs[i].pass && result.runs[i].in_grid) passing.push_back(i);
  }
  std::sort(passing.begin(), passing.end(), [&](size_t a, size_t b) {
    return result.runs[a].ms_samples.front() < result.runs[b].ms_samples.front();
  });
  passing.resize(std::min<size_t>(passing.size(), static_cast<size_t>(plan.finalists)));
  std::vector<size_t>& timed = result.timed;
  timed = passing;
  if (std::find(timed.begin(), timed.end(), result.default_run) == timed.end()) {
    timed.push_back(result.default_run);
  }
  if (plan.repeats > 1) {
    say("rewind-tune: timing " + std::to_string(timed.size()) + " settings " +
        std::to_string(plan.repeats - 1) + " more times each");
  }
  for (int round = 1; round < plan.repeats; ++round) {
    for (size_t i : timed) {
      SettingRun& run = result.runs[i];
      const Measurement again = target.measure(run.setting);
      run.ms_samples.push_back(again.ms_per_step);
      std::vector<Metric> metrics = again.metrics;
      plan.budget.apply(metrics);
      if (!same_values(metrics, run.metrics)) result.repeatable = false;
    }
  }
  if (!result.repeatable) {
    say("rewind-tune: warning: a repeated run measured different errors (the step should be "
        "deterministic)");
  }
  for (SettingRun& run : result.runs) run.ms_per_step = median(run.ms_samples);
}

// The pick comes from the settings timed with repeats (a single run is too
// noisy to rank); without one, the closest setting of the grid.
void choose(TuneResult& result) {
  for (size_t i : result.timed) {
    const SettingRun& run = result.runs[i];
    if (!run.pass || !run.in_grid) continue;
    if (!result.pick || run.ms_per_step < result.runs[*result.pick].ms_per_step) result.pick = i;
  }
  if (result.pick) return;
  for (size_t i = 0; i < result.runs.size(); ++i) {
    const SettingRun& run = result.runs[i];
    if (!run.in_grid) continue;
    if (!result.closest) {
      result.closest = i;
      continue;
    }
    const SettingRun& best = result.runs[*result.closest];
    if (run.worst_overshoot < best.worst_overshoot ||
        (run.worst_overshoot == best.worst_overshoot && run.ms_per_step < best.ms_per_step)) {
      result.closest = i;
    }
  }
}

}  // namespace

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

Result<TuneResult> tune(TuneTarget& target, const SweepPlan& plan, std::ostream* progress) {
  auto say = [&](const std::string& line) {
    if (progress == nullptr) return;
    *progress << line << "\n";
    progress->flush();
  };
  auto measured = [](const SolverSetting& setting, const Measurement& m) {
    SettingRun run;
    run.setting = setting;
    run.ms_samples = {m.ms_per_step};
    run.metrics = m.metrics;
    run.error = m.error;
    return run;
  };

  // The default first: it is the baseline, and its metrics name what a
  // budget may set.
  const SolverSetting default_setting = target.default_setting();
  say("rewind-tune: default " + default_setting.label() + " ...");
  SettingRun baseline = measured(default_setting, target.measure(default_setting));
  baseline.is_default = true;
  if (!baseline.error.empty()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the default setting cannot run: " + baseline.error);
  }
  if (Status status = plan.budget.check_names(baseline.metrics); !status.ok()) return status;
  judge(baseline, plan.budget);

  TuneResult result;
  bool default_in_grid = false;
  const size_t total = plan.grid.size();
  for (size_t i = 0; i < total; ++i) {
    const SolverSetting& setting = plan.grid[i];
    std::ostringstream line;
    line << "[" << i + 1 << "/" << total << "] " << setting.label() << ": ";
    if (setting == default_setting) {
      default_in_grid = true;
      result.default_run = result.runs.size();
      result.runs.push_back(baseline);
    } else {
      result.runs.push_back(measured(setting, target.measure(setting)));
      judge(result.runs.back(), plan.budget);
    }
    const SettingRun& run = result.runs.back();
    line << std::setprecision(3) << run.ms_samples.front() << " ms/step, " << verdict(run)
         << (run.is_default ? " (default)" : "");
    say(line.str());
    if (run.pass) ++result.passing;
  }
  if (!default_in_grid) {
    baseline.in_grid = false;
    result.default_run = result.runs.size();
    result.runs.push_back(baseline);
  }

  retime(target, plan, result, say);
  choose(result);
  return result;
}

}  // namespace rwd::tune
