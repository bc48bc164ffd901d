// SPDX-License-Identifier: MIT
#pragma once
// A hosted match's desync and resync path. A client's desync report is
// reassembled from its chunks and handed to DesyncForensics (the bodies and
// fields that differ, stored; a few per client, spaced out, so nobody can
// stall the match or fill the disk by inventing desyncs). Then, or when a
// client fell behind the final ticks still held, a resync episode starts: a
// snapshot checked to load here before it goes out, resent in chunks until
// the client acknowledges the tick before it, replaced when the client
// refuses it.
#include <cstdint>
#include <functional>
#include <vector>

#include "rewind/net/chunked_transfer.h"
#include "rewind/net/rollback_session.h"
#include "rewind/server/desync_forensics.h"
#include "rewind/server/match_config.h"
#include "rewind/server/match_environment.h"
#include "rewind/server/match_finalizer.h"
#include "rewind/server/match_outbox.h"
#include "rewind/server/match_seats.h"
#include "rewind/server/match_stats.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

class MatchResync {
 public:
  /// Sees every resync snapshot right after it is serialized, before the
  /// server checks that it loads, and may damage it (fault tests).
  using SnapshotHook = std::function<void(Tick tick, std::vector<uint8_t>& bytes)>;

  /// Everything given by reference outlives this.
  MatchResync(const MatchConfig& config, net::RollbackSession& session, MatchSeats& seats,
              const MatchFinalizer& finalizer, MatchOutbox& outbox, MatchStats& stats,
              MatchEnvironment env);

  void set_snapshot_hook(SnapshotHook hook) { snapshot_hook_ = std::move(hook); }

  /// A new holder took seat `id`: nothing of the last one's is kept.
  void clear(uint32_t id);
  /// The seat's holder came back on a new connection: its episode and the
  /// reports being assembled are void (the spacing of stored reports stays).
  void restart(uint32_t id);

  /// One chunk of a desync report from seat `id`.
  void on_desync_report(uint32_t id, const v1::DesyncReport& report, TimePoint now);
  /// The client asks for a snapshot, naming the last one it could not load.
  void on_resync_request(uint32_t id, const v1::ResyncRequest& request, TimePoint now);
  /// Before the seat's datagram of the tick: starts an episode for a client
  /// behind everything held, resends one not yet acknowledged, and ends one
  /// that is. Returns whether a snapshot is still on its way.
  bool before_broadcast(uint32_t id, TimePoint now);

 private:
  struct Offer {  // the snapshot of the seat's episode, resent as is until acknowledged
    Tick tick = kNoTick;
    std::vector<uint8_t> bytes;
    uint64_t checksum = 0;
    uint32_t snapshot_id = 0;
    TimePoint last_sent;
    bool sent_once = false;
  };
  struct Report {  // a desync report being assembled, and the seat's history of them
    uint32_t report_id = 0;
    Tick tick = kNoTick;
    uint64_t client_checksum = 0;
    uint64_t server_checksum = 0;                         // ours, as the client received it
    net::ChunkAssembler chunks{net::kDesyncChunkLimits};  // the client's state dump
    std::vector<uint32_t> handled;                        // recent report ids, counted once
    TimePoint last_stored;
    uint32_t stored = 0;
  };

  void send(uint32_t id, TimePoint now);
  bool start_episode(uint32_t id);
  void send_chunks(uint32_t id, TimePoint now);
  void store(uint32_t id, const Report& report, std::span<const uint8_t> dump);

  const MatchConfig& config_;
  net::RollbackSession& session_;
  MatchSeats& seats_;
  const MatchFinalizer& finalizer_;
  MatchOutbox& outbox_;
  MatchStats& stats_;
  std::vector<Offer> offers_;    // by seat
  std::vector<Report> reports_;  // by seat
  uint32_t next_snapshot_id_ = 1;
  SnapshotHook snapshot_hook_;
  DesyncForensics forensics_;
};

}  // namespace rwd::server
