// SPDX-License-Identifier: MIT
#pragma once
// rewind-synctest as a library function: a game developer's own program
// registers its games (rewind/game/game_registry.h) and calls
// synctest_main(argc, argv) to become a full rewind-synctest for them.

namespace rwd::tools {

/// Parses the flags, runs the sync test (rewind/game/sync_test.h), prints
/// the verdict on stdout and returns the exit status: 0 deterministic, 1
/// not (the first check that failed is printed), 64 bad usage (unknown
/// game, bad flags).
int synctest_main(int argc, const char* const* argv);

}  // namespace rwd::tools
