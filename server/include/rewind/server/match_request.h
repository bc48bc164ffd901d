// SPDX-License-Identifier: MIT
#pragma once
// The arguments of a control call that allocates a match
// (POST /matches?id=duel-7&players=2&ticks=3600), read strictly: every key
// known, every value in the same range as the matching rewind-server flag,
// nothing repeated. The query is the whole input; request bodies are not
// read.
#include <cstdint>
#include <string_view>

#include "rewind/core/status.h"
#include "rewind/server/match_config.h"

namespace rwd::server {

struct MatchRequest {
  MatchConfig match;  ///< the defaults with the query's values over them
  uint16_t port = 0;  ///< UDP port to bind; 0: any free port
};

/// Reads `query` (the part of the target after '?', possibly empty): keys
/// id, game, players, start_players, spectators, tick_rate, window, ticks, seed,
/// join_timeout, peer_timeout, port, as `key=value` pairs joined by '&',
/// values of [A-Za-z0-9._-] only (no percent escapes). Starts from
/// `defaults`; the result is validated (MatchConfig::validate). At most
/// 1024 bytes. kInvalidArgument names the first bad key or value.
Result<MatchRequest> parse_match_request(std::string_view query, const MatchConfig& defaults);

}  // namespace rwd::server
