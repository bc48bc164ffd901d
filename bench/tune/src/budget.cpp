// SPDX-License-Identifier: MIT
#include "rewind/tune/budget.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace rwd::tune {

Status Budget::add(std::string_view text) {
  const size_t eq = text.find('=');
  auto bad = [&](const std::string& why) {
    return Status::Error(ErrorCode::kInvalidArgument, "--budget: expected METRIC=LIMIT, " + why +
                                                          " in '" + std::string(text) + "'");
  };
  if (eq == std::string_view::npos) return bad("no '='");
  const std::string name(text.substr(0, eq));
  const std::string number(text.substr(eq + 1));
  if (name.empty()) return bad("no metric name");
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || errno != 0 || *end != '\0' || !std::isfinite(value)) {
    return bad("LIMIT must be a finite number");
  }
  for (Limit& l : limits_) {
    if (l.metric == name) {
      l.value = value;
      return Status::Ok();
    }
  }
  limits_.push_back({name, value});
  return Status::Ok();
}

Status Budget::check_names(const std::vector<Metric>& metrics) const {
  for (const Limit& l : limits_) {
    const bool known = std::any_of(metrics.begin(), metrics.end(),
                                   [&](const Metric& m) { return m.name == l.metric; });
    if (known) continue;
    std::string names;
    for (const Metric& m : metrics) {
      if (!names.empty()) names += ", ";
      names += m.name + " (" + m.unit + ")";
    }
    return Status::Error(ErrorCode::kInvalidArgument,
                         "--budget: no metric '" + l.metric + "'; this one has " + names);
  }
  return Status::Ok();
}

void Budget::apply(std::vector<Metric>& metrics) const {
  for (Metric& m : metrics) {
    for (const Limit& l : limits_) {
      if (l.metric == m.name) m.limit = l.value;
    }
  }
}

bool Budget::overrides(std::string_view metric) const {
  return std::any_of(limits_.begin(), limits_.end(),
                     [&](const Limit& l) { return l.metric == metric; });
}

bool has_limit(const Metric& metric) {
  return std::isfinite(metric.limit);
}

bool meets(const Metric& metric) {
  return !has_limit(metric) || metric.pass();
}

double overshoot(const Metric& metric) {
  if (!has_limit(metric)) return -std::numeric_limits<double>::infinity();
  if (std::isnan(metric.value)) return std::numeric_limits<double>::infinity();
  const double scale = metric.limit != 0.0 ? std::fabs(metric.limit) : 1.0;
  const double excess = metric.bound == Metric::Bound::kAtMost ? metric.value - metric.limit
                                                               : metric.limit - metric.value;
  return excess / scale;
}

double worst_overshoot(const std::vector<Metric>& metrics) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const Metric& m : metrics) worst = std::max(worst, overshoot(m));
  return worst;
}

}  // namespace rwd::tune
