// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace rwd {

/// Streams chosen state fields, in a fixed order and a fixed little-endian
/// encoding, into XXH3-64. Never feed raw structs: padding is not state.
/// Floats are hashed by their bits, with -0 folded onto +0 so that two
/// equal values always hash alike.
class StateHasher {
 public:
  StateHasher() { XXH3_64bits_reset(&state_); }
  StateHasher(const StateHasher&) = delete;
  StateHasher& operator=(const StateHasher&) = delete;

  void add_u8(uint8_t v) { put(&v, 1); }
  void add_u32(uint32_t v) {
    uint8_t b[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    put(b, 4);
  }
  void add_i32(int32_t v) { add_u32(static_cast<uint32_t>(v)); }
  void add_u64(uint64_t v) {
    add_u32(static_cast<uint32_t>(v));
    add_u32(static_cast<uint32_t>(v >> 32));
  }
  void add_f32(float v) {
    if (v == 0.0f) v = 0.0f;  // fold -0 onto +0
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    add_u32(bits);
  }
  /// A handle of either lane (BodyId, BodyId2D, JointId, ...): its index,
  /// then its generation, so a recycled slot hashes differently.
  template <class Id>
  void add_id(const Id& id) {
    add_u32(id.index);
    add_u32(id.generation);
  }
  void add_bytes(const void* data, size_t size) {
    flush();
    XXH3_64bits_update(&state_, data, size);
  }

  /// The hash of everything added so far. Streaming XXH3 gives the same value
  /// however the input was split, so buffering changes no checksum.
  uint64_t digest() {
    flush();
    return XXH3_64bits_digest(&state_);
  }

 private:
  // Fields are a few bytes each; one XXH3 update per field would cost more
  // than the hashing itself, so they are gathered into blocks first.
  void put(const uint8_t* bytes, size_t size) {
    if (used_ + size > sizeof(buffer_)) flush();
    std::memcpy(buffer_ + used_, bytes, size);
    used_ += size;
  }
  void flush() {
    if (used_ == 0) return;
    XXH3_64bits_update(&state_, buffer_, used_);
    used_ = 0;
  }

  XXH3_state_t state_;
  size_t used_ = 0;
  uint8_t buffer_[512];
};

}  // namespace rwd
