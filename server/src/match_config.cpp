// SPDX-License-Identifier: MIT
#include "rewind/server/match_config.h"

#include "rewind/game/simulation.h"

namespace rwd::server {

// A name, never a path: the id becomes a file name (replays) and a
// directory (desync reports), so "..", "." and a leading dot are refused.
bool is_match_id(std::string_view id) {
  if (id.empty() || id.size() > 64 || id.front() == '.') return false;
  if (id.find("..") != std::string_view::npos) return false;
  for (const char c : id) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

Status MatchConfig::validate() const {
  auto bad = [](const std::string& message) {
    return Status::Error(ErrorCode::kInvalidArgument, message);
  };
  if (!game::make_builtin_game(game)) {
    std::string known;
    for (std::string_view name : game::builtin_game_names()) known += " " + std::string(name);
    return bad("unknown game '" + game + "' (known:" + known + ")");
  }
  if (!is_match_id(match_id)) {
    return bad("match id '" + match_id.substr(0, 64) +
               "' must be a name: 1 to 64 characters of A-Z a-z 0-9 . _ -, not starting "
               "with '.' and without '..'");
  }
  if (players < 1 || players > game::kMaxPlayers) {
    return bad("players must be in [1, " + std::to_string(game::kMaxPlayers) + "]");
  }
  if (start_players > players) return bad("start players must be at most players");
  if (players + max_spectators > 64) return bad("players + spectators must be at most 64");
  if (tick_rate_hz < 1 || tick_rate_hz > 1000) return bad("tick rate must be in [1, 1000] Hz");
  if (window_ticks < 1 || window_ticks > 120) return bad("window must be in [1, 120] ticks");
  if (max_ticks < 0) return bad("ticks must be >= 0");
  if (keyframe_interval < 0) return bad("keyframe interval must be >= 0");
  if (live_keyframe_ticks < 1 || live_keyframe_ticks > 3600) {
    return bad("live keyframe ticks must be in [1, 3600]");
  }
  if (live_delay_ticks > 36000) return bad("live delay must be in [0, 36000] ticks");
  if (!(join_timeout_s > 0) || !(peer_timeout_s > 0)) return bad("timeouts must be > 0");
  if (!(start_delay_s >= 0 && start_delay_s <= 10)) return bad("start delay must be in [0, 10] s");
  if (!(closing_s >= 0 && closing_s <= 10)) return bad("closing time must be in [0, 10] s");
  // Inputs are held from the last final tick up to the lead ahead of now:
  // together they must fit the 256-tick input queues.
  if (max_input_lead_ticks < 1 || window_ticks + max_input_lead_ticks > 240) {
    return bad("window + max input lead must be at most 240 ticks");
  }
  return Status::Ok();
}

}  // namespace rwd::server
