// SPDX-License-Identifier: MIT
#pragma once
// Input scripts for bot clients, and for the games rewind-tune plays. Each
// is a pure function of (seed, bot, tick), so a load test can be rerun with
// the same inputs and a tuning run can replay them at every setting.
#include <cstdint>
#include <string_view>

#include "rewind/game/player_input.h"
#include "rewind/sim/tick.h"

namespace rwd::tools {

enum class BotScript : uint8_t {
  kRandom,  ///< a random stick direction every 40 ticks, occasional jump/dash
  kCircle,  ///< steers in a circle
  kIdle,    ///< neutral input
};

/// Parses "random", "circle", "idle".
bool parse_bot_script(std::string_view text, BotScript* out);

game::PlayerInput bot_input(BotScript script, uint64_t seed, uint32_t bot, Tick tick);

}  // namespace rwd::tools
