// SPDX-License-Identifier: MIT
#pragma once
// Match settings carried by an Agones allocation. The allocator (a
// GameServerAllocation's metadata, set by the matchmaker) writes them as
// annotations or labels named `rewind.dev/<setting>`; each setting takes
// the value the rewind-server flag of the same name would, with the same
// range:
//   rewind.dev/game          built-in game name
//   rewind.dev/players       [1, 32]
//   rewind.dev/spectators    [0, 63]
//   rewind.dev/tick-rate     [1, 1000] Hz
//   rewind.dev/window        [1, 120] ticks
//   rewind.dev/ticks         [0, 2^31] final ticks (0 = until stopped)
//   rewind.dev/seed          [0, 2^63 - 1]
//   rewind.dev/match-id      1-128 visible ASCII characters
//   rewind.dev/join-timeout  [0.1, 86400] s
//   rewind.dev/peer-timeout  [0.1, 3600] s
// An annotation wins over a label of the same name (label values are
// limited to 63 characters; annotations are not). Other keys under the
// prefix are refused, so a misspelt setting is never silently ignored.
#include <string>
#include <string_view>

#include "rewind/core/status.h"
#include "rewind/server/agones_sdk.h"
#include "rewind/server/match_config.h"

namespace rwd::server {

/// The prefix of every setting's annotation or label name.
inline constexpr std::string_view kAgonesSettingPrefix = "rewind.dev/";

/// Applies the allocation's settings to `match`, then checks the result with
/// MatchConfig::validate(). Returns what was applied, e.g.
/// "players=3 (annotation), ticks=600 (label)", or "" when there was
/// nothing. Errors (kInvalidArgument) name the setting and the accepted
/// values; `match` is then unchanged.
Result<std::string> apply_agones_match_settings(const AgonesGameServer& game_server,
                                                MatchConfig* match);

}  // namespace rwd::server
