// SPDX-License-Identifier: MIT
#pragma once
// Input scripts for bot clients, and for the games rewind-tune plays. Each
// is a pure function of (seed, bot, tick), so a load test can be rerun with
// the same inputs and a tuning run can replay them at every setting.
#include <cstdint>
#include <string_view>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"

namespace rwd::tools {

enum class BotScript : uint8_t {
  kGame,    ///< the game's own Game::bot_input() (random_bot_input() unless it overrides)
  kRandom,  ///< a random stick direction every 40 ticks, occasional jump/dash
  kCircle,  ///< steers in a circle
  kIdle,    ///< neutral input
};

/// Parses "game", "random", "circle", "idle".
bool parse_bot_script(std::string_view text, BotScript* out);

/// The input `script` sends for seat `bot` on `tick` in `game`.
rwd::PlayerInput bot_input(BotScript script, const game::Game& game, uint64_t seed, uint32_t bot,
                           Tick tick);

}  // namespace rwd::tools
