// SPDX-License-Identifier: MIT
#pragma once
// One hosted match: the tick loop and the dispatch of what clients send to
// the parts that own each concern: MatchAdmission (who takes which seat),
// InputRelay (accepted inputs on their way to the other clients),
// MatchFinalizer (final ticks, substitution, each client's datagram of the
// tick), MatchResync (desync reports, resync snapshots) and MatchRecorder
// (the replay and the live feed). It never touches a socket or a clock: the server shell hands it
// datagrams and the steady time, it sends through a callback, and the wall clock and files it needs
// (a replay's date, desync reports) come through a MatchEnvironment. That keeps every rule here
// testable on its own.
#include <google/protobuf/arena.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/net/rollback_session.h"
#include "rewind/replay/replay_writer.h"
#include "rewind/server/input_relay.h"
#include "rewind/server/live_feed.h"
#include "rewind/server/match_admission.h"
#include "rewind/server/match_config.h"
#include "rewind/server/match_environment.h"
#include "rewind/server/match_finalizer.h"
#include "rewind/server/match_outbox.h"
#include "rewind/server/match_phase.h"
#include "rewind/server/match_recorder.h"
#include "rewind/server/match_resync.h"
#include "rewind/server/match_seats.h"
#include "rewind/server/match_stats.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

class MatchHost {
 public:
  using SendFn = MatchOutbox::SendFn;
  using Phase = MatchPhase;

  /// Validates the config, builds the simulation and opens the replay file.
  static Result<std::unique_ptr<MatchHost>> create(const MatchConfig& config, SendFn send,
                                                   TimePoint now,
                                                   MatchEnvironment env = MatchEnvironment::os());

  /// Handles one received datagram. Anything malformed, spoofed or not
  /// allowed is counted and dropped; nothing a client sends can stop the
  /// match or act for another player. In secure mode (MatchConfig::secure)
  /// `who` is what the sender's connect token names (SecureGateway), and a
  /// datagram without it is dropped. In tokenless mode a join is taken only
  /// with a `who` (its slot and client id unused): the sender's address
  /// answered a cookie (TokenlessGateway); nothing is sent to an address
  /// that did not.
  void on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, TimePoint now,
                   const Admission* who = nullptr);
  /// Runs one tick of the loop: re-simulate on late input, finalize, step,
  /// broadcast. Call at the tick's scheduled time.
  void on_tick(TimePoint now);
  /// Ends the match (shutdown, timeout, or the tick budget): tells the
  /// clients, finishes the replay.
  void end(const std::string& reason, TimePoint now);

  Phase phase() const { return phase_; }
  const MatchConfig& config() const { return config_; }
  /// Counters, with the rollback figures folded in.
  MatchStats stats() const;
  /// Joined players still heard from: not timed out, not gone.
  uint32_t players_connected() const { return seats_.players_connected(); }
  /// Whether the client at `endpoint` holds `slot` (a player slot, or
  /// players + a spectator seat) now: joined, and neither dropped by the
  /// peer timeout nor gone. The secure gateway asks, so that it lets a
  /// token for another client take a slot exactly when the match would.
  bool seated(uint32_t slot, const Endpoint& endpoint) const {
    return seats_.seated(slot, endpoint);
  }
  Tick current_tick() const { return session_->current_tick(); }
  /// The server's clock in ticks: negative during the start countdown.
  Tick server_tick() const { return session_->current_tick() - countdown_ticks_; }
  Tick last_final_tick() const { return finalizer_.next_final() - 1; }
  const net::RollbackSession& session() const { return *session_; }
  /// Final ticks still held for resending, oldest first.
  const std::deque<v1::FinalTick>& recent_finals() const { return finalizer_.held().ticks(); }

  /// Publishes every final tick, a state every feed->info().keyframe_ticks
  /// and the players' names to `feed` from now on (spectating browsers:
  /// LiveFeed). Attach before the first tick; null detaches.
  void attach_live_feed(std::shared_ptr<LiveFeed> feed) {
    recorder_.attach_live_feed(std::move(feed));
  }

  /// Test hook: sees every resync snapshot right after it is serialized,
  /// before the server checks that it loads, and may damage it; fault
  /// tests use it to drive the refusal path. Empty by default.
  using SnapshotHook = MatchResync::SnapshotHook;
  void set_resync_snapshot_hook(SnapshotHook hook) { resync_.set_snapshot_hook(std::move(hook)); }

  MatchHost(const MatchConfig& config, SendFn send, std::unique_ptr<net::RollbackSession> session,
            std::optional<replay::ReplayWriter> replay, TimePoint now, MatchEnvironment env);

 private:
  void handle_join(const v1::JoinRequest& request, const Endpoint& from, TimePoint now,
                   const Admission& who);
  void handle_input(Seat& seat, uint32_t player, const v1::InputFrame& frame);
  void start_match(TimePoint now);
  void send_match_start(Seat& seat, TimePoint now);
  void send_match_end(TimePoint now);
  void time_out_silent_seats(TimePoint now);
  void close_if_done(TimePoint now);
  void broadcast(TimePoint now);

  MatchConfig config_;
  MatchStats stats_;
  std::unique_ptr<net::RollbackSession> session_;
  MatchSeats seats_;
  MatchOutbox outbox_;
  MatchRecorder recorder_;  // the replay and the live feed
  MatchFinalizer finalizer_;
  InputRelay relay_;
  MatchAdmission admission_;
  MatchResync resync_;
  Phase phase_ = Phase::kLobby;
  int32_t countdown_ticks_ = 0;
  TimePoint closing_deadline_;
  TimePoint created_;
  TimePoint started_;
  TimePoint tick_started_;
  TimePoint ended_;
  // The messages of the hot path live on arenas reset after each use: a
  // datagram parsed (receive_arena_) and the tick's datagram to every
  // client (broadcast_arena_) cost no allocation once their first blocks
  // are warm. Two arenas, because a datagram can start the match, whose
  // messages must not be freed under the one being handled.
  static constexpr size_t kReceiveArenaBytes = 8 * 1024;
  static constexpr size_t kBroadcastArenaBytes = 32 * 1024;
  std::unique_ptr<char[]> arena_blocks_;
  google::protobuf::Arena receive_arena_;
  google::protobuf::Arena broadcast_arena_;
};

}  // namespace rwd::server
