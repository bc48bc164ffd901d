// SPDX-License-Identifier: MIT
#pragma once
// rewind-server as a library function: a game developer's own program
// registers its games (rewind/game/game_registry.h) and calls
// server_main(argc, argv) to become a full rewind-server that hosts them,
// with every flag, endpoint and exit status of the shipped one
// (docs/hosting.md: "rewind-server").

namespace rwd::server {

/// Parses the flags, hosts the match(es) to their end, prints the summary
/// and returns the process exit status: 0 done, 1 a failure (logged to
/// stderr), 2 the lobby timed out, 64 bad usage. Call it once per process,
/// from main(), after registering games.
int server_main(int argc, const char* const* argv);

}  // namespace rwd::server
