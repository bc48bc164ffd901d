// SPDX-License-Identifier: MIT
#pragma once
// The state behind ClientProtocol, shared by the files that implement it:
// client_protocol.cpp (lifecycle, tick clock, inputs, sending),
// client_receive.cpp (decoding and dispatching the server's datagrams,
// join and start), client_finals.cpp (relayed inputs, final ticks) and
// client_resync.cpp (desync report, resync assembly).
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "datagram_queue.h"
#include "rewind/client/client_protocol.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/chunked_transfer.h"
#include "rewind/net/connection.h"
#include "rewind/net/secure_channel.h"
#include "rewind/net/time_sync.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::client {

struct ClientProtocol::Impl {
  Impl(const ClientConfig& config, uint64_t join_nonce);

  // client_protocol.cpp
  void connect(TimePoint now);
  int update(TimePoint now);
  void send_join(TimePoint now);
  void step_due_ticks(TimePoint now);
  void verify_finals(TimePoint now);
  void send_inputs(TimePoint now);
  void finish_ending(TimePoint now);
  /// Stamps, encodes (and seals, on a secure connection) and queues.
  void send(v1::Envelope& envelope, TimePoint now);
  /// Queues a datagram as is.
  void transmit(std::span<const uint8_t> datagram);
  void emit(ClientEvent event) { events_.push_back(std::move(event)); }
  double period_s() const { return 1.0 / tick_rate_hz_; }

  // client_receive.cpp
  void receive(std::span<const uint8_t> datagram, TimePoint now);
  void handle(const v1::Envelope& envelope, TimePoint now);
  void on_join_accept(const v1::JoinAccept& accept, TimePoint now);
  void on_match_start(const v1::MatchStart& start, TimePoint now);
  void on_match_end(const v1::MatchEnd& end, TimePoint now);
  void on_pong(const v1::Pong& pong, TimePoint now);

  // client_finals.cpp
  void on_final_ticks(const v1::FinalTicks& finals, TimePoint now);
  /// Applies the next final tick; its inputs may be packed against those
  /// of the tick before (last_final_inputs_).
  bool apply_final_tick(const v1::FinalTick& final_tick, TimePoint now);
  /// Another player's inputs as the server relayed them.
  void on_relayed(uint32_t player, Tick first_tick, std::span<const rwd::PlayerInput> inputs);

  // client_resync.cpp
  void request_resync(TimePoint now);
  void send_desync_report(TimePoint now);
  void on_resync_chunk(const v1::ResyncChunk& chunk, TimePoint now);
  void load_resync(const v1::ResyncChunk& last_chunk, TimePoint now);
  void refuse_resync(uint32_t snapshot_id, Tick tick, const std::string& reason, TimePoint now);
  void send_resync_request(TimePoint now);

  ClientConfig config_;
  net::Connection connection_{TimePoint{}};
  ClientPhase phase_ = ClientPhase::kIdle;
  uint64_t nonce_ = 0;
  uint32_t player_ = 0;
  bool spectator_ = false;  // a read-only seat: no inputs of our own
  uint32_t player_count_ = 0;
  uint32_t tick_rate_hz_ = 60;
  std::unique_ptr<net::RollbackSession> session_;
  net::TimeSync time_sync_;
  InputProvider provider_;
  rwd::PlayerInput held_input_;

  // The tick clock: fractional ticks, advanced by the time given scaled by
  // the time sync, so steps happen at the right moments.
  double tick_clock_ = 0.0;
  TimePoint last_update_;
  TimePoint joined_at_;
  TimePoint last_join_sent_;
  TimePoint last_ping_;
  Tick next_input_tick_ = 0;  // first tick whose input is not yet taken
  std::deque<std::pair<Tick, rwd::PlayerInput>> unacked_;
  Tick input_ack_ = kNoTick;
  Tick last_final_received_ = kNoTick;
  /// Last final tick our state is known to agree on: verified, or passed
  /// over by a resync snapshot whose checksum matched.
  Tick agreed_through_ = kNoTick;
  std::deque<std::pair<Tick, uint64_t>> pending_finals_;  // (tick, server checksum)
  std::map<Tick, v1::FinalTick> early_finals_;            // arrived ahead of a gap, bounded
  /// The final inputs of tick last_final_received_ (empty after a resync:
  /// the server then sends the next tick standalone).
  std::vector<rwd::PlayerInput> last_final_inputs_;
  std::vector<rwd::PlayerInput> final_inputs_buffer_;
  std::vector<rwd::PlayerInput> relayed_buffer_;
  std::vector<proto::RelayedRun> relayed_runs_;
  Tick last_final_acked_ = kNoTick;  // last_final_received_ as last sent
  /// Since when an acknowledgement of new final ticks has waited for an
  /// input packet to carry it (meaningful while ack_waiting_).
  TimePoint ack_waiting_since_;
  bool ack_waiting_ = false;
  int report_sends_ = 0;
  int32_t server_tick_ = 0;
  bool awaiting_resync_ = false;
  Tick end_tick_ = kNoTick;
  std::string end_reason_;
  TimePoint ending_deadline_;
  Tick desync_tick_ = kNoTick;
  uint64_t desync_server_checksum_ = 0;
  uint64_t desync_local_checksum_ = 0;
  uint32_t report_id_ = 0;
  TimePoint last_report_sent_;
  uint32_t refused_snapshot_id_ = 0;  // the last snapshot that did not load, 0 = none
  std::string refused_reason_;
  net::ChunkAssembler resync_{net::kResyncChunkLimits};

  std::deque<ClientEvent> events_;
  DatagramQueue outbox_{kMaxQueuedDatagrams};
  ClientStats stats_;
  std::vector<uint8_t> encode_buffer_;
  // Tokenless servers: the cookie that admits our join (net/address_cookie.h),
  // asked for with a Hello, and when it came (it is asked for again before
  // the server stops taking it).
  std::optional<net::AddressCookie> cookie_;
  TimePoint cookie_at_;
  std::vector<uint8_t> hello_;
  std::vector<uint8_t> framed_buffer_;
  // Secure connections (ClientConfig::connect_token): the handshake, its
  // response (resent with the join until the server speaks), and buffers.
  std::optional<net::ClientHandshake> handshake_;
  std::vector<uint8_t> handshake_response_;
  bool secure_confirmed_ = false;
  std::vector<uint8_t> sealed_buffer_;
  std::vector<uint8_t> opened_buffer_;
  std::vector<uint8_t> state_buffer_;
};

}  // namespace rwd::client
