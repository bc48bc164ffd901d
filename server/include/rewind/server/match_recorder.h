// SPDX-License-Identifier: MIT
#pragma once
// Where a hosted match's final ticks go besides its clients: the replay file
// and the live feed browsers spectate. One of MatchHost's concerns, kept
// apart: it sees only final ticks (inputs, substitution mask, checksum) and
// the rollback session that holds the state after them.
//
// The replay gets a keyframe every keyframe interval, kept only when it
// loads back with its tick's checksum (a keyframe the verifier could not
// load would stop it there). A failed write stops the replay, never the
// match: the file keeps its verified prefix. The live feed gets every final
// tick and, when it asks, the state after one (the keyframe's bytes when
// the replay has just serialized the same state).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/net/rollback_session.h"
#include "rewind/replay/replay_writer.h"
#include "rewind/server/live_feed.h"
#include "rewind/server/match_stats.h"

namespace rwd::server {

class MatchRecorder {
 public:
  /// `replay`: the open writer, or none; `keyframe_interval`: ticks between
  /// keyframes (0: none).
  MatchRecorder(std::optional<replay::ReplayWriter> replay, uint32_t keyframe_interval);

  /// From now on every final tick also goes to `feed` (null: none).
  void attach_live_feed(std::shared_ptr<LiveFeed> feed);
  bool has_live_feed() const { return live_ != nullptr; }

  /// Final tick `t`: `inputs` (one per slot), the substituted slots, its
  /// checksum. `session` holds the state after `t` (serialized for a
  /// keyframe or the live feed). Keyframes that do not load are counted in
  /// `stats.keyframe_load_failures` and logged.
  void record(net::RollbackSession& session, Tick t, std::span<const rwd::PlayerInput> inputs,
              uint64_t substituted, uint64_t checksum, MatchStats& stats);
  /// The seats' names changed: the live feed hears them with the next
  /// publish_names().
  void names_changed() { names_stale_ = live_ != nullptr; }
  bool names_stale() const { return names_stale_; }
  void publish_names(std::vector<std::string> names);

  /// Writes what the replay holds when its flush interval is due.
  void flush_if_due();
  /// The match ended after final tick `last_final`: the replay's end
  /// record, and the live feed's end.
  void finish(Tick last_final, const std::string& reason);

 private:
  void stop_replay(const Status& status);

  std::optional<replay::ReplayWriter> replay_;
  uint32_t keyframe_interval_ = 0;
  bool replay_failed_ = false;
  std::shared_ptr<LiveFeed> live_;
  bool names_stale_ = false;
  std::vector<uint8_t> state_buffer_;  // the state after a tick, reused
};

}  // namespace rwd::server
