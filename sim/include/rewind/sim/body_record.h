// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "rewind/core/body_field.h"
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

/// Appends `record` to a lane-neutral dump, one BodyField per field in this
/// order: generation, kind, user_data, position.{x,y,z},
/// rotation.{x,y,z,w}, linear_velocity.{x,y,z}, angular_velocity.{x,y,z},
/// awake, enabled. Floats keep their exact bits; kind, awake and enabled
/// are unsigned integers.
void append_body_fields(const BodyRecord& record, std::vector<BodyField>& out);

}  // namespace rwd::sim
