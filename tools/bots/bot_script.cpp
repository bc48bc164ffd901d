// SPDX-License-Identifier: MIT
#include "rewind/tools/bot_script.h"

#include <algorithm>
#include <string>

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

Status check_bot_script(BotScript script, const rwd::InputSpec& spec) {
  if (script == BotScript::kCircle && (rwd::find_input_field(spec, "axis_x") == nullptr ||
                                       rwd::find_input_field(spec, "axis_y") == nullptr)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the circle script steers the input fields axis_x and axis_y, and the "
                         "game's input ('" +
                             std::string(spec.name) + "') has no such fields");
  }
  return Status::Ok();
}

rwd::PlayerInput bot_input(BotScript script, const game::Game& game, uint64_t seed, uint32_t bot,
                           Tick tick) {
  const rwd::InputSpec& spec = game.input_spec();
  rwd::PlayerInput input;
  switch (script) {
    case BotScript::kIdle:
      break;
    case BotScript::kCircle: {
      // A square-ish circle from integer steps (the stick's thousandths,
      // clamped to the fields' ranges): no trig needed for a bot.
      static constexpr int64_t kX[8] = {1000, 707, 0, -707, -1000, -707, 0, 707};
      const uint32_t phase = (static_cast<uint32_t>(tick) / 15 + bot) % 8;
      const rwd::InputField* x = rwd::find_input_field(spec, "axis_x");
      const rwd::InputField* y = rwd::find_input_field(spec, "axis_y");
      if (x == nullptr || y == nullptr) break;  // check_bot_script() refuses this
      rwd::write_input_field(input, *x, std::clamp(kX[phase], x->min, x->max));
      rwd::write_input_field(input, *y, std::clamp(kX[(phase + 2) % 8], y->min, y->max));
      break;
    }
    case BotScript::kGame:
      input = game.bot_input(seed, bot, tick);
      break;
    case BotScript::kRandom:
      input = game::random_bot_input(spec, seed, bot, tick);
      break;
  }
  return input;
}

}  // namespace rwd::tools
