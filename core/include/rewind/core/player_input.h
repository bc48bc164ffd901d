// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd {

/// One player's input for one tick. Fixed size and game-agnostic: each game
/// gives the axes and buttons their meaning. Axes are in [-1000, 1000]
/// (thousandths of full deflection); values outside are rejected at the
/// network edge and clamped by games.
struct PlayerInput {
  int16_t axis_x = 0;
  int16_t axis_y = 0;
  uint32_t buttons = 0;

  friend bool operator==(const PlayerInput&, const PlayerInput&) = default;
};

inline constexpr int16_t kAxisMax = 1000;

/// True when every field is within the documented ranges.
inline bool is_valid(const PlayerInput& input) {
  return input.axis_x >= -kAxisMax && input.axis_x <= kAxisMax && input.axis_y >= -kAxisMax &&
         input.axis_y <= kAxisMax;
}

}  // namespace rwd
