// SPDX-License-Identifier: MIT
#pragma once
// rewind-bots as a library function: a game developer's own program
// registers its games (rewind/game/game_registry.h) and calls
// bots_main(argc, argv) to become a full rewind-bots that plays them.

namespace rwd::tools {

/// Connects the bots, plays until the match ends, prints the summary and
/// returns the exit status: 0 every bot finished with no desync, 1 a desync
/// was reported, 2 a bot failed (cannot connect, refused, timed out), 64 bad
/// usage.
int bots_main(int argc, const char* const* argv);

}  // namespace rwd::tools
