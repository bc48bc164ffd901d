// SPDX-License-Identifier: MIT
#pragma once
// Little-endian field access and libsodium start-up, shared by the token
// and the channel.
#include <sodium.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>

namespace rwd::net::detail {

/// sodium_init() once per process; Rewind cannot run without a working
/// random source, so a failure aborts.
inline void ensure_sodium() {
  static const bool ready = sodium_init() >= 0;
  if (!ready) std::abort();
}

inline void put_le(uint8_t* out, uint64_t value, size_t bytes) {
  for (size_t i = 0; i < bytes; ++i) out[i] = static_cast<uint8_t>(value >> (8 * i));
}

inline uint64_t get_le(const uint8_t* in, size_t bytes) {
  uint64_t value = 0;
  for (size_t i = 0; i < bytes; ++i) value |= uint64_t{in[i]} << (8 * i);
  return value;
}

/// Appends bytes to a cursor.
struct Writer {
  uint8_t* at;
  void u8(uint8_t v) { *at++ = v; }
  void le(uint64_t v, size_t bytes) {
    put_le(at, v, bytes);
    at += bytes;
  }
  void raw(const uint8_t* p, size_t n) {
    for (size_t i = 0; i < n; ++i) at[i] = p[i];
    at += n;
  }
};

/// Reads bytes from a cursor (callers check sizes first).
struct Reader {
  const uint8_t* at;
  uint8_t u8() { return *at++; }
  uint64_t le(size_t bytes) {
    const uint64_t v = get_le(at, bytes);
    at += bytes;
    return v;
  }
  void raw(uint8_t* p, size_t n) {
    for (size_t i = 0; i < n; ++i) p[i] = at[i];
    at += n;
  }
};

}  // namespace rwd::net::detail
