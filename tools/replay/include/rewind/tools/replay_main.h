// SPDX-License-Identifier: MIT
#pragma once
// rewind-replay as a library function: a game developer's own program
// registers its games (rewind/game/game_registry.h) and calls
// replay_main(argc, argv) to become a full rewind-replay that verifies,
// inspects and shows its replays.

namespace rwd::tools {

/// Runs one rewind-replay command (verify, inspect, view, tamper) and
/// returns the exit status: 0 done (verify: every tick re-simulated as
/// recorded), 1 a failure or a mismatch (printed), 64 bad usage.
int replay_main(int argc, const char* const* argv);

}  // namespace rwd::tools
