// SPDX-License-Identifier: MIT
#pragma once
// Little-endian writes and bounds-checked reads for the viewer's flat
// formats (view bundles, live tick batches): integers of 1-8 bytes, and
// byte runs and strings as a u32 length and that many bytes.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/player_input.h"

namespace rwd::viewer::detail {

class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
  void put(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void bytes(std::span<const uint8_t> b) {
    put(b.size(), 4);
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void str(std::string_view s) { bytes({reinterpret_cast<const uint8_t*>(s.data()), s.size()}); }

 private:
  std::vector<uint8_t>& out_;
};

/// Bounds-checked reads; the first failure is kept with its offset and
/// every later read gives zeros.
class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, size_t start) : bytes_(bytes), pos_(start) {}
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t remaining() const { return bytes_.size() - pos_; }
  size_t offset() const { return pos_; }

  uint64_t get(int n, const char* what) {
    if (!ok()) return 0;
    if (remaining() < static_cast<size_t>(n)) {
      fail(what, "runs past the end");
      return 0;
    }
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint64_t{bytes_[pos_ + static_cast<size_t>(i)]} << (8 * i);
    pos_ += static_cast<size_t>(n);
    return v;
  }
  std::span<const uint8_t> run(uint32_t bound, const char* what) {
    const uint64_t n = get(4, what);
    if (!ok()) return {};
    if (n > bound) {
      fail(what,
           ("is " + std::to_string(n) + " bytes, more than " + std::to_string(bound)).c_str());
      return {};
    }
    if (remaining() < n) {
      fail(what, "runs past the end");
      return {};
    }
    const auto out = bytes_.subspan(pos_, static_cast<size_t>(n));
    pos_ += static_cast<size_t>(n);
    return out;
  }
  std::string str(uint32_t bound, const char* what) {
    const auto b = run(bound, what);
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }
  void fail(const char* what, const char* problem) {
    if (ok()) error_ = std::string(what) + " at byte " + std::to_string(pos_) + " " + problem;
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  std::string error_;
};

/// How a format stores inputs.
enum class InputEncoding : uint8_t {
  kBytes,  ///< u8 length (at most kInputCapacity), then the input's bytes
           ///< without its trailing zeros
  kStick,  ///< older versions: i16 axis_x, i16 axis_y, u32 buttons
};

inline void put_input(Writer& w, const rwd::PlayerInput& in) {
  size_t used = in.bytes.size();
  while (used > 0 && in.bytes[used - 1] == 0) --used;
  w.put(used, 1);
  for (size_t i = 0; i < used; ++i) w.put(in.bytes[i], 1);
}
inline rwd::PlayerInput get_input(Reader& r, InputEncoding layout) {
  rwd::PlayerInput in;
  if (layout == InputEncoding::kStick) {
    // The stick input's bytes are these eight, in this order.
    for (size_t i = 0; i < 8 && r.ok(); ++i) in.bytes[i] = static_cast<uint8_t>(r.get(1, "input"));
    return in;
  }
  const uint64_t used = r.get(1, "input length");
  if (r.ok() && used > rwd::kInputCapacity) r.fail("input length", "is beyond 32 bytes");
  for (uint64_t i = 0; i < used && r.ok(); ++i) {
    in.bytes[i] = static_cast<uint8_t>(r.get(1, "input"));
  }
  // One form per input: the writer leaves trailing zeros out.
  if (r.ok() && used > 0 && in.bytes[used - 1] == 0) r.fail("input", "ends in a zero byte");
  return in;
}

/// Tick records as both formats store them: per tick u64 checksum, u64
/// substituted mask, then `players` inputs.
inline void put_ticks(Writer& w, uint32_t players, const std::vector<uint64_t>& checksums,
                      const std::vector<uint64_t>& masks,
                      const std::vector<rwd::PlayerInput>& inputs) {
  for (size_t t = 0; t < checksums.size(); ++t) {
    w.put(checksums[t], 8);
    w.put(masks[t], 8);
    for (uint32_t p = 0; p < players; ++p) put_input(w, inputs[t * players + p]);
  }
}
/// Reads a u32 tick count (at most `bound`) and that many records.
inline void get_ticks(Reader& r, InputEncoding layout, uint64_t players, uint64_t bound,
                      std::vector<uint64_t>& checksums, std::vector<uint64_t>& masks,
                      std::vector<rwd::PlayerInput>& inputs) {
  const uint64_t ticks = r.get(4, "tick count");
  if (r.ok() && ticks > bound) r.fail("tick count", "is beyond the bound");
  // Each tick takes at least 16 bytes and one per player: refuse a count
  // the bytes cannot hold before reserving for it.
  const uint64_t least = 16 + (layout == InputEncoding::kStick ? 8 : 1) * players;
  if (r.ok() && r.remaining() / least < ticks) r.fail("ticks", "run past the end");
  if (!r.ok()) return;
  checksums.reserve(ticks);
  masks.reserve(ticks);
  inputs.reserve(ticks * players);
  for (uint64_t t = 0; r.ok() && t < ticks; ++t) {
    checksums.push_back(r.get(8, "checksum"));
    masks.push_back(r.get(8, "substituted mask"));
    for (uint64_t p = 0; p < players; ++p) inputs.push_back(get_input(r, layout));
  }
}

}  // namespace rwd::viewer::detail
