// SPDX-License-Identifier: MIT
#pragma once
// A game client's side of a hosted match: join, submit inputs, predict the
// other players and roll back when their real inputs arrive, compare our
// checksum with the server's for every final tick, report a desync and
// resynchronize from the server's snapshot.
//
// Threading: everything runs on the caller's io_context thread. Call
// update(now) regularly (every frame, or every millisecond or so from a
// timer); it steps as many ticks as the tick clock says are due.
//
// A session made with create_detached() has no socket: it hands its
// datagrams to a callback and takes the server's through receive(), and
// its only clock is the times it is given (another transport, or a
// simulated clock in headless tests).
#include <asio/io_context.hpp>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/client/client_config.h"
#include "rewind/client/client_event.h"
#include "rewind/game/player_input.h"
#include "rewind/net/connection.h"
#include "rewind/net/fault_injector.h"
#include "rewind/net/rollback_session.h"
#include "rewind/net/secure_channel.h"
#include "rewind/net/time_sync.h"
#include "rewind/net/udp_endpoint.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::client {

using TimePoint = net::TimePoint;

class ClientSession {
 public:
  /// Supplies our input for a tick, once per tick, when that tick is first
  /// simulated.
  using InputProvider = std::function<game::PlayerInput(Tick tick)>;
  /// kEnding: the server ended the match; the last final ticks are still
  /// being received and verified before kMatchEnded is reported.
  enum class Phase : uint8_t { kIdle, kJoining, kLobby, kRunning, kEnding, kEnded };

  /// Opens a UDP socket on an ephemeral port. Errors: bad address, socket.
  static Result<std::unique_ptr<ClientSession>> create(asio::io_context& io,
                                                       const ClientConfig& config);
  /// Datagrams for the server, from a detached session.
  using SendFn = std::function<void(std::span<const uint8_t> datagram)>;
  /// A session without a socket: every datagram for the server goes to
  /// `send`, and the server's datagrams come in through receive(). The
  /// address fields of `config` are unused; `config.faults` needs a socket
  /// and is refused (kInvalidArgument), as is a bad snapshot_ticks.
  static Result<std::unique_ptr<ClientSession>> create_detached(const ClientConfig& config,
                                                                SendFn send);
  /// Hands the session one datagram from the server, received at `now`.
  /// Sessions with a socket receive on their own.
  void receive(std::span<const uint8_t> datagram, TimePoint now);

  /// Starts joining (JoinRequest resent until answered).
  void connect(TimePoint now);
  /// Sets the input provider; by default the last set_input() value is held.
  void set_input_provider(InputProvider provider) { provider_ = std::move(provider); }
  /// The input used for every tick from now on (when no provider is set).
  void set_input(const game::PlayerInput& input) { held_input_ = input; }
  /// Advances the tick clock, steps due ticks, verifies final ticks, sends
  /// what is due. Returns the number of ticks stepped.
  int update(TimePoint now);
  /// Pops the oldest pending event.
  bool poll_event(ClientEvent& out);
  /// Sends a Disconnect and stops.
  void disconnect(const std::string& reason, TimePoint now);

  Phase phase() const { return phase_; }
  uint32_t player() const { return player_; }
  ClientStats stats() const;
  /// The local simulation (predicted present), or nullptr before joining.
  const game::Simulation* simulation() const {
    return session_ ? &session_->simulation() : nullptr;
  }
  const net::RollbackSession* rollback() const { return session_.get(); }
  /// The socket's port; 0 for a detached session.
  uint16_t local_port() const { return socket_ ? socket_->local_port() : 0; }

  ClientSession(asio::io_context& io, const ClientConfig& config, net::UdpEndpoint socket,
                asio::ip::udp::endpoint server);
  ClientSession(const ClientConfig& config, SendFn send);
  ~ClientSession();

