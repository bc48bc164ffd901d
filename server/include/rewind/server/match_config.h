// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "rewind/core/status.h"

namespace rwd::server {

/// Everything one hosted match is configured with.
struct MatchConfig {
  std::string game = "crates";  ///< a built-in game name
  uint32_t players = 2;         ///< slots; the match starts when all are joined
  /// Start once this many players have joined instead of waiting for every
  /// slot; the slots still free are taken later by late joiners, who catch
  /// up from a snapshot (their inputs are substituted until then). 0: every
  /// slot (no late join). [0, players].
  uint32_t start_players = 0;
  /// Read-only seats: spectators get every final tick and verify its
  /// checksum but send no inputs; they may join at any time. players +
  /// max_spectators <= 64. On a secure server token slots from `players`
  /// on are spectator seats.
  uint32_t max_spectators = 8;
  uint32_t tick_rate_hz = 60;  ///< [1, 1000]
  int32_t window_ticks = 8;    ///< finalization deadline, [1, 120]
  int64_t max_ticks = 0;       ///< end after this many final ticks; 0 = until stopped
  uint64_t seed = 1;           ///< the game's RNG seed
  /// Bound into connect tokens, names the match in logs, metrics and the
  /// control API: 1 to 64 characters of [A-Za-z0-9._-].
  std::string match_id = "match";
  /// Connections come through a SecureGateway (connect tokens, sealed
  /// packets) and every join names its slot by its token. False: the
  /// tokenless mode for local tests, where any address that answered a
  /// cookie (TokenlessGateway) takes a free slot.
  bool secure = false;
  std::string replay_path;  ///< empty: no replay file
  bool replay_overwrite = true;
  int32_t keyframe_interval = 300;  ///< ticks between replay keyframes, 0 = none
  std::string desync_dir;           ///< empty: desync reports are counted, not stored
  /// Publish the match to browsers that spectate it (LiveFeed; the
  /// server's live endpoint, ServerConfig::live, serves it).
  bool live = false;
  /// Ticks between the states a joining spectator starts from, [1, 3600].
  uint32_t live_keyframe_ticks = 120;
  /// Spectators see each tick this many ticks after it became final,
  /// [0, 36000] (10 minutes at 60 Hz); 0: at once.
  uint32_t live_delay_ticks = 0;
  double join_timeout_s = 60.0;  ///< give up when the lobby is not full by then
  /// Countdown between "everyone joined" and tick 0, so that every client
  /// hears MatchStart (repeated each tick) and starts its clock in time.
  double start_delay_s = 0.25;
  /// After the match ends, final ticks are still resent this long, until
  /// every client has acknowledged the last one.
  double closing_s = 1.0;
  double peer_timeout_s = 5.0;  ///< a silent peer is dropped; its inputs are substituted
  /// Inputs this many ticks ahead of the server's tick are rejected.
  int32_t max_input_lead_ticks = 120;

  /// Snapshot ring size: the deepest rollback is the window plus slack.
  /// One second more keeps the states of recent final ticks, so a desync
  /// report (a round trip after its final tick, or half a second later
  /// when a chunk was lost) can still be diffed against the server's state,
  /// and a resync has older final states to fall back to.
  /// Players joining a running match into a slot nobody held are allowed.
  bool late_join() const { return start_players != 0 && start_players < players; }
  /// Joined players the lobby waits for.
  uint32_t players_to_start() const { return start_players == 0 ? players : start_players; }
  int32_t snapshot_ticks() const { return window_ticks + 8 + static_cast<int32_t>(tick_rate_hz); }
  /// Checks ranges and that the game exists.
  Status validate() const;
};

/// True for a valid MatchConfig::match_id: a name, never a path (1 to 64
/// characters of A-Z a-z 0-9 . _ -, no leading '.', no "..").
bool is_match_id(std::string_view id);

}  // namespace rwd::server
