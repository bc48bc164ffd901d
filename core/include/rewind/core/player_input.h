// SPDX-License-Identifier: MIT
#pragma once
// One player's input for one tick, in the shape its game defines. The
// engine, the rollback queues, the wire and replays carry it as bytes and
// never look inside: only the game, through its InputSpec (input_spec.h),
// gives them a meaning. A game's input is any trivially copyable struct of
// integers up to kInputCapacity bytes with no padding; PlayerInput::of()
// and as() convert.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace rwd {

/// Most bytes one input can hold.
inline constexpr size_t kInputCapacity = 32;

/// What a game's input struct must be: trivially copyable, every bit part
/// of the value (no padding, no floating point: NaN and -0 have several
/// encodings, so two equal inputs could differ in bytes and checksums), and
/// at most kInputCapacity bytes.
template <class T>
concept InputLayout = std::is_trivially_copyable_v<T> &&
                      std::has_unique_object_representations_v<T> && sizeof(T) <= kInputCapacity;

static_assert(std::endian::native == std::endian::little,
              "inputs travel as their little-endian bytes");

struct PlayerInput {
  /// The input's bytes: the game's struct as it lies in memory
  /// (little-endian), the rest zero. All zero is the neutral input, what a
  /// player who never sent anything plays.
  std::array<uint8_t, kInputCapacity> bytes{};

  /// The bytes of `value`.
  template <InputLayout T>
  static PlayerInput of(const T& value) {
    PlayerInput input;
    std::memcpy(input.bytes.data(), &value, sizeof(T));
    return input;
  }
  /// The input read back as the game's struct (its first sizeof(T) bytes).
  template <InputLayout T>
  T as() const {
    T value;
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
  }
  bool is_neutral() const { return *this == PlayerInput{}; }

  friend bool operator==(const PlayerInput&, const PlayerInput&) = default;
};

}  // namespace rwd
