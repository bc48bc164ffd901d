// SPDX-License-Identifier: MIT
#pragma once
// Input scripts for bot clients, and for the games rewind-tune plays. Each
// is a pure function of (seed, bot, tick), so a load test can be rerun with
// the same inputs and a tuning run can replay them at every setting.
#include <cstdint>
#include <string_view>

#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"

namespace rwd::tools {

enum class BotScript : uint8_t {
  kGame,    ///< the game's own Game::bot_input() (random_bot_input() unless it overrides)
  kRandom,  ///< game::random_bot_input(): for the stick input a random direction every
            ///< 40 ticks with an occasional jump or dash; any other input's fields at random
  kCircle,  ///< steers in a circle (the input fields axis_x and axis_y)
  kIdle,    ///< neutral input
};

/// Parses "game", "random", "circle", "idle".
bool parse_bot_script(std::string_view text, BotScript* out);

/// kInvalidArgument when `script` cannot drive an input of `spec` (circle
/// needs fields axis_x and axis_y).
Status check_bot_script(BotScript script, const rwd::InputSpec& spec);

/// The input `script` sends for seat `bot` on `tick` in `game`.
rwd::PlayerInput bot_input(BotScript script, const game::Game& game, uint64_t seed, uint32_t bot,
                           Tick tick);

}  // namespace rwd::tools
