// SPDX-License-Identifier: MIT
#pragma once
// Finalizing and broadcasting a hosted match's ticks. A tick becomes final
// when every held slot's input is in or the input window has passed; a
// missing input becomes the prediction the simulation already used, so
// finalizing never re-simulates. Each final tick goes to the recorder (the
// replay and the live feed) with its checksum, and is held for the clients
// (FinalTickLog) until every connected player has acknowledged it, within
// a bounded tail for those that fall behind. Each client's datagram of the
// tick is composed here: its input acknowledgement and lead, the server's
// clock, the other players' new inputs (InputRelay) and final ticks.
//
// The last 1,024 final ticks' substitution masks and checksums are kept to
// tell a resend of an input the server had from one that came too late,
// and to check a desync report against what the server finalized.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "rewind/net/rollback_session.h"
#include "rewind/server/final_tick_log.h"
#include "rewind/server/input_relay.h"
#include "rewind/server/match_config.h"
#include "rewind/server/match_recorder.h"
#include "rewind/server/match_seats.h"
#include "rewind/server/match_stats.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

class MatchFinalizer {
 public:
  /// Everything given outlives this.
  MatchFinalizer(const MatchConfig& config, net::RollbackSession& session, const MatchSeats& seats,
                 MatchRecorder& recorder, MatchStats& stats);

  /// Finalizes every tick that is ready (never past config.max_ticks) and
  /// trims what every client has.
  void finalize_ready_ticks();

  /// The next tick to become final; next_final() - 1 is the last final one.
  Tick next_final() const { return next_final_; }
  const FinalTickLog& held() const { return finals_; }
  /// The checksum of final tick `tick` while it is in the recent history.
  std::optional<uint64_t> checksum(Tick tick) const;
  /// Whether final tick `tick` was finalized without `player`'s input
  /// (false once it left the recent history).
  bool substituted(Tick tick, uint32_t player) const;

  /// The datagram of the tick for the holder of seat `id`: acknowledgement,
  /// lead and clock; the other players' relayed inputs; and, unless a
  /// resync snapshot is on its way (the client ignores final ticks then),
  /// the final ticks it still needs, all within one datagram's budget.
  void compose(Seat& seat, uint32_t id, Tick server_tick, const InputRelay& relay,
               bool resync_pending, v1::FinalTicks& out) const;

 private:
  struct FinalRecord {
    Tick tick = kNoTick;
    uint64_t substituted = 0;
    uint64_t checksum = 0;
  };
  static constexpr size_t kFinalHistory = 1024;

  const MatchConfig& config_;
  net::RollbackSession& session_;
  const MatchSeats& seats_;
  MatchRecorder& recorder_;
  MatchStats& stats_;
  FinalTickLog finals_;  // held for the clients, oldest first
  Tick next_final_ = 0;
  std::vector<FinalRecord> history_;  // by tick % kFinalHistory
  std::vector<rwd::PlayerInput> final_inputs_;
};

}  // namespace rwd::server