 private:
  void on_datagram(std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& from);
  void handle(const v1::Envelope& envelope, TimePoint now);
  void on_join_accept(const v1::JoinAccept& accept, TimePoint now);
  void on_match_start(const v1::MatchStart& start, TimePoint now);
  void on_final_ticks(const v1::FinalTicks& finals, TimePoint now);
  /// Applies the next final tick; its inputs may be packed against those
  /// of the tick before (last_final_inputs_).
  bool apply_final_tick(const v1::FinalTick& final_tick, TimePoint now);
  void request_resync(TimePoint now);
  void finish_ending(TimePoint now);
  void on_resync_chunk(const v1::ResyncChunk& chunk, TimePoint now);
  void refuse_resync(uint32_t snapshot_id, Tick tick, const std::string& reason, TimePoint now);
  void send_resync_request(TimePoint now);
  void step_due_ticks(TimePoint now);
  void verify_finals(TimePoint now);
  void send_inputs(TimePoint now);
  void send_desync_report(TimePoint now);
  void send(v1::Envelope& envelope, TimePoint now);
  /// Another player's inputs as the server relayed them.
  void on_relayed(uint32_t player, Tick first_tick, std::span<const game::PlayerInput> inputs);
  /// Puts a datagram on the wire (or the detached sender, or the faults).
  void transmit(std::span<const uint8_t> datagram);
  /// Reads config.connect_token into the session's handshake.
  static Status use_connect_token(ClientSession& session, const ClientConfig& config);
  void emit(ClientEvent event) { events_.push_back(std::move(event)); }
  double period_s() const { return 1.0 / tick_rate_hz_; }

  ClientConfig config_;
  SendFn send_;  // set for a detached session
  std::optional<net::UdpEndpoint> socket_;
  asio::ip::udp::endpoint server_;
  std::optional<net::FaultyLink> outbound_faults_;
  std::optional<net::FaultyLink> inbound_faults_;
  net::Connection connection_;
  Phase phase_ = Phase::kIdle;
  uint64_t nonce_ = 0;
  uint32_t player_ = 0;
  bool spectator_ = false;  // a read-only seat: no inputs of our own
  uint32_t player_count_ = 0;
  uint32_t tick_rate_hz_ = 60;
  std::unique_ptr<net::RollbackSession> session_;
  net::TimeSync time_sync_;
  InputProvider provider_;
  game::PlayerInput held_input_;

  // The tick clock: fractional ticks, advanced by wall time scaled by the
  // time sync, so steps happen at the right moments.
  double tick_clock_ = 0.0;
  TimePoint last_update_;
  TimePoint joined_at_;
  TimePoint last_join_sent_;
  TimePoint last_ping_;
  Tick next_input_tick_ = 0;  // first tick whose input is not yet taken
  std::deque<std::pair<Tick, game::PlayerInput>> unacked_;
  Tick input_ack_ = kNoTick;
  Tick last_final_received_ = kNoTick;
  std::deque<std::pair<Tick, uint64_t>> pending_finals_;  // (tick, server checksum)
  std::map<Tick, v1::FinalTick> early_finals_;            // arrived ahead of a gap, bounded
  /// The final inputs of tick last_final_received_ (empty after a resync:
  /// the server then sends the next tick standalone).
  std::vector<game::PlayerInput> last_final_inputs_;
  std::vector<game::PlayerInput> final_inputs_buffer_;
  std::vector<game::PlayerInput> relayed_buffer_;
  std::vector<proto::RelayedRun> relayed_runs_;
  Tick last_final_acked_ = kNoTick;  // last_final_received_ as last sent
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
  struct ResyncAssembly {
    uint32_t snapshot_id = 0;
    Tick tick = kNoTick;
    uint64_t checksum = 0;
    uint32_t total_size = 0;
    uint32_t received = 0;
    std::vector<std::string> chunks;
  } resync_;

  std::deque<ClientEvent> events_;
  ClientStats stats_;
  std::vector<uint8_t> encode_buffer_;
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
