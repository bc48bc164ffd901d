// SPDX-License-Identifier: MIT
#pragma once
// A lane-neutral body dump: one record per (body, field), each holding the
// field's exact bits and how to read them. Desync reports and the replay
// verifier compare these, so they work for any lane's dump.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rwd {

/// How a BodyField's `bits` are read.
enum class FieldType : uint8_t {
  kFloat32 = 0,   ///< the low 32 bits are an IEEE binary32 pattern
  kUnsigned = 1,  ///< bits is the value
  kSigned = 2,    ///< bits is the value in two's complement (int64)
  kFixed16 = 3,   ///< the low 32 bits are a Q16.16 raw value (int32): value = raw / 65536
  kFixed32 = 4,   ///< bits is a Q32.32 raw value (int64): value = raw / 2^32
};

/// One field of one body. `name` must refer to storage that outlives the
/// dump (lanes use string literals, e.g. "position.x").
struct BodyField {
  uint32_t body_index = 0;
  std::string_view name;
  FieldType type = FieldType::kUnsigned;
  uint64_t bits = 0;

  static BodyField float32(uint32_t body_index, std::string_view name, float value);
  static BodyField unsigned_int(uint32_t body_index, std::string_view name, uint64_t value);
  static BodyField signed_int(uint32_t body_index, std::string_view name, int64_t value);
  static BodyField fixed16(uint32_t body_index, std::string_view name, int32_t raw);
  static BodyField fixed32(uint32_t body_index, std::string_view name, int64_t raw);

  /// The value as a double, for reports. Exact for every kFloat32 and
  /// kFixed16 value, for kFixed32 values up to 2^21 in magnitude and for
  /// integers up to 2^53 in magnitude.
  double value() const;
};

/// One differing field between two dumps, e.g. body 7 "position.y".
struct FieldDifference {
  uint32_t body_index = 0;
  std::string field;
  double expected = 0.0;
  double actual = 0.0;
};

/// Compares two dumps bit for bit and lists every field that differs. Both
/// dumps list bodies in ascending index order and each body's fields in the
/// lane's fixed order. A body present in one dump only is reported once as
/// field "exists" (1 = present, 0 = absent); a field present on one side
/// only (dumps of different lanes) is reported under its own name with 0
/// for the side that lacks it.
std::vector<FieldDifference> diff_body_fields(const std::vector<BodyField>& expected,
                                              const std::vector<BodyField>& actual);

}  // namespace rwd
