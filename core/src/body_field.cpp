// SPDX-License-Identifier: MIT
#include "rewind/core/body_field.h"

#include <cstddef>
#include <cstring>

namespace rwd {
namespace {

// A float's bits and back (std::bit_cast, which some standard libraries
// the engine builds with, Emscripten's among them, do not have yet).
uint32_t bits_of(float v) {
  uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}
float float_of(uint32_t bits) {
  float v = 0.0f;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// The half-open range of `fields` that belongs to the body at `begin`.
size_t body_end(const std::vector<BodyField>& fields, size_t begin) {
  size_t end = begin;
  while (end < fields.size() && fields[end].body_index == fields[begin].body_index) ++end;
  return end;
}

void compare_body(const std::vector<BodyField>& expected, size_t e, size_t e_end,
                  const std::vector<BodyField>& actual, size_t a, size_t a_end,
                  std::vector<FieldDifference>& out) {
  // Same-lane dumps list the same names in the same order; a name missing
  // on one side is reported against 0 and the walk resumes on the next.
  while (e < e_end || a < a_end) {
    if (e < e_end && a < a_end && expected[e].name == actual[a].name) {
      // Bit-exact: -0 vs +0 and NaN payloads are differences; "==" on the
      // values would hide the former and misreport the latter.
      if (expected[e].type != actual[a].type || expected[e].bits != actual[a].bits) {
        out.push_back({expected[e].body_index, std::string(expected[e].name), expected[e].value(),
                       actual[a].value()});
      }
      ++e;
      ++a;
    } else if (e < e_end) {
      out.push_back(
          {expected[e].body_index, std::string(expected[e].name), expected[e].value(), 0.0});
      ++e;
    } else {
      out.push_back({actual[a].body_index, std::string(actual[a].name), 0.0, actual[a].value()});
      ++a;
    }
  }
}

}  // namespace

BodyField BodyField::float32(uint32_t body_index, std::string_view name, float value) {
  return {body_index, name, FieldType::kFloat32, bits_of(value)};
}

BodyField BodyField::unsigned_int(uint32_t body_index, std::string_view name, uint64_t value) {
  return {body_index, name, FieldType::kUnsigned, value};
}

BodyField BodyField::signed_int(uint32_t body_index, std::string_view name, int64_t value) {
  return {body_index, name, FieldType::kSigned, static_cast<uint64_t>(value)};
}

BodyField BodyField::fixed16(uint32_t body_index, std::string_view name, int32_t raw) {
  return {body_index, name, FieldType::kFixed16, static_cast<uint32_t>(raw)};
}

BodyField BodyField::fixed32(uint32_t body_index, std::string_view name, int64_t raw) {
  return {body_index, name, FieldType::kFixed32, static_cast<uint64_t>(raw)};
}

double BodyField::value() const {
  switch (type) {
    case FieldType::kFloat32:
      return static_cast<double>(float_of(static_cast<uint32_t>(bits)));
    case FieldType::kUnsigned:
      return static_cast<double>(bits);
    case FieldType::kSigned:
      return static_cast<double>(static_cast<int64_t>(bits));
    case FieldType::kFixed16:
      return static_cast<double>(static_cast<int32_t>(static_cast<uint32_t>(bits))) / 65536.0;
    case FieldType::kFixed32:
      return static_cast<double>(static_cast<int64_t>(bits)) / 4294967296.0;
  }
  return 0.0;
}

std::vector<FieldDifference> diff_body_fields(const std::vector<BodyField>& expected,
                                              const std::vector<BodyField>& actual) {
  std::vector<FieldDifference> out;
  size_t i = 0;
  size_t j = 0;
  while (i < expected.size() || j < actual.size()) {
    const size_t i_end = i < expected.size() ? body_end(expected, i) : i;
    const size_t j_end = j < actual.size() ? body_end(actual, j) : j;
    if (j == actual.size() ||
        (i < expected.size() && expected[i].body_index < actual[j].body_index)) {
      out.push_back({expected[i].body_index, "exists", 1.0, 0.0});
      i = i_end;
    } else if (i == expected.size() || actual[j].body_index < expected[i].body_index) {
      out.push_back({actual[j].body_index, "exists", 0.0, 1.0});
      j = j_end;
    } else {
      compare_body(expected, i, i_end, actual, j, j_end, out);
      i = i_end;
      j = j_end;
    }
  }
  return out;
}

}  // namespace rwd
