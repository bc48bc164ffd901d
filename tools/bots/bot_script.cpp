// SPDX-License-Identifier: MIT
#include "rewind/tools/bot_script.h"

namespace rwd::tools {

bool parse_bot_script(std::string_view text, BotScript* out) {
  if (text == "game")
    *out = BotScript::kGame;
  else if (text == "random")
    *out = BotScript::kRandom;
  else if (text == "circle")
    *out = BotScript::kCircle;
  else if (text == "idle")
    *out = BotScript::kIdle;
  else
    return false;
  return true;
}

rwd::PlayerInput bot_input(BotScript script, const game::Game& game, uint64_t seed, uint32_t bot,
                           Tick tick) {
  rwd::PlayerInput input;
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
    case BotScript::kGame:
      input = game.bot_input(seed, bot, tick);
      break;
    case BotScript::kRandom:
      input = game::random_bot_input(seed, bot, tick);
      break;
  }
  return input;
}

}  // namespace rwd::tools
