// SPDX-License-Identifier: MIT
#pragma once
// Getting back in step with the server once our state is wrong or cannot
// be checked: the desync report (our checksums and the state dump, in
// chunks, sent a few times and then only as a short request), the plain
// resync request when there is nothing to show, the server's snapshot
// reassembled from its chunks and loaded only when its checksum holds, and
// a refused snapshot named until the server sends another. One concern
// because one flag, awaiting(), gates it all: while it is set the protocol
// applies no final ticks and this keeps asking.
//
// It sends through the ServerChannel it is handed and loads into the
// RollbackSession it is handed; what a loaded snapshot means for the rest
// (final ticks, inputs, the clock) is the protocol's to do.
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/core/tick.h"
#include "rewind/net/chunked_transfer.h"
#include "rewind/net/clock.h"
#include "rewind/net/rollback_session.h"
#include "rewind/v1/envelope.pb.h"
#include "server_channel.h"

namespace rwd::client {

class DesyncRecovery {
 public:
  using TimePoint = net::TimePoint;

  /// What a resync chunk led to (on_chunk()).
  enum class Outcome : uint8_t {
    kNone,      ///< ignored, or taken and more are needed
    kRejected,  ///< malformed or inconsistent with the transfer: count it
    kLoaded,    ///< the snapshot at `tick` replaced our state
    kRefused,   ///< the snapshot at `tick` did not load (`reason`); another was asked for
  };
  struct ChunkOutcome {
    Outcome outcome = Outcome::kNone;
    Tick tick = kNoTick;
    uint64_t checksum = 0;  ///< the server's, for kLoaded
    std::string reason;     ///< for kRefused
  };

  /// Whether we wait for a snapshot (final ticks are then not applied).
  bool awaiting() const { return awaiting_; }

  /// Asks for a snapshot with nothing to report (history we cannot
  /// re-simulate, a tick beyond our window); nothing when already asking.
  void request(ServerChannel& channel, TimePoint now);
  /// Our checksum after final tick `tick` is `local_checksum`, the
  /// server's `server_checksum`: reports it with our state after the tick.
  void on_desync(net::RollbackSession& session, Tick tick, uint64_t local_checksum,
                 uint64_t server_checksum, ServerChannel& channel, TimePoint now);
  /// Repeats the report (or request) while awaiting, every 500 ms.
  void resend_if_due(ServerChannel& channel, TimePoint now);

  /// A chunk of the server's snapshot. Only one past what we settled can
  /// help: past `session`'s final tick, not before `acked_final` (the
  /// server would never resend the final ticks in between) and, unless
  /// awaiting, past `received_final` + 1. A complete snapshot is loaded
  /// into `session` when its checksum holds.
  ChunkOutcome on_chunk(net::RollbackSession& session, const v1::ResyncChunk& chunk,
                        Tick acked_final, Tick received_final, ServerChannel& channel,
                        TimePoint now);

 private:
  void send_report(ServerChannel& channel, TimePoint now);
  void send_request(ServerChannel& channel, TimePoint now);

  bool awaiting_ = false;
  Tick desync_tick_ = kNoTick;  // kNoTick: nothing to report, just ask
  uint64_t desync_server_checksum_ = 0;
  uint64_t desync_local_checksum_ = 0;
  uint32_t report_id_ = 0;
  int report_sends_ = 0;
  TimePoint last_report_sent_;
  std::vector<uint8_t> state_buffer_;  // our state after desync_tick_, the report's dump
  uint32_t refused_snapshot_id_ = 0;   // the last snapshot that did not load, 0 = none
  std::string refused_reason_;
  net::ChunkAssembler resync_{net::kResyncChunkLimits};
};

}  // namespace rwd::client
