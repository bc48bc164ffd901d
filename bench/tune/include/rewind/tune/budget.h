// SPDX-License-Identifier: MIT
#pragma once
// The error budget a setting must meet: each metric's own limit (a scene's
// criterion, or a game metric's default) unless the user replaced it with
// --budget NAME=LIMIT. The bound keeps its direction: an "at most" metric
// stays at most, in the metric's own unit.
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/scenes/scene.h"

namespace rwd::tune {

using scenes::Metric;

class Budget {
 public:
  /// Adds "NAME=LIMIT" (LIMIT a finite number in the metric's unit). A
  /// later limit for the same name replaces an earlier one.
  /// kInvalidArgument for text that is not of that form.
  Status add(std::string_view text);

  /// kInvalidArgument naming any limit whose metric is not in `metrics`,
  /// with the names that are.
  Status check_names(const std::vector<Metric>& metrics) const;
  /// Replaces the limit of every metric the user set.
  void apply(std::vector<Metric>& metrics) const;
  /// True when the user set this metric's limit.
  bool overrides(std::string_view metric) const;
  bool empty() const { return limits_.empty(); }

 private:
  struct Limit {
    std::string metric;
    double value = 0.0;
  };
  std::vector<Limit> limits_;
};

/// True when the metric has a limit at all (game metrics reported for
/// information carry an infinite one).
bool has_limit(const Metric& metric);

/// True when the metric meets its limit, or has none.
bool meets(const Metric& metric);

/// How far a metric is from its limit, relative to the limit's size (to 1
/// in the metric's unit when the limit is 0): negative or 0 when it passes,
/// 0.5 when an "at most" value is 50% over, +infinity when the value is
/// not a number (a scene that fell over measures NaN).
double overshoot(const Metric& metric);

/// The largest overshoot() of `metrics`: the metric furthest from passing.
double worst_overshoot(const std::vector<Metric>& metrics);

}  // namespace rwd::tune
