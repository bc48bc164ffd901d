// SPDX-License-Identifier: MIT
#pragma once
// The one place a replay header is made: the server and every tool or test
// that records a match call make_replay_header(), so what a file says about
// the engine that produced it is filled in the same way everywhere.
#include <cstdint>
#include <string>

#include "rewind/game/game.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// The match parameters a header records besides what the game says.
struct RecordingSetup {
  game::MatchSetup match;
  uint32_t tick_rate_hz = 60;
  uint32_t window_ticks = 8;
  uint32_t keyframe_interval = 0;  ///< ticks between keyframes, 0 = none
  std::string server_version;
  int64_t started_unix_ms = 0;
};

/// A format kFormatVersion header for a match of `game`: the setup, and this
/// build's engine identity (engine name, sim revision, the game's name,
/// rules version and encoded world config).
v1::ReplayHeader make_replay_header(const game::Game& game, const RecordingSetup& setup);

}  // namespace rwd::replay
