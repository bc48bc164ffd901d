// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/sim/body.h"

namespace rwd::sim {

/// A body's dynamic state in readable form: what a desync report carries
/// and what the replay verifier compares to name the fields that differ.
struct BodyRecord {
  BodyId id;
  BodyKind kind = BodyKind::kDynamic;
  uint64_t user_data = 0;
  Vec3 position;
  Quat rotation;
  Vec3 linear_velocity;
  Vec3 angular_velocity;
  bool awake = true;
  bool enabled = true;  ///< false once disabled (left the world bounds)
};

/// One differing field between two dumps, e.g. body 7 "position.y".
struct FieldDifference {
  uint32_t body_index = 0;
  std::string field;
  double expected = 0.0;
  double actual = 0.0;
};

/// Compares two dumps (bit-exact) and lists every field that differs,
/// including bodies present in one and not the other (field "exists").
std::vector<FieldDifference> diff_body_records(const std::vector<BodyRecord>& expected,
                                               const std::vector<BodyRecord>& actual);

}  // namespace rwd::sim
