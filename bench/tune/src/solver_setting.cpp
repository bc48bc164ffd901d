// SPDX-License-Identifier: MIT
#include "rewind/tune/solver_setting.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <tuple>

namespace rwd::tune {
namespace {

// The range World3D::validate_config() accepts.
constexpr double kMinHertz = 1e-3;
constexpr double kMaxHertz = 1e4;

// Splits "a,b,c" into its items; an empty item is kept so that "1,,2" is
// reported rather than read as "1,2".
std::vector<std::string> split_commas(std::string_view text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    items.emplace_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return items;
}

}  // namespace

SolverSetting SolverSetting::of(const sim::WorldConfig& config) {
  return {config.substeps, config.relax_iterations, config.contact_hertz};
}

sim::WorldConfig SolverSetting::applied_to(sim::WorldConfig base) const {
  base.substeps = substeps;
  base.relax_iterations = relax_iterations;
  base.contact_hertz = contact_hertz;
  return base;
}

std::string SolverSetting::label() const {
  std::ostringstream out;
  out << "substeps=" << substeps << " relax=" << relax_iterations << " hertz=" << contact_hertz;
  return out.str();
}

SettingGrid SettingGrid::standard() {
  return {{4, 5, 6, 8, 12, 16}, {0, 1, 2, 4}, {15.0f, 30.0f, 60.0f, 120.0f}};
}

SettingGrid SettingGrid::quick() {
  return {{4, 6, 8}, {0, 1}, {30.0f}};
}

std::vector<SolverSetting> SettingGrid::settings() const {
  std::vector<SolverSetting> out;
  for (int32_t s : substeps) {
    for (int32_t r : relax_iterations) {
      for (float hz : contact_hertz) {
        const SolverSetting setting{s, r, hz};
        if (std::find(out.begin(), out.end(), setting) == out.end()) out.push_back(setting);
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const SolverSetting& a, const SolverSetting& b) {
    return std::make_tuple(a.work(), a.substeps, a.relax_iterations, a.contact_hertz) <
           std::make_tuple(b.work(), b.substeps, b.relax_iterations, b.contact_hertz);
  });
  return out;
}

Result<std::vector<int32_t>> parse_int_list(std::string_view text, int32_t min, int32_t max) {
  std::vector<int32_t> values;
  for (const std::string& item : split_commas(text)) {
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || errno != 0 || *end != '\0') {
      return Status::Error(
          ErrorCode::kInvalidArgument,
          "expected integers separated by commas, got '" + std::string(text) + "'");
    }
    if (v < min || v > max) {
      return Status::Error(
          ErrorCode::kInvalidArgument,
          item + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    values.push_back(static_cast<int32_t>(v));
  }
  return values;
}

Result<std::vector<float>> parse_hertz_list(std::string_view text) {
  std::vector<float> values;
  for (const std::string& item : split_commas(text)) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || errno != 0 || *end != '\0' || !std::isfinite(v)) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "expected numbers separated by commas, got '" + std::string(text) + "'");
    }
    if (v < kMinHertz || v > kMaxHertz) {
      return Status::Error(ErrorCode::kInvalidArgument, item + " is outside [0.001, 10000]");
    }
    values.push_back(static_cast<float>(v));
  }
  return values;
}

}  // namespace rwd::tune
