// SPDX-License-Identifier: MIT
#include "rewind/core/splitmix64.h"
#include "rewind/game/game.h"

namespace rwd::game {
namespace {

int16_t axis_from(uint64_t bits) {
  return static_cast<int16_t>(static_cast<int64_t>(bits % 2001) - 1000);
}

}  // namespace

PlayerInput random_bot_input(const InputSpec& spec, uint64_t seed, uint32_t player, Tick tick) {
  // A new direction every 40 ticks; hashing the segment number keeps the
  // function pure in `tick`.
  const uint64_t block = static_cast<uint64_t>(tick) / 20;
  if (&spec != &stick_input_spec()) {
    return random_input(spec, splitmix64_once(seed ^ splitmix64_once(player) ^ block));
  }
  const uint64_t h = splitmix64_once(seed ^ splitmix64_once(player) ^ splitmix64_once(block / 2));
  StickInput input;
  input.axis_x = axis_from(h);
  input.axis_y = axis_from(h >> 16);
  const uint64_t b = splitmix64_once(h ^ static_cast<uint64_t>(tick));
  if (b % 97 == 0) input.buttons |= 1u;   // jump
  if (b % 131 == 0) input.buttons |= 2u;  // dash
  return PlayerInput::of(input);
}

}  // namespace rwd::game
