// SPDX-License-Identifier: MIT
// The 3D lane's world config as readable text, for replay tools.
#include <charconv>
#include <cstdio>
#include <cstdlib>

#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// Shortest text that reads back to the same float, so two configs print
// differently exactly when their values differ.
std::string text(float v) {
  char buf[32];
#if defined(__cpp_lib_to_chars)
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
#else
  // A standard library without floating-point to_chars (Emscripten's): the
  // fewest significant digits that read back to the same float.
  for (int digits = 1; digits < 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(v));
    if (std::strtof(buf, nullptr) == v) return buf;
  }
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
#endif
}

std::string text(Vec3 v) {
  return "(" + text(v.x) + ", " + text(v.y) + ", " + text(v.z) + ")";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> World3D::describe_config(const WorldConfig& c) {
  // Every field encode_config() writes, in its order; a field missing here
  // still shows up as "bytes differ" where replays compare configs.
  return {
      {"gravity", text(c.gravity) + " m/s^2"},
      {"tick_seconds", text(c.tick_seconds)},
      {"substeps", std::to_string(c.substeps)},
      {"relax_iterations", std::to_string(c.relax_iterations)},
      {"contact_hertz", text(c.contact_hertz)},
      {"contact_damping_ratio", text(c.contact_damping_ratio)},
      {"contact_push_max_mps", text(c.contact_push_max_mps)},
      {"restitution_threshold_mps", text(c.restitution_threshold_mps)},
      {"linear_slop_m", text(c.linear_slop_m)},
      {"speculative_distance_m", text(c.speculative_distance_m)},
      {"enable_sleep", c.enable_sleep ? "true" : "false"},
      {"sleep_threshold_mps", text(c.sleep_threshold_mps)},
      {"time_to_sleep_s", text(c.time_to_sleep_s)},
      {"max_bodies", std::to_string(c.max_bodies)},
      {"bounds_lower", text(c.bounds_lower) + " m"},
      {"bounds_upper", text(c.bounds_upper) + " m"},
  };
}

}  // namespace rwd::sim
