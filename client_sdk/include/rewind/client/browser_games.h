// SPDX-License-Identifier: MIT
#pragma once
// The games a browser client module plays besides the built-in ones.
//
// The client SDK for browsers (client_sdk/web/rewind-client.js) drives a
// WebAssembly module that holds the engine and the games. Every module
// defines this function exactly once: Rewind's own module registers nothing
// (client_sdk/wasm/builtin_games.cpp), and a game's module registers its
// game under the name its server hosts, the way its server does:
//
//   rwd::Status rwd::client::register_browser_games() {
//     return tag::register_tag_game();  // rwd::game::register_game("tag", ...)
//   }
//
// and is linked with rewind_add_browser_client() (RewindBrowserConfig.cmake,
// installed under share/rewind/wasm; docs/writing-a-game.md). The module
// calls it once, before its first input spec or client; an error it returns
// is what every later call reports.
#include "rewind/core/status.h"

namespace rwd::client {

Status register_browser_games();

}  // namespace rwd::client
