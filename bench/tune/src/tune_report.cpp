// SPDX-License-Identifier: MIT
#include "rewind/tune/tune_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>

#include "rewind/cli/json_text.h"
#include "rewind/tune/csv.h"

namespace rwd::tune {
namespace {

using cli::json_string;

std::string number(double v) {
  // NaN is how a scene says it could not measure (the overlaps of a stack
  // that fell), as in docs/BENCHMARKS.md.
  if (std::isnan(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string ratio_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string with_unit(double v, const std::string& unit) {
  return unit.empty() || std::isnan(v) ? number(v) : number(v) + " " + unit;
}

std::string bound_text(const Metric& m) {
  if (!has_limit(m)) return "no limit";
  return std::string(m.bound == Metric::Bound::kAtMost ? "at most " : "at least ") +
         with_unit(m.limit, m.unit);
}

std::string budget_source(const TuneTarget& target, const Budget& budget, const Metric& m) {
  if (budget.overrides(m.name)) return "user";
  if (!has_limit(m)) return "none";
  return target.kind();
}

std::string padded(std::string text, size_t width) {
  if (text.size() < width) text.resize(width, ' ');
  return text;
}

// The distinct values of one field over the grid, in ascending order.
template <class Field>
std::string axis(const SweepPlan& plan, Field field) {
  std::set<double> values;
  for (const SolverSetting& s : plan.grid) values.insert(static_cast<double>(field(s)));
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + number(v);
  return out;
}

std::string timing(const SettingRun& run) {
  const size_t n = run.ms_samples.size();
  return number(run.ms_per_step) + " ms/step" +
         (n > 1 ? " (median of " + std::to_string(n) + " runs)" : " (1 run)");
}

// True when the fastest run of one is no faster than the slowest of the
// other: the ordering of the medians is then not to be trusted.
bool overlap(const SettingRun& a, const SettingRun& b) {
  const auto [a_min, a_max] = std::minmax_element(a.ms_samples.begin(), a.ms_samples.end());
  const auto [b_min, b_max] = std::minmax_element(b.ms_samples.begin(), b.ms_samples.end());
  return *a_min <= *b_max && *b_min <= *a_max;
}

void print_metrics(const SettingRun& run, std::ostream& out) {
  for (const Metric& m : run.metrics) {
    out << "  " << padded(m.name, 24) << padded(with_unit(m.value, m.unit), 16)
        << padded(bound_text(m), 22) << (meets(m) ? "pass" : "FAIL") << "\n";
  }
}

std::string failing_metrics(const SettingRun& run) {
  std::string out;
  for (const Metric& m : run.metrics) {
    if (meets(m)) continue;
    out += (out.empty() ? "" : ", ") + m.name + " " + with_unit(m.value, m.unit) + " (" +
           bound_text(m) + ")";
  }
  return out;
}

// JSON ---------------------------------------------------------------------

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string csv_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return json_number(v);
}

std::string json_setting(const SettingRun& run) {
  std::ostringstream out;
  out << "{\"substeps\":" << run.setting.substeps
      << ",\"relax_iterations\":" << run.setting.relax_iterations
      << ",\"contact_hertz\":" << json_number(run.setting.contact_hertz)
      << ",\"label\":" << json_string(run.setting.label())
      << ",\"ms_per_step\":" << json_number(run.ms_per_step)
      << ",\"timing_runs\":" << run.ms_samples.size()
      << ",\"pass\":" << (run.pass ? "true" : "false") << ",\"metrics\":[";
  for (size_t i = 0; i < run.metrics.size(); ++i) {
    const Metric& m = run.metrics[i];
    out << (i ? "," : "") << "{\"name\":" << json_string(m.name)
        << ",\"unit\":" << json_string(m.unit) << ",\"value\":" << json_number(m.value)
        << ",\"bound\":" << (m.bound == Metric::Bound::kAtMost ? "\"at_most\"" : "\"at_least\"")
        << ",\"limit\":" << json_number(m.limit) << ",\"pass\":" << (meets(m) ? "true" : "false")
        << "}";
  }
  out << "]}";
  return out.str();
}

}  // namespace

int exit_code(const TuneResult& result) {
  return result.pick ? kExitFound : kExitNonePasses;
}

void print_text(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
                std::ostream& out) {
  const SettingRun& base = result.default_setting();
  out << "rewind-tune: " << target.description() << "\n";
  out << "grid: " << plan.grid.size() << " settings (substeps "
      << axis(plan, [](const SolverSetting& s) { return s.substeps; }) << "; relax "
      << axis(plan, [](const SolverSetting& s) { return s.relax_iterations; }) << "; hertz "
      << axis(plan, [](const SolverSetting& s) { return s.contact_hertz; }) << "), "
      << result.passing << " meet the budget\n";
  out << "budget:\n";
  for (const Metric& m : base.metrics) {
    const std::string source = budget_source(target, plan.budget, m);
    out << "  " << padded(m.name, 24) << padded(bound_text(m), 22)
        << (source == "user"   ? "(--budget)"
            : source == "none" ? "(reported only)"
                               : "(" + source + " default)")
        << "\n";
  }
  out << "\n";

  const std::string default_verdict =
      base.pass ? "meets the budget" : "does not meet the budget: " + failing_metrics(base);
  if (result.pick) {
    const SettingRun& pick = result.runs[*result.pick];
    out << "pick:     " << padded(pick.setting.label(), 30) << timing(pick) << "\n";
    out << "default:  " << padded(base.setting.label(), 30) << timing(base) << ", "
        << default_verdict << "\n";
    if (*result.pick == result.default_run) {
      out << "cost:     the pick is the default setting\n";
    } else if (base.ms_per_step > 0.0 && pick.ms_per_step > 0.0) {
      const double ratio = pick.ms_per_step / base.ms_per_step;
      out << "cost:     the pick takes " << ratio_text(ratio) << "x the default's time per step";
      if (ratio < 1.0) out << " (" << ratio_text(1.0 / ratio) << "x cheaper)";
      out << "\n";
      if (overlap(pick, base)) {
        out << "          (their timed runs overlap: on this machine the difference is within "
               "the noise)\n";
      }
    }
    out << "\nmetrics at the pick:\n";
    print_metrics(pick, out);
    out << "\nset in WorldConfig: substeps = " << pick.setting.substeps
        << ", relax_iterations = " << pick.setting.relax_iterations
        << ", contact_hertz = " << number(pick.setting.contact_hertz) << "\n";
  } else {
    out << "no setting of the " << plan.grid.size() << " meets the budget\n";
    if (result.closest) {
      const SettingRun& closest = result.runs[*result.closest];
      out << "closest:  " << padded(closest.setting.label(), 30) << timing(closest) << ", misses "
          << failing_metrics(closest) << "\n";
    }
    out << "default:  " << padded(base.setting.label(), 30) << timing(base) << ", "
        << default_verdict << "\n";
    if (result.closest) {
      out << "\nmetrics at the closest setting:\n";
      print_metrics(result.runs[*result.closest], out);
    }
  }
  if (!result.repeatable) {
    out << "\nwarning: a repeated run measured different errors; the step should be "
           "deterministic\n";
  }
}

void print_json(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
                std::ostream& out) {
  const SettingRun& base = result.default_setting();
  out << "{\"target\":{\"kind\":" << json_string(target.kind())
      << ",\"name\":" << json_string(target.name()) << ",\"size\":" << target.size()
      << ",\"ticks\":" << target.ticks() << ",\"description\":" << json_string(target.description())
      << "},\"grid_settings\":" << plan.grid.size() << ",\"passing\":" << result.passing
      << ",\"budget\":[";
  for (size_t i = 0; i < base.metrics.size(); ++i) {
    const Metric& m = base.metrics[i];
    out << (i ? "," : "") << "{\"metric\":" << json_string(m.name)
        << ",\"unit\":" << json_string(m.unit)
        << ",\"bound\":" << (m.bound == Metric::Bound::kAtMost ? "\"at_most\"" : "\"at_least\"")
        << ",\"limit\":" << json_number(m.limit)
        << ",\"source\":" << json_string(budget_source(target, plan.budget, m))
        << ",\"criterion\":" << json_string(m.criterion) << "}";
  }
  out << "],\"outcome\":" << (result.pick ? "\"found\"" : "\"none_passes\"")
      << ",\"exit_code\":" << exit_code(result);
  out << ",\"pick\":" << (result.pick ? json_setting(result.runs[*result.pick]) : "null");
  out << ",\"default\":" << json_setting(base);
  out << ",\"closest\":" << (result.closest ? json_setting(result.runs[*result.closest]) : "null");
  double ratio = std::nan("");
  if (result.pick && base.ms_per_step > 0.0) {
    ratio = result.runs[*result.pick].ms_per_step / base.ms_per_step;
  }
  const bool noise =
      result.pick && *result.pick != result.default_run && overlap(result.runs[*result.pick], base);
  out << ",\"pick_cost_ratio\":" << json_number(ratio)
      << ",\"within_noise\":" << (noise ? "true" : "false")
      << ",\"repeatable\":" << (result.repeatable ? "true" : "false") << "}\n";
}

void write_csv(const TuneTarget& target, const SweepPlan& plan, const TuneResult& result,
               std::ostream& out) {
  out << "kind,name,size,settings,substeps,relax,hertz,ms_per_step,timing_runs,metric,unit,value,"
         "bound,limit,budget,pass,setting_pass,default,pick,criterion\n";
  for (size_t i = 0; i < result.runs.size(); ++i) {
    const SettingRun& run = result.runs[i];
    std::ostringstream head;
    head << target.kind() << "," << target.name() << "," << target.size() << ","
         << run.setting.label() << "," << run.setting.substeps << ","
         << run.setting.relax_iterations << "," << number(run.setting.contact_hertz) << ","
         << json_number(run.ms_per_step) << "," << run.ms_samples.size() << ",";
    const std::string tail = std::string(",") + (run.pass ? "1" : "0") + "," +
                             (run.is_default ? "1" : "0") + "," + (result.pick == i ? "1" : "0") +
                             ",";
    if (!run.error.empty()) {
      out << head.str() << "error,,,,,,0" << tail << csv_quoted(run.error) << "\n";
      continue;
    }
    for (const Metric& m : run.metrics) {
      out << head.str() << m.name << "," << m.unit << "," << csv_number(m.value) << ","
          << (m.bound == Metric::Bound::kAtMost ? "at_most" : "at_least") << ","
          << (has_limit(m) ? json_number(m.limit) : "") << ","
          << budget_source(target, plan.budget, m) << "," << (meets(m) ? "1" : "0") << tail
          << csv_quoted(m.criterion) << "\n";
    }
  }
}

}  // namespace rwd::tune
