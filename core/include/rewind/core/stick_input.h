// SPDX-License-Identifier: MIT
#pragma once
// The stick-and-buttons input of the built-in games (crates, arena, joust)
// and Game::input_spec()'s default: two axes and 32 buttons, 8 bytes.
#include <cstdint>
#include <span>
#include <vector>

#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"

namespace rwd {

/// Full deflection of a stick axis, in thousandths.
inline constexpr int16_t kAxisMax = 1000;

struct StickInput {
  int16_t axis_x = 0;    ///< [-kAxisMax, kAxisMax], thousandths of full deflection
  int16_t axis_y = 0;    ///< [-kAxisMax, kAxisMax]
  uint32_t buttons = 0;  ///< one bit per button; the game gives them meaning

  friend bool operator==(const StickInput&, const StickInput&) = default;
};
static_assert(InputLayout<StickInput> && sizeof(StickInput) == 8);

/// The stick input as a PlayerInput.
inline PlayerInput stick_input(int16_t axis_x, int16_t axis_y, uint32_t buttons = 0) {
  return PlayerInput::of(StickInput{axis_x, axis_y, buttons});
}

/// Stick inputs as PlayerInputs, one for one (a convenience for tests and
/// tools; it allocates).
inline std::vector<PlayerInput> stick_inputs(std::span<const StickInput> sticks) {
  std::vector<PlayerInput> out;
  out.reserve(sticks.size());
  for (const StickInput& s : sticks) out.push_back(PlayerInput::of(s));
  return out;
}

/// True when both axes are within [-kAxisMax, kAxisMax].
inline bool is_valid(const StickInput& input) {
  return input.axis_x >= -kAxisMax && input.axis_x <= kAxisMax && input.axis_y >= -kAxisMax &&
         input.axis_y <= kAxisMax;
}

/// The spec of StickInput: fields axis_x, axis_y, buttons; repeat the
/// newest input when one is missing.
const InputSpec& stick_input_spec();

}  // namespace rwd
