// SPDX-License-Identifier: MIT
#pragma once
// One hosted match: lobby, tick loop body, input intake and relay,
// finalization with substitution, final-tick broadcast, desync reports,
// resync snapshots and the replay file. It never touches a socket or a
// clock: the server shell hands it datagrams and the steady time, it sends
// through a callback, and the wall clock and files it needs (a replay's
// date, desync reports) come through a MatchEnvironment. That keeps every
// rule here testable on its own.
#include <google/protobuf/arena.h>
#include <asio/ip/udp.hpp>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/net/chunked_transfer.h"
#include "rewind/net/connection.h"
#include "rewind/net/connection_id.h"
#include "rewind/net/rollback_session.h"
#include "rewind/replay/replay_writer.h"
#include "rewind/server/desync_forensics.h"
#include "rewind/server/final_tick_log.h"
#include "rewind/server/live_feed.h"
#include "rewind/server/match_config.h"
#include "rewind/server/match_environment.h"
#include "rewind/server/match_recorder.h"
#include "rewind/server/match_stats.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

using Endpoint = asio::ip::udp::endpoint;
using TimePoint = net::TimePoint;

class MatchHost {
 public:
  using SendFn = std::function<void(const Endpoint&, std::span<const uint8_t>)>;
  /// kLobby: waiting for every slot. kRunning: counting down to tick 0,
  /// then ticking. kClosing: the match is over; final ticks are still
  /// resent until acknowledged. kEnded: nothing more to do.
  enum class Phase : uint8_t { kLobby, kRunning, kClosing, kEnded };

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
  uint32_t players_connected() const;
  /// Whether the client at `endpoint` holds `slot` (a player slot, or
  /// players + a spectator seat) now: joined, and neither dropped by the
  /// peer timeout nor gone. The secure gateway asks, so that it lets a
  /// token for another client take a slot exactly when the match would.
  bool seated(uint32_t slot, const Endpoint& endpoint) const;
  Tick current_tick() const { return session_->current_tick(); }
  /// The server's clock in ticks: negative during the start countdown.
  Tick server_tick() const { return session_->current_tick() - countdown_ticks_; }
  Tick last_final_tick() const { return next_final_ - 1; }
  const net::RollbackSession& session() const { return *session_; }
  /// Final ticks still held for resending, oldest first.
  const std::deque<v1::FinalTick>& recent_finals() const { return finals_.ticks(); }

  /// Publishes every final tick, a state every feed->info().keyframe_ticks
  /// and the players' names to `feed` from now on (spectating browsers:
  /// LiveFeed). Attach before the first tick; null detaches.
  void attach_live_feed(std::shared_ptr<LiveFeed> feed);

  /// Test hook: sees every resync snapshot right after it is serialized,
  /// before the server checks that it loads, and may damage it; fault
  /// tests use it to drive the refusal path. Empty by default.
  using SnapshotHook = std::function<void(Tick tick, std::vector<uint8_t>& bytes)>;
  void set_resync_snapshot_hook(SnapshotHook hook) { snapshot_hook_ = std::move(hook); }

  MatchHost(const MatchConfig& config, SendFn send, std::unique_ptr<net::RollbackSession> session,
            std::optional<replay::ReplayWriter> replay, TimePoint now, MatchEnvironment env);

 private:
  struct DesyncAssembly {
    // What the report says, every chunk alike (filled in once it is whole).
    uint32_t report_id = 0;
    Tick tick = kNoTick;
    uint64_t client_checksum = 0;
    uint64_t server_checksum = 0;                         // ours, as the client received it
    net::ChunkAssembler chunks{net::kDesyncChunkLimits};  // the client's state dump
  };
  struct Peer {
    bool joined = false;
    bool connected = false;
    Endpoint endpoint;
    uint64_t join_nonce = 0;
    uint64_t client_id = 0;  // secure mode: the client its token names
    std::optional<net::Connection> connection;
    Tick final_seen = kNoTick;          // newest final tick the client has acknowledged
    Tick final_sent = kNoTick;          // newest final tick sent at least once
    Tick resync_tick = kNoTick;         // a resync snapshot at this tick awaits acknowledgement
    std::vector<uint8_t> resync_bytes;  // that snapshot, resent as is until acknowledged
    uint64_t resync_checksum = 0;
    uint32_t resync_id = 0;
    Tick resend_cursor = kNoTick;  // round-robin position among unacknowledged finals
    // The first final tick the client applies without the one before it
    // (the match's first, or a resync snapshot's): sent standalone; later
    // ticks go packed against the tick before.
    Tick standalone_from = 0;
    bool left = false;  // sent Disconnect: nothing more is taken from it
    int32_t last_lead = 0;
    bool sent_input = false;
    TimePoint last_receive;
    std::string name;
    DesyncAssembly desync;
    std::vector<uint32_t> handled_reports;  // recent report ids, to count each once
    TimePoint last_resync;
    bool resynced_once = false;
    TimePoint last_report_stored;
    uint32_t reports_stored = 0;
  };

