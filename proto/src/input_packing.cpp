// SPDX-License-Identifier: MIT
#include "rewind/proto/input_packing.h"

#include <cstring>

namespace rwd::proto {
namespace {

constexpr size_t kInputBytes = 8;

void to_bytes(const rwd::PlayerInput& in, uint8_t* out) {
  const auto x = static_cast<uint16_t>(in.axis_x);
  const auto y = static_cast<uint16_t>(in.axis_y);
  out[0] = static_cast<uint8_t>(x);
  out[1] = static_cast<uint8_t>(x >> 8);
  out[2] = static_cast<uint8_t>(y);
  out[3] = static_cast<uint8_t>(y >> 8);
  for (int i = 0; i < 4; ++i) out[4 + i] = static_cast<uint8_t>(in.buttons >> (8 * i));
}

rwd::PlayerInput from_bytes(const uint8_t* in) {
  rwd::PlayerInput out;
  out.axis_x = static_cast<int16_t>(static_cast<uint16_t>(in[0] | in[1] << 8));
  out.axis_y = static_cast<int16_t>(static_cast<uint16_t>(in[2] | in[3] << 8));
  out.buttons = 0;
  for (int i = 0; i < 4; ++i) out.buttons |= uint32_t{in[4 + i]} << (8 * i);
  return out;
}

void pack_one(const rwd::PlayerInput& value, const rwd::PlayerInput& reference, std::string& out) {
  uint8_t a[kInputBytes];
  uint8_t b[kInputBytes];
  to_bytes(value, a);
  to_bytes(reference, b);
  uint8_t mask = 0;
  for (size_t i = 0; i < kInputBytes; ++i) {
    if (a[i] != b[i]) mask |= static_cast<uint8_t>(1u << i);
  }
  out.push_back(static_cast<char>(mask));
  for (size_t i = 0; i < kInputBytes; ++i) {
    if (mask >> i & 1u) out.push_back(static_cast<char>(a[i] ^ b[i]));
  }
}

// Reads one input at `at` against `reference`; false when the bytes end.
bool unpack_one(std::string_view bytes, size_t& at, const rwd::PlayerInput& reference,
                rwd::PlayerInput& out) {
  if (at >= bytes.size()) return false;
  const auto mask = static_cast<uint8_t>(bytes[at++]);
  uint8_t value[kInputBytes];
  to_bytes(reference, value);
  for (size_t i = 0; i < kInputBytes; ++i) {
    if ((mask >> i & 1u) == 0) continue;
    if (at >= bytes.size()) return false;
    value[i] ^= static_cast<uint8_t>(bytes[at++]);
  }
  out = from_bytes(value);
  return true;
}

bool in_range(const rwd::PlayerInput& in) {
  return in.axis_x >= -rwd::kAxisMax && in.axis_x <= rwd::kAxisMax && in.axis_y >= -rwd::kAxisMax &&
         in.axis_y <= rwd::kAxisMax;
}

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, what);
}

}  // namespace

void pack_inputs(std::span<const rwd::PlayerInput> values,
                 std::span<const rwd::PlayerInput> references, std::string& out) {
  out.push_back(static_cast<char>(values.size()));
  const rwd::PlayerInput neutral;
  for (size_t i = 0; i < values.size(); ++i) {
    pack_one(values[i], references.empty() ? neutral : references[i], out);
  }
}

void pack_run(std::span<const rwd::PlayerInput> run, std::string& out) {
  out.push_back(static_cast<char>(run.size()));
  rwd::PlayerInput previous;
  for (const rwd::PlayerInput& input : run) {
    pack_one(input, previous, out);
    previous = input;
  }
}

Status unpack_inputs(std::string_view bytes, std::span<const rwd::PlayerInput> references,
                     std::vector<rwd::PlayerInput>& out) {
  out.clear();
  if (bytes.empty()) return corrupt("packed inputs: no count");
  const auto count = static_cast<uint8_t>(bytes[0]);
  if (count > kMaxPackedInputs) return corrupt("packed inputs: more than 64");
  if (!references.empty() && references.size() != count) {
    return corrupt("packed inputs: " + std::to_string(count) + " against " +
                   std::to_string(references.size()) + " references");
  }
  size_t at = 1;
  const rwd::PlayerInput neutral;
  for (size_t i = 0; i < count; ++i) {
    rwd::PlayerInput in;
    if (!unpack_one(bytes, at, references.empty() ? neutral : references[i], in)) {
      out.clear();
      return corrupt("packed inputs: cut short at input " + std::to_string(i));
    }
    if (!in_range(in)) {
      out.clear();
      return corrupt("packed inputs: input " + std::to_string(i) +
                     " has an axis outside [-1000, 1000]");
    }
    out.push_back(in);
  }
  if (at != bytes.size()) {
    out.clear();
    return corrupt("packed inputs: trailing bytes");
  }
  return Status::Ok();
}

Status check_packed_inputs(std::string_view bytes) {
  if (bytes.empty()) return corrupt("packed inputs: no count");
  const auto count = static_cast<uint8_t>(bytes[0]);
  if (count > kMaxPackedInputs) return corrupt("packed inputs: more than 64");
  size_t at = 1;
  for (size_t i = 0; i < count; ++i) {
    if (at >= bytes.size())
      return corrupt("packed inputs: cut short at input " + std::to_string(i));
    const auto mask = static_cast<uint8_t>(bytes[at++]);
    at += static_cast<size_t>(__builtin_popcount(mask));
    if (at > bytes.size()) return corrupt("packed inputs: cut short at input " + std::to_string(i));
  }
  if (at != bytes.size()) return corrupt("packed inputs: trailing bytes");
  return Status::Ok();
}

Status unpack_run(std::string_view bytes, std::vector<rwd::PlayerInput>& out) {
  out.clear();
  if (bytes.empty()) return corrupt("packed run: no count");
  const auto count = static_cast<uint8_t>(bytes[0]);
  if (count > kMaxPackedInputs) return corrupt("packed run: more than 64 inputs");
  size_t at = 1;
  rwd::PlayerInput previous;
  for (size_t i = 0; i < count; ++i) {
    rwd::PlayerInput in;
    if (!unpack_one(bytes, at, previous, in) || !in_range(in)) {
      out.clear();
      return corrupt("packed run: input " + std::to_string(i) + " cut short or out of range");
    }
    out.push_back(in);
    previous = in;
  }
  if (at != bytes.size()) {
    out.clear();
    return corrupt("packed run: trailing bytes");
  }
  return Status::Ok();
}

}  // namespace rwd::proto
