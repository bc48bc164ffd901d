// SPDX-License-Identifier: MIT
#include "rewind/sim/body_record.h"

#include <cstring>

namespace rwd::sim {
namespace {

// Bit-exact comparison: a desync is any bit that differs, including -0 vs +0
// and NaN payloads; "==" would hide the former and misreport the latter.
bool same_bits(float a, float b) {
  uint32_t ua = 0;
  uint32_t ub = 0;
  std::memcpy(&ua, &a, 4);
  std::memcpy(&ub, &b, 4);
  return ua == ub;
}

void compare(uint32_t index, const char* field, float expected, float actual,
             std::vector<FieldDifference>& out) {
  if (!same_bits(expected, actual)) {
    out.push_back({index, field, static_cast<double>(expected), static_cast<double>(actual)});
  }
}

void compare_u64(uint32_t index, const char* field, uint64_t expected, uint64_t actual,
                 std::vector<FieldDifference>& out) {
  if (expected != actual) {
    out.push_back({index, field, static_cast<double>(expected), static_cast<double>(actual)});
  }
}

void compare_vec(uint32_t index, const char* name, Vec3 e, Vec3 a,
                 std::vector<FieldDifference>& out) {
  std::string base(name);
  compare(index, (base + ".x").c_str(), e.x, a.x, out);
  compare(index, (base + ".y").c_str(), e.y, a.y, out);
  compare(index, (base + ".z").c_str(), e.z, a.z, out);
}

void compare_records(const BodyRecord& e, const BodyRecord& a, std::vector<FieldDifference>& out) {
  uint32_t i = e.id.index;
  compare_u64(i, "generation", e.id.generation, a.id.generation, out);
  compare_u64(i, "kind", static_cast<uint64_t>(e.kind), static_cast<uint64_t>(a.kind), out);
  compare_u64(i, "user_data", e.user_data, a.user_data, out);
  compare_vec(i, "position", e.position, a.position, out);
  compare(i, "rotation.x", e.rotation.x, a.rotation.x, out);
  compare(i, "rotation.y", e.rotation.y, a.rotation.y, out);
  compare(i, "rotation.z", e.rotation.z, a.rotation.z, out);
  compare(i, "rotation.w", e.rotation.w, a.rotation.w, out);
  compare_vec(i, "linear_velocity", e.linear_velocity, a.linear_velocity, out);
  compare_vec(i, "angular_velocity", e.angular_velocity, a.angular_velocity, out);
  compare_u64(i, "awake", e.awake ? 1 : 0, a.awake ? 1 : 0, out);
  compare_u64(i, "enabled", e.enabled ? 1 : 0, a.enabled ? 1 : 0, out);
}

}  // namespace

std::vector<FieldDifference> diff_body_records(const std::vector<BodyRecord>& expected,
                                               const std::vector<BodyRecord>& actual) {
  // Both dumps are in ascending index order; merge them so a body missing
  // on one side is reported once as "exists" (1 = present, 0 = absent).
  std::vector<FieldDifference> out;
  size_t i = 0;
  size_t j = 0;
  while (i < expected.size() || j < actual.size()) {
    if (j == actual.size() || (i < expected.size() && expected[i].id.index < actual[j].id.index)) {
      out.push_back({expected[i].id.index, "exists", 1.0, 0.0});
      ++i;
    } else if (i == expected.size() || actual[j].id.index < expected[i].id.index) {
      out.push_back({actual[j].id.index, "exists", 0.0, 1.0});
      ++j;
    } else {
      compare_records(expected[i], actual[j], out);
      ++i;
      ++j;
    }
  }
  return out;
}

}  // namespace rwd::sim
