// SPDX-License-Identifier: MIT
#pragma once
// Where a hosted match is in its life; every part of the match host reads it.
#include <cstdint>

namespace rwd::server {

/// kLobby: waiting for every slot. kRunning: counting down to tick 0, then
/// ticking. kClosing: the match is over; final ticks are still resent until
/// acknowledged. kEnded: nothing more to do.
enum class MatchPhase : uint8_t { kLobby, kRunning, kClosing, kEnded };

/// "lobby", "running", "closing" or "ended": the phase as the metrics and
/// the control API name it.
const char* phase_name(MatchPhase phase);

}  // namespace rwd::server
