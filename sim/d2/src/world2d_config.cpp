// SPDX-License-Identifier: MIT
// Checking, encoding and describing a World2DConfig.
#include <string>

#include "byte_codec2d.h"
#include "fx_check.h"
#include "fx_text.h"
#include "rewind/sim2d/world2d.h"
#include "state_schema2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

Status invalid(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, "world config: " + message);
}

}  // namespace

Status World2D::validate_config(const World2DConfig& c) {
  if (c.tick_hz < 1 || c.tick_hz > 1000) return invalid("tick_hz must be in [1, 1000]");
  if (c.substeps < 1 || c.substeps > 32) return invalid("substeps must be in [1, 32]");
  if (c.tick_hz * c.substeps < 240) {
    return invalid(
        "a substep must be at most 1/240 s (tick_hz * substeps >= 240: at 60 Hz, 4 substeps or "
        "more); joint grids and box pyramids fall apart with longer substeps");
  }
  if (c.relax_iterations < 0 || c.relax_iterations > 8) {
    return invalid("relax_iterations must be in [0, 8]");
  }
  if (!in_range(c.gravity.x, -1000_fx, 1000_fx) || !in_range(c.gravity.y, -1000_fx, 1000_fx)) {
    return invalid("gravity components must be in [-1000, 1000] m/s^2");
  }
  if (!in_range(c.contact_hertz, Fx::epsilon(), 1000_fx)) {
    return invalid("contact_hertz must be in (0, 1000]");
  }
  if (!in_range(c.contact_damping_ratio, Fx(), 100_fx)) {
    return invalid("contact_damping_ratio must be in [0, 100]");
  }
  if (!in_range(c.sleep_threshold, Fx(), 100_fx))
    return invalid("sleep_threshold must be in [0, 100]");
  if (!in_range(c.time_to_sleep, Fx::epsilon(), 100_fx)) {
    return invalid("time_to_sleep must be in (0, 100]");
  }
  if (!in_range(c.joint_damping_ratio, Fx(), 100_fx)) {
    return invalid("joint_damping_ratio must be in [0, 100]");
  }
  if (!in_range(c.contact_push_max, Fx::epsilon(), 1000_fx)) {
    return invalid("contact_push_max must be in (0, 1000] m/s");
  }
  if (!in_range(c.restitution_threshold, Fx(), 1000_fx)) {
    return invalid("restitution_threshold must be in [0, 1000] m/s");
  }
  if (!in_range(c.linear_slop, Fx(), 1_fx)) return invalid("linear_slop must be in [0, 1] m");
  if (!in_range(c.speculative_distance, Fx::epsilon(), 10_fx)) {
    return invalid("speculative_distance must be in (0, 10] m");
  }
  if (!in_range(c.max_linear_speed, Fx::epsilon(), 10000_fx)) {
    return invalid("max_linear_speed must be in (0, 10000] m/s");
  }
  if (c.max_bodies < 1 || c.max_bodies > (1u << 20)) {
    return invalid("max_bodies must be in [1, 1048576]");
  }
  if (!(c.bounds_lower.x < c.bounds_upper.x) || !(c.bounds_lower.y < c.bounds_upper.y)) {
    return invalid("bounds_lower must be below bounds_upper on both axes");
  }
  return Status::Ok();
}

void World2D::encode_config(const World2DConfig& config, std::vector<uint8_t>& out) {
  out.clear();
  ByteWriter2D writer(out);
  visit_config(config, writer);
}

Result<World2DConfig> World2D::decode_config(std::span<const uint8_t> bytes) {
  World2DConfig config;
  ByteReader2D reader(bytes);
  visit_config(config, reader);
  if (!reader.ok() || !reader.at_end()) {
    return Status::Error(ErrorCode::kCorrupt, "world config: wrong length");
  }
  if (Status s = validate_config(config); !s.ok()) {
    return Status::Error(ErrorCode::kCorrupt, s.message());
  }
  return config;
}

namespace {

// Writes "name" -> exact decimal text with a unit where one helps.
class ConfigDescriber {
 public:
  explicit ConfigDescriber(std::vector<std::pair<std::string, std::string>>& out) : out_(out) {}
  template <class T>
  void operator()(std::string_view name, const T& field) {
    if constexpr (std::is_same_v<T, Fx>) {
      out_.emplace_back(std::string(name), fx_to_text(field));
    } else if constexpr (std::is_same_v<T, bool>) {
      out_.emplace_back(std::string(name), field ? "true" : "false");
    } else {
      out_.emplace_back(std::string(name), std::to_string(field));
    }
  }

 private:
  std::vector<std::pair<std::string, std::string>>& out_;
};

}  // namespace

std::vector<std::pair<std::string, std::string>> World2D::describe_config(
    const World2DConfig& config) {
  std::vector<std::pair<std::string, std::string>> out;
  ConfigDescriber describer(out);
  visit_config(config, describer);
  return out;
}

}  // namespace rwd::sim2d
