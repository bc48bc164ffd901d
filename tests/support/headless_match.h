// SPDX-License-Identifier: MIT
#pragma once
// A whole hosted match in one thread on a simulated clock: the real
// MatchHost, real client SDK sessions (detached: no sockets) and scripted
// protocol peers, joined by a simulated network with latency, jitter and
// loss. Nothing waits for the wall clock, so a 100,000-tick match (28
// minutes at 60 Hz) plays in as long as the simulations take to step.
//
// The SDK sessions predict, roll back, verify every final checksum, report
// desyncs and resync, exactly as in a game. The scripted peers
// (scripted_peer.h) only speak the protocol through the real envelope codec
// and connection layer: they join, send their inputs ahead of the server
// with redundancy, acknowledge final ticks and say goodbye. They let a
// 16-player match run at the cost of a few simulations instead of
// seventeen. A secure match puts the server's SecureGateway in front of the
// host and gives every peer a connect token, as rewind-server does with a
// key.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "rewind/client/client_session.h"
#include "rewind/core/player_input.h"
#include "rewind/server/match_host.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/server/tokenless_gateway.h"
#include "scripted_peer.h"

namespace rwd::test {

struct HeadlessConfig {
  server::MatchConfig match;  ///< players = SDK clients + scripted peers
  /// Connect tokens and sealed datagrams, through the server's gateway.
  bool secure = false;
  /// How many of the peers are client SDK sessions; the rest are scripted.
  uint32_t sdk_clients = 2;
  /// Rollback depth of the SDK sessions.
  int32_t snapshot_ticks = 96;
  /// This SDK client (index among the SDK clients) corrupts its own state
  /// right after simulating `corrupt_at_tick` (ClientConfig's test hook).
  int32_t corrupt_client = -1;
  Tick corrupt_at_tick = kNoTick;
  double latency_ms = 20.0;  ///< one way, each direction
  double jitter_ms = 5.0;    ///< uniform +- on every datagram (reorders them)
  double loss = 0.0;         ///< probability a datagram is dropped, each direction
  uint64_t seed = 1;         ///< seeds the network's random decisions
  InputScript inputs;        ///< every player's inputs; neutral when empty
  int updates_per_tick = 2;  ///< client updates per server tick period
  /// Ticks the host on the wall clock's grid of the tick period (sleeping in
  /// between, as a live server does) instead of back to back: the host work
  /// then runs after an idle wait, with whatever that costs on the machine
  /// (cold caches, a waking core). Simulated time is unchanged.
  bool wall_paced = false;
  /// Gives up (the run reports it) after this much simulated time.
  double max_match_seconds = 7200.0;
};

/// What one SDK client saw.
struct SdkClientResult {
  uint32_t player = 0;
  client::ClientStats stats;
  /// Every event except kFinalTick, in order.
  std::vector<client::ClientEvent> events;
  uint64_t final_tick_events = 0;
  bool ended = false;  ///< reached kMatchEnded
  uint64_t count(client::ClientEventType type) const;
};

struct HeadlessResult {
  server::MatchStats server;
  std::vector<SdkClientResult> clients;
  uint32_t scripted_peers_finished = 0;  ///< scripted peers that saw the end and left
  double simulated_seconds = 0.0;
  bool timed_out = false;  ///< max_match_seconds passed before everything ended
  /// Wall time the host spent in on_tick and on_datagram (the server's
  /// whole work: simulation, finalization, intake, broadcast, encoding,
  /// and in a secure match the gateway's opening and sealing),
  /// and the server ticks it ran, for the host benchmark.
  double host_busy_seconds = 0.0;
  /// The same, tick by tick: each tick with the datagrams the host took
  /// since the tick before. On a shared machine a few ticks are stretched
  /// by preemption; their median is not.
  std::vector<double> host_tick_seconds;
  uint64_t host_ticks = 0;
  uint64_t datagrams_to_clients = 0;
};

/// Which way a datagram travels; for link filters.
enum class Direction : uint8_t { kToServer, kToClient };
/// Sees every datagram that survived loss; may change it, or return false to
/// drop it. `peer` is the index of the peer (SDK clients first).
using LinkFilter =
    std::function<bool(Direction direction, uint32_t peer, std::vector<uint8_t>& datagram)>;

class HeadlessMatch {
 public:
  /// Builds the host (the replay file is opened here) and the peers.
  static Result<std::unique_ptr<HeadlessMatch>> create(const HeadlessConfig& config);

  /// Plays the match to its end: joins, runs until the server's tick budget
  /// ends it and every peer has left (or the time limit passes).
  HeadlessResult run();

  void set_link_filter(LinkFilter filter) { filter_ = std::move(filter); }
  server::MatchHost& host() { return *host_; }

  class Peer;
  HeadlessMatch(const HeadlessConfig& config, TimePoint start);
  ~HeadlessMatch();

 private:
  struct InFlight {
    TimePoint at;
    uint64_t order = 0;  // FIFO among datagrams due at the same time
    Direction direction = Direction::kToServer;
    uint32_t peer = 0;
    std::vector<uint8_t> bytes;
    bool operator>(const InFlight& other) const {
      return at != other.at ? at > other.at : order > other.order;
    }
  };
  void transmit(Direction direction, uint32_t peer, std::span<const uint8_t> bytes);
  void deliver_due();
  server::Endpoint endpoint_of(uint32_t peer) const;
  /// The wall clock's seconds at a simulated time (token expiry).
  int64_t unix_seconds(TimePoint at) const;

  HeadlessConfig config_;
  TimePoint now_;
  TimePoint start_;
  int64_t unix_start_s_ = 0;
  std::unique_ptr<server::SecureGateway> gateway_;  ///< secure matches only
  std::unique_ptr<server::MatchHost> host_;
  /// The front door a tokenless server puts before the host (address
  /// cookies), so the peers join as they would over a socket.
  std::unique_ptr<server::TokenlessGateway> tokenless_;  ///< tokenless matches only
  std::vector<std::unique_ptr<Peer>> peers_;
  std::priority_queue<InFlight, std::vector<InFlight>, std::greater<>> in_flight_;
  uint64_t next_order_ = 0;
  std::mt19937_64 rng_;
  LinkFilter filter_;
  std::chrono::steady_clock::duration host_busy_{};
  std::chrono::steady_clock::duration busy_before_{};  // host_busy_ at the last tick
  std::vector<double> host_tick_seconds_;
  uint64_t host_ticks_ = 0;
  uint64_t datagrams_to_clients_ = 0;
};

/// Aggressive crates play for long matches: everyone drives into the same
/// corner for a while (pile-ups, and escapes where the arena lets them),
/// then another corner, with bursts of free-for-all; jumps and dashes all
/// the time. A pure function of (seed, player, tick).
rwd::PlayerInput aggressive_crates_input(uint64_t seed, uint32_t player, Tick tick);

}  // namespace rwd::test
