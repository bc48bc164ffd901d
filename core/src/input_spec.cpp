// SPDX-License-Identifier: MIT
#include "rewind/core/input_spec.h"

#include <array>
#include <cstddef>
#include <limits>

#include "rewind/core/splitmix64.h"
#include "rewind/core/stick_input.h"

namespace rwd {
namespace {

struct TypeRange {
  int64_t min;
  int64_t max;
};

TypeRange type_range(InputFieldType type) {
  switch (type) {
    case InputFieldType::kI8:
      return {INT8_MIN, INT8_MAX};
    case InputFieldType::kU8:
      return {0, UINT8_MAX};
    case InputFieldType::kI16:
      return {INT16_MIN, INT16_MAX};
    case InputFieldType::kU16:
      return {0, UINT16_MAX};
    case InputFieldType::kI32:
      return {INT32_MIN, INT32_MAX};
    case InputFieldType::kU32:
      return {0, UINT32_MAX};
  }
  return {0, 0};
}

bool is_signed(InputFieldType type) {
  return type == InputFieldType::kI8 || type == InputFieldType::kI16 ||
         type == InputFieldType::kI32;
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > 32) return false;
  for (char c : name) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

}  // namespace

size_t input_field_bytes(InputFieldType type) {
  switch (type) {
    case InputFieldType::kI8:
    case InputFieldType::kU8:
      return 1;
    case InputFieldType::kI16:
    case InputFieldType::kU16:
      return 2;
    case InputFieldType::kI32:
    case InputFieldType::kU32:
      return 4;
  }
  return 0;
}

Status check_input_spec(const InputSpec& spec) {
  if (spec.size < 1 || spec.size > kInputCapacity) {
    return invalid("an input spec's size must be 1 to " + std::to_string(kInputCapacity) +
                   " bytes, not " + std::to_string(spec.size));
  }
  std::array<bool, kInputCapacity> used{};
  for (size_t i = 0; i < spec.fields.size(); ++i) {
    const InputField& f = spec.fields[i];
    const std::string which =
        "input field " + std::to_string(i) + " ('" + std::string(f.name) + "')";
    if (!valid_name(f.name)) {
      return invalid(which + ": a name is 1 to 32 letters, digits or '_'");
    }
    for (size_t j = 0; j < i; ++j) {
      if (spec.fields[j].name == f.name) return invalid(which + ": the name is used twice");
    }
    const size_t bytes = input_field_bytes(f.type);
    if (bytes == 0) return invalid(which + ": unknown type");
    if (size_t{f.offset} + bytes > spec.size) {
      return invalid(which + ": ends past the input's " + std::to_string(spec.size) + " bytes");
    }
    for (size_t b = f.offset; b < f.offset + bytes; ++b) {
      if (used[b]) return invalid(which + ": overlaps another field");
      used[b] = true;
    }
    const TypeRange r = type_range(f.type);
    if (f.min > f.max || f.min < r.min || f.max > r.max) {
      return invalid(which + ": range [" + std::to_string(f.min) + ", " + std::to_string(f.max) +
                     "] is empty or does not fit the field's type");
    }
  }
  return Status::Ok();
}

const InputField* find_input_field(const InputSpec& spec, std::string_view name) {
  for (const InputField& f : spec.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

int64_t read_input_field(const PlayerInput& input, const InputField& field) {
  const size_t bytes = input_field_bytes(field.type);
  uint64_t raw = 0;
  for (size_t b = 0; b < bytes; ++b) {
    raw |= uint64_t{input.bytes[field.offset + b]} << (8 * b);
  }
  if (is_signed(field.type) && bytes < 8 && (raw >> (8 * bytes - 1) & 1u) != 0) {
    raw |= ~uint64_t{0} << (8 * bytes);  // sign-extend
  }
  return static_cast<int64_t>(raw);
}

void write_input_field(PlayerInput& input, const InputField& field, int64_t value) {
  const size_t bytes = input_field_bytes(field.type);
  const auto raw = static_cast<uint64_t>(value);
  for (size_t b = 0; b < bytes; ++b) {
    input.bytes[field.offset + b] = static_cast<uint8_t>(raw >> (8 * b));
  }
}

Status check_input(const InputSpec& spec, const PlayerInput& input) {
  for (size_t b = spec.size; b < kInputCapacity; ++b) {
    if (input.bytes[b] != 0) {
      return invalid("input byte " + std::to_string(b) + " is set, past the game's " +
                     std::to_string(spec.size) + "-byte input");
    }
  }
  for (const InputField& f : spec.fields) {
    const int64_t v = read_input_field(input, f);
    if (v < f.min || v > f.max) {
      return invalid("input field '" + std::string(f.name) + "' is " + std::to_string(v) +
                     ", outside [" + std::to_string(f.min) + ", " + std::to_string(f.max) + "]");
    }
  }
  return Status::Ok();
}

PlayerInput predict_input(const InputSpec& spec, const PlayerInput& newest) {
  return spec.predict != nullptr ? spec.predict(newest) : newest;
}

std::string describe_input(const InputSpec& spec, const PlayerInput& input) {
  std::string out;
  if (spec.fields.empty()) {
    static constexpr char kHex[] = "0123456789abcdef";
    const size_t used = spec.size == 0 ? kInputCapacity : spec.size;
    for (size_t b = 0; b < used; ++b) {
      out.push_back(kHex[input.bytes[b] >> 4]);
      out.push_back(kHex[input.bytes[b] & 15]);
    }
    return out;
  }
  for (const InputField& f : spec.fields) {
    if (!out.empty()) out.push_back(' ');
    out.append(f.name);
    out.push_back('=');
    out.append(std::to_string(read_input_field(input, f)));
  }
  return out;
}

PlayerInput random_input(const InputSpec& spec, uint64_t bits) {
  PlayerInput input;
  if (spec.fields.empty()) {
    for (size_t b = 0; b < spec.size && b < kInputCapacity; ++b) {
      input.bytes[b] = static_cast<uint8_t>(splitmix64_once(bits ^ b));
    }
    return input;
  }
  for (size_t i = 0; i < spec.fields.size(); ++i) {
    const InputField& f = spec.fields[i];
    const uint64_t span = static_cast<uint64_t>(f.max - f.min) + 1;
    const uint64_t h = splitmix64_once(bits ^ splitmix64_once(i));
    write_input_field(input, f, f.min + static_cast<int64_t>(h % span));
  }
  return input;
}

const InputSpec& stick_input_spec() {
  static constexpr InputField kFields[] = {
      {"axis_x", InputFieldType::kI16, offsetof(StickInput, axis_x), -kAxisMax, kAxisMax},
      {"axis_y", InputFieldType::kI16, offsetof(StickInput, axis_y), -kAxisMax, kAxisMax},
      {"buttons", InputFieldType::kU32, offsetof(StickInput, buttons), 0, UINT32_MAX},
  };
  static constexpr InputSpec kSpec{"stick", sizeof(StickInput), kFields, nullptr};
  return kSpec;
}

}  // namespace rwd
