// SPDX-License-Identifier: MIT
#pragma once
// Little-endian field writer and bounds-checked reader for the 2D state's
// portable bytes; both are schema visitors (state_schema2d.h).
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

#include "rewind/fixed/fx.h"

namespace rwd::sim2d::detail {

class ByteWriter2D {
 public:
  explicit ByteWriter2D(std::vector<uint8_t>& out) : out_(out) {}

  void put(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }

  template <class T>
  void operator()(std::string_view, const T& field) {
    if constexpr (std::is_same_v<T, fixed::Fx>) {
      put(static_cast<uint32_t>(field.raw()), 4);
    } else if constexpr (std::is_enum_v<T>) {
      put(static_cast<uint64_t>(field), sizeof(T));
    } else {
      put(static_cast<uint64_t>(field), sizeof(T));
    }
  }

 private:
  std::vector<uint8_t>& out_;
};

class ByteReader2D {
 public:
  explicit ByteReader2D(std::span<const uint8_t> bytes) : bytes_(bytes) {}

  /// False once a read ran past the end; later reads give zeros.
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == bytes_.size(); }

  uint64_t get(int bytes) {
    if (bytes_.size() - pos_ < static_cast<size_t>(bytes)) {
      ok_ = false;
      pos_ = bytes_.size();
      return 0;
    }
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= uint64_t{bytes_[pos_ + i]} << (8 * i);
    pos_ += static_cast<size_t>(bytes);
    return v;
  }
  std::span<const uint8_t> take(size_t n) {
    if (bytes_.size() - pos_ < n) {
      ok_ = false;
      pos_ = bytes_.size();
      return {};
    }
    const auto out = bytes_.subspan(pos_, n);
    pos_ += n;
    return out;
  }

  template <class T>
  void operator()(std::string_view, T& field) {
    if constexpr (std::is_same_v<T, fixed::Fx>) {
      field = fixed::Fx::from_raw(static_cast<int32_t>(static_cast<uint32_t>(get(4))));
    } else if constexpr (std::is_same_v<T, bool>) {
      const uint64_t v = get(1);
      if (v > 1) ok_ = false;  // one canonical byte per flag
      field = v == 1;
    } else {
      field = static_cast<T>(get(sizeof(T)));
    }
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace rwd::sim2d::detail
