// SPDX-License-Identifier: MIT
#pragma once
// The state behind ClientProtocol: the orchestrator of its parts, each a
// class of its own with its own state -
//   ServerChannel      the wire: connection, cookie or handshake, sealing, outbox
//   TickClock          the tick clock, the server's tick, pings and the round trip
//   InputSender        our inputs until acknowledged, the final-tick acknowledgement
//   FinalTickVerifier  relayed and final inputs, checksums checked as ticks are simulated
//   DesyncRecovery     the desync report, the resync snapshot, loading or refusing it
// - and what ties them together: the phase (joining, lobby, running, ending),
// our seat, the rollback session they all act on, the events and the stats.
// The parts hold no references to one another (DesyncRecovery is handed
// the channel it sends on, call by call); every decision that involves two
// of them is made here. client_protocol.cpp has the lifecycle and the ticking,
// client_receive.cpp the dispatch of what the server sends.
#include <chrono>
#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <utility>

#include "desync_recovery.h"
#include "final_tick_verifier.h"
#include "input_sender.h"
#include "rewind/client/client_protocol.h"
#include "server_channel.h"
#include "tick_clock.h"

namespace rwd::client {

struct ClientProtocol::Impl {
  static constexpr auto kJoinResend = std::chrono::milliseconds(250);

  Impl(const ClientConfig& config, uint64_t join_nonce);

  // client_protocol.cpp
  void connect(TimePoint now);
  int update(TimePoint now);
  void disconnect(const std::string& reason, TimePoint now);
  void send_join(TimePoint now);
  void step_due_ticks(TimePoint now);
  void verify_finals(TimePoint now);
  void send_inputs(TimePoint now);
  void finish_ending(TimePoint now);
  void emit(ClientEvent event) { events_.push_back(std::move(event)); }
  ClientStats stats() const;

  // client_receive.cpp
  void receive(std::span<const uint8_t> datagram, TimePoint now);
  void handle(const v1::Envelope& envelope, TimePoint now);
  void on_join_accept(const v1::JoinAccept& accept, TimePoint now);
  void on_match_start(const v1::MatchStart& start, TimePoint now);
  void on_match_end(const v1::MatchEnd& end, TimePoint now);
  void on_final_ticks(const v1::FinalTicks& finals, TimePoint now);
  void on_resync_chunk(const v1::ResyncChunk& chunk, TimePoint now);

  ClientConfig config_;
  ClientPhase phase_ = ClientPhase::kIdle;
  uint64_t nonce_ = 0;
  uint32_t player_ = 0;
  bool spectator_ = false;  // a read-only seat: no inputs of our own
  uint32_t player_count_ = 0;
  std::unique_ptr<net::RollbackSession> session_;

  ServerChannel channel_{kMaxQueuedDatagrams};
  TickClock clock_;
  InputSender inputs_;
  FinalTickVerifier finals_;
  DesyncRecovery resync_;

  TimePoint joined_at_;
  TimePoint last_join_sent_;
  Tick end_tick_ = kNoTick;
  std::string end_reason_;
  TimePoint ending_deadline_;

  std::deque<ClientEvent> events_;
  /// The counters the parts do not keep themselves (stats() adds theirs).
  ClientStats stats_;
};

}  // namespace rwd::client
