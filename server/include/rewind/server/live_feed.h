// SPDX-License-Identifier: MIT
#pragma once
// A hosted match as browsers spectate it: a read-only seat that takes no
// slot and sends nothing to the match. The match host publishes each
// final tick (inputs, substituted mask, checksum), a state every
// `keyframe_ticks` and the players' names; the server's live endpoint
// (ServerConfig::live) answers viewers from it on its own thread. A viewer
// loads start_bundle() (the newest published state and the ticks after
// it, a view bundle) and then polls ticks_from(); it re-simulates the
// ticks itself and checks every checksum, as for a replay.
//
// Bounded: a few keyframes and the ticks since the oldest of them. With a
// delay, spectators see each tick `delay_ticks` after it became final
// (so a spectator cannot relay the present to a player).
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"

namespace rwd::server {

class LiveFeed {
 public:
  struct Info {
    std::string match_id;
    std::string game;
    game::MatchSetup setup;
    uint32_t tick_rate_hz = 60;
    uint32_t keyframe_ticks = 120;  ///< [1, 3600]: ticks between published states
    uint32_t delay_ticks = 0;       ///< spectators trail the newest final tick by this
  };
  /// What a listing of live matches shows.
  struct Summary {
    std::string match_id;
    std::string game;
    uint32_t players = 0;
    std::vector<std::string> player_names;  ///< one per player ("" for a free slot)
    Tick newest_final = kNoTick;            ///< what the match has made final
    Tick published = kNoTick;               ///< what spectators may see (newest - delay)
    uint32_t tick_rate_hz = 0;
    bool ended = false;
  };

  explicit LiveFeed(Info info);

  const Info& info() const { return info_; }

  // The match host's side, on the match's strand.

  /// Tick `tick`'s final inputs (one per player), its substituted-input
  /// mask and its checksum. Ticks come in order from 0; anything else is
  /// ignored.
  void publish_tick(Tick tick, std::span<const rwd::PlayerInput> inputs, uint64_t substituted,
                    uint64_t checksum);
  /// Whether publish_state() wants the state at `position` (after tick
  /// position - 1): every keyframe_ticks.
  bool wants_state(Tick position) const {
    return position > 0 && position % static_cast<Tick>(info_.keyframe_ticks) == 0;
  }
  /// Simulation::serialize bytes of the state at `position`, which must
  /// follow the ticks published (it is ignored otherwise).
  void publish_state(Tick position, std::span<const uint8_t> state);
  /// Names of the seats, one per player ("" while free).
  void publish_names(std::vector<std::string> names);
  /// The match is over: viewers are told once they have its last tick.
  void end();

  // The viewers' side, from any thread.

  /// A view bundle (rewind/viewer/view_bundle.h) starting at the newest
  /// published state spectators may see (or at tick 0 before the first),
  /// holding every visible tick after it.
  Status start_bundle(std::vector<uint8_t>& out) const;
  /// A live tick batch (rewind/viewer/live_ticks.h) of the visible ticks
  /// from `from` on (at most kLiveMaxBatchTicks; none when `from` is
  /// ahead). kNotFound when `from` is older than the feed still holds:
  /// the viewer starts over from start_bundle(). kInvalidArgument for a
  /// negative `from`.
  Status ticks_from(Tick from, std::vector<uint8_t>& out) const;
  Summary summary() const;

 private:
  struct Keyframe {
    Tick position = 0;
    std::vector<uint8_t> state;
  };
  Tick published_locked() const;
  /// Appends the held ticks from .. through (both held) to the three lists.
  void copy_ticks_locked(Tick from, Tick through, std::vector<uint64_t>& checksums,
                         std::vector<uint64_t>& masks, std::vector<rwd::PlayerInput>& inputs) const;
  /// Drops the oldest keyframes and their ticks while two later ones are
  /// visible to spectators.
  void trim_locked();

  const Info info_;
  mutable std::mutex mutex_;
  std::vector<std::string> names_;
  Tick base_ = 0;                   ///< the first tick held
  Tick newest_ = kNoTick;           ///< the newest final tick
  std::deque<uint64_t> checksums_;  ///< from base_
  std::deque<uint64_t> masks_;
  std::deque<rwd::PlayerInput> inputs_;  ///< players per tick
  std::deque<Keyframe> keyframes_;       ///< ascending positions, all >= base_
  bool ended_ = false;
};

}  // namespace rwd::server
