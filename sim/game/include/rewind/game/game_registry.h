// SPDX-License-Identifier: MIT
#pragma once
// Games the server can host besides the built-in ones. A game developer
// links Rewind's server library into their own process, registers their
// Game under a name at start-up, and hosts it exactly like a built-in game
// (MatchConfig::game, Simulation::create(), replays, the verifier).
#include <functional>
#include <memory>
#include <string_view>

#include "rewind/core/status.h"
#include "rewind/game/game.h"

namespace rwd::game {

/// Makes a fresh Game for one match. Called from whichever thread creates a
/// match; it must be safe to call from several threads at once.
using GameFactory = std::function<std::unique_ptr<Game>()>;

/// Adds a game under `name` (1 to 64 characters of [A-Za-z0-9._-]); from
/// then on builtin_game_names() lists it and make_builtin_game() makes it.
/// Registered games live until the process ends. kInvalidArgument for a bad
/// name, an empty factory, or a name already taken (built-in or not), which
/// leaves the earlier game in place. Thread-safe.
Status register_game(std::string_view name, GameFactory factory);

}  // namespace rwd::game
