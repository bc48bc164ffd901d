// SPDX-License-Identifier: MIT
#include "rewind/tools/bot_script.h"
#include "rewind/sim/splitmix64.h"

namespace rwd::tools {
namespace {

uint64_t mix(uint64_t z) {
  return splitmix64_once(z);
}

int16_t axis_from(uint64_t bits) {
  return static_cast<int16_t>(static_cast<int64_t>(bits % 2001) - 1000);
}

}  // namespace

bool parse_bot_script(std::string_view text, BotScript* out) {
  if (text == "random")
    *out = BotScript::kRandom;
  else if (text == "circle")
    *out = BotScript::kCircle;
  else if (text == "idle")
    *out = BotScript::kIdle;
  else
    return false;
  return true;
}

game::PlayerInput bot_input(BotScript script, uint64_t seed, uint32_t bot, Tick tick) {
  game::PlayerInput input;
  switch (script) {
    case BotScript::kIdle:
      break;
    case BotScript::kCircle: {
      // A square-ish circle from integer steps: no trig needed for a bot.
      static constexpr int16_t kX[8] = {1000, 707, 0, -707, -1000, -707, 0, 707};
      const uint32_t phase = (static_cast<uint32_t>(tick) / 15 + bot) % 8;
      input.axis_x = kX[phase];
      input.axis_y = kX[(phase + 2) % 8];
      break;
    }
    case BotScript::kRandom: {
      // A new direction every 40 ticks; hashing the segment number keeps the
      // function pure in `tick`.
      const uint64_t block = static_cast<uint64_t>(tick) / 20;
      const uint64_t h = mix(seed ^ mix(bot) ^ mix(block / 2));
      input.axis_x = axis_from(h);
      input.axis_y = axis_from(h >> 16);
      const uint64_t b = mix(h ^ static_cast<uint64_t>(tick));
      if (b % 97 == 0) input.buttons |= 1u;   // jump
      if (b % 131 == 0) input.buttons |= 2u;  // dash
      break;
    }
  }
  return input;
}

}  // namespace rwd::tools