  void handle_join(const v1::Envelope& envelope, const Endpoint& from, TimePoint now,
                   const Admission* who);
  void handle_input(Peer& peer, uint32_t player, const v1::InputFrame& frame);
  void handle_desync(Peer& peer, uint32_t player, const v1::DesyncReport& report, TimePoint now);
  void store_desync_report(uint32_t player, const DesyncAssembly& assembly,
                           std::span<const uint8_t> dump);
  void send_resync(Peer& peer, TimePoint now);
  bool start_resync_episode(Peer& peer);
  void on_resync_refused(Peer& peer, uint32_t player, const v1::ResyncRequest& request);
  std::optional<uint64_t> final_checksum(Tick tick) const;
  void send_resync_chunks(Peer& peer, TimePoint now);
  /// Adds final ticks to `out` within `budget` encoded bytes.
  void add_final_ticks(Peer& peer, v1::FinalTicks& out, size_t budget);
  /// A new connection takes a slot mid-match: per-connection state starts
  /// over, so the broadcast sends it a snapshot and final ticks after it.
  void restart_peer(Peer& peer);
  /// In the lobby: a seat whose holder left or went silent for the peer
  /// timeout is free again, so a squatter cannot hold it until the start.
  void free_silent_lobby_seats(TimePoint now);
  void start_match(TimePoint now);
  void send_match_start(Peer& peer, TimePoint now);
  void send_match_end(TimePoint now);
  void close_if_done(TimePoint now);
  void finalize_ready_ticks();
  void broadcast(TimePoint now);
  /// One client's datagram of the tick (`id`: slot, or players + seat).
  void broadcast_to(Peer& peer, uint32_t id, Tick oldest_held, TimePoint now);
  /// Takes a spectator seat for a join request; false when none is free.
  bool seat_spectator(const v1::JoinRequest& request, const Endpoint& from, TimePoint now,
                      const Admission* who, uint32_t* id);
  void send(Peer& peer, v1::Envelope& envelope, TimePoint now);
  void send_unconnected(const Endpoint& to, v1::Envelope& envelope);
  Peer* find_peer(uint64_t connection_id, uint32_t* player);

  MatchConfig config_;
  SendFn send_;
  std::unique_ptr<net::RollbackSession> session_;
  MatchRecorder recorder_;  // the replay and the live feed
  Phase phase_ = Phase::kLobby;
  std::vector<Peer> peers_;       // the player slots, by slot
  std::vector<Peer> spectators_;  // read-only seats; seat s is id players + s
  FinalTickLog finals_;           // held for the clients, oldest first
  // Inputs accepted since the last broadcast, relayed in it to every other
  // client; with each run's encoded size.
  struct RelayRun {
    uint32_t player = 0;
    Tick first_tick = 0;
    std::vector<rwd::PlayerInput> inputs;
  };
  std::vector<RelayRun> relay_batch_;
  std::vector<std::string> relay_packed_;    // each run packed, at broadcast
  std::vector<rwd::PlayerInput> relay_run_;  // the run being gathered
  Tick next_final_ = 0;
  int32_t countdown_ticks_ = 0;
  // Substitution masks of the last kFinalHistory final ticks, to tell a
  // resend of an input the server had from one that came too late, and
  // their checksums, for desync reports on ticks every client has seen.
  struct FinalRecord {
    Tick tick = kNoTick;
    uint64_t substituted = 0;
    uint64_t checksum = 0;
  };
  static constexpr size_t kFinalHistory = 1024;
  std::vector<FinalRecord> final_history_;
  TimePoint closing_deadline_;
  TimePoint created_;
  TimePoint started_;
  TimePoint tick_started_;
  TimePoint ended_;
  MatchStats stats_;
  uint32_t next_snapshot_id_ = 1;
  net::ConnectionIdGenerator ids_;  // unguessable by other clients
  std::vector<uint8_t> encode_buffer_;
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
  std::vector<rwd::PlayerInput> final_inputs_;
  SnapshotHook snapshot_hook_;
  DesyncForensics forensics_;
};

/// "lobby", "running", "closing" or "ended": the phase as the metrics and
/// the control API name it.
const char* phase_name(MatchHost::Phase phase);

}  // namespace rwd::server
