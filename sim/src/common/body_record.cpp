// SPDX-License-Identifier: MIT
#include "rewind/sim/body_record.h"

namespace rwd::sim {

void append_body_fields(const BodyRecord& r, std::vector<BodyField>& out) {
  const uint32_t i = r.id.index;
  out.push_back(BodyField::unsigned_int(i, "generation", r.id.generation));
  out.push_back(BodyField::unsigned_int(i, "kind", static_cast<uint64_t>(r.kind)));
  out.push_back(BodyField::unsigned_int(i, "user_data", r.user_data));
  out.push_back(BodyField::float32(i, "position.x", r.position.x));
  out.push_back(BodyField::float32(i, "position.y", r.position.y));
  out.push_back(BodyField::float32(i, "position.z", r.position.z));
  out.push_back(BodyField::float32(i, "rotation.x", r.rotation.x));
  out.push_back(BodyField::float32(i, "rotation.y", r.rotation.y));
  out.push_back(BodyField::float32(i, "rotation.z", r.rotation.z));
  out.push_back(BodyField::float32(i, "rotation.w", r.rotation.w));
  out.push_back(BodyField::float32(i, "linear_velocity.x", r.linear_velocity.x));
  out.push_back(BodyField::float32(i, "linear_velocity.y", r.linear_velocity.y));
  out.push_back(BodyField::float32(i, "linear_velocity.z", r.linear_velocity.z));
  out.push_back(BodyField::float32(i, "angular_velocity.x", r.angular_velocity.x));
  out.push_back(BodyField::float32(i, "angular_velocity.y", r.angular_velocity.y));
  out.push_back(BodyField::float32(i, "angular_velocity.z", r.angular_velocity.z));
  out.push_back(BodyField::unsigned_int(i, "awake", r.awake ? 1 : 0));
  out.push_back(BodyField::unsigned_int(i, "enabled", r.enabled ? 1 : 0));
}

}  // namespace rwd::sim
