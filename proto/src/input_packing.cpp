// SPDX-License-Identifier: MIT
#include "rewind/proto/input_packing.h"

#include <bit>
#include <cstdint>

namespace rwd::proto {
namespace {

static_assert(rwd::kInputCapacity == 32, "the byte mask has one bit per input byte");

void pack_one(const rwd::PlayerInput& value, const rwd::PlayerInput& reference, std::string& out) {
  uint32_t mask = 0;
  for (size_t i = 0; i < rwd::kInputCapacity; ++i) {
    if (value.bytes[i] != reference.bytes[i]) mask |= 1u << i;
  }
  // The mask as a little-endian base-128 varint: the first byte covers
  // bytes 0 to 6, so an unchanged input costs one byte.
  uint32_t m = mask;
  while (m >= 0x80) {
    out.push_back(static_cast<char>(m | 0x80));
    m >>= 7;
  }
  out.push_back(static_cast<char>(m));
  for (size_t i = 0; i < rwd::kInputCapacity; ++i) {
    if (mask >> i & 1u) out.push_back(static_cast<char>(value.bytes[i] ^ reference.bytes[i]));
  }
}

// Reads a mask at `at`; false when the bytes end or it is longer than 32 bits.
bool read_mask(std::string_view bytes, size_t& at, uint32_t& mask) {
  mask = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    if (at >= bytes.size()) return false;
    const auto byte = static_cast<uint8_t>(bytes[at++]);
    const uint64_t bits = uint64_t{byte & 0x7Fu} << shift;
    if (bits > UINT32_MAX) return false;
    mask |= static_cast<uint32_t>(bits);
    if ((byte & 0x80u) == 0) return true;
  }
  return false;
}

// Reads one input at `at` against `reference`; false when the bytes end.
bool unpack_one(std::string_view bytes, size_t& at, const rwd::PlayerInput& reference,
                rwd::PlayerInput& out) {
  uint32_t mask = 0;
  if (!read_mask(bytes, at, mask)) return false;
  out = reference;
  for (size_t i = 0; i < rwd::kInputCapacity; ++i) {
    if ((mask >> i & 1u) == 0) continue;
    if (at >= bytes.size()) return false;
    out.bytes[i] ^= static_cast<uint8_t>(bytes[at++]);
  }
  return true;
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
    uint32_t mask = 0;
    if (!read_mask(bytes, at, mask)) {
      return corrupt("packed inputs: bad mask at input " + std::to_string(i));
    }
    at += static_cast<size_t>(std::popcount(mask));
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
    if (!unpack_one(bytes, at, previous, in)) {
      out.clear();
      return corrupt("packed run: input " + std::to_string(i) + " cut short");
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
