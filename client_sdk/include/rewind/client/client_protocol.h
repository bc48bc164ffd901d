// SPDX-License-Identifier: MIT
#pragma once
// A game client's side of a hosted match with no socket and no clock:
// datagrams and times go in, datagrams and events come out. It joins
// (through the secure handshake when given a connect token; otherwise
// after fetching the tokenless server's address cookie), waits in the
// lobby, submits inputs, predicts the other players and rolls back when
// their real inputs arrive, compares its checksum with the server's for
// every final tick, reports a desync and resynchronizes from the server's
// snapshot, and sees the match to its end.
//
// The caller owns the transport and the clock: after each call that takes
// a time (connect, receive, update, disconnect) it drains next_datagram()
// onto its wire. Call update(now) regularly (every frame, or every
// millisecond or so from a timer); it steps as many ticks as the tick
// clock says are due. ClientSession is this protocol on a UDP socket.
//
// Threading: none of its own; one thread at a time.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rewind/client/client_config.h"
#include "rewind/client/client_event.h"
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/net/clock.h"
#include "rewind/net/rollback_session.h"

namespace rwd::client {

using TimePoint = net::TimePoint;

/// kEnding: the server ended the match; the last final ticks are still
/// being received and verified before kMatchEnded is reported.
enum class ClientPhase : uint8_t { kIdle, kJoining, kLobby, kRunning, kEnding, kEnded };

class ClientProtocol {
 public:
  /// Supplies our input for a tick, once per tick, when that tick is first
  /// simulated.
  using InputProvider = std::function<rwd::PlayerInput(Tick tick)>;
  /// Datagrams held for the caller at most; more are dropped and counted
  /// (ClientStats::datagrams_dropped) until it drains them.
  static constexpr size_t kMaxQueuedDatagrams = 1024;

  /// `join_nonce` tells the server's answers to this join apart from those
  /// to an earlier one: pick it at random. The address and fault fields of
  /// `config` belong to the transport and are not read. Errors
  /// (kInvalidArgument): snapshot_ticks outside [16, 1024], a bad connect
  /// token.
  static Result<ClientProtocol> create(const ClientConfig& config, uint64_t join_nonce);

  ClientProtocol(ClientProtocol&&) noexcept;
  ClientProtocol& operator=(ClientProtocol&&) noexcept;
  ClientProtocol(const ClientProtocol&) = delete;
  ClientProtocol& operator=(const ClientProtocol&) = delete;
  ~ClientProtocol();

  /// Starts joining (the join request goes out now and is resent every
  /// 250 ms until answered, for at most config.join_timeout_s). Only from
  /// kIdle; otherwise nothing happens.
  void connect(TimePoint now);
  /// One datagram from the server, received at `now`. Anything that does
  /// not decode, is not for this connection, repeats or comes out of place
  /// is dropped and counted (ClientStats::packets_rejected) and changes
  /// nothing else.
  void receive(std::span<const uint8_t> datagram, TimePoint now);
  /// Advances the tick clock, steps due ticks, verifies final ticks, queues
  /// what is due. Returns the number of ticks stepped. Times must not go
  /// backwards; a time before the last one counts as no time passing.
  int update(TimePoint now);
  /// Queues a Disconnect (when connected) and stops.
  void disconnect(const std::string& reason, TimePoint now);

  /// Sets the input provider; by default the last set_input() value is held.
  /// A provided input the game's InputSpec refuses is replaced by the
  /// neutral input (the server would refuse it).
  void set_input_provider(InputProvider provider);
  /// The input used for every tick from now on (when no provider is set).
  /// Once the match is joined, an input the game's InputSpec refuses is
  /// kInvalidArgument and the held input stays; one set before is checked
  /// when sent, as a provider's is.
  Status set_input(const rwd::PlayerInput& input);

  /// The oldest datagram for the server, removed from the queue; nullopt
  /// when none is left. The bytes stay valid until the next call that
  /// takes a time.
  std::optional<std::span<const uint8_t>> next_datagram();
  /// Pops the oldest pending event.
  bool poll_event(ClientEvent& out);

  ClientPhase phase() const;
  /// Our slot (a spectator's seat is past the player slots); 0 before joining.
  uint32_t player() const;
  ClientStats stats() const;
  /// The local simulation (predicted present), or nullptr before joining.
  /// Valid while this protocol lives.
  const game::Simulation* simulation() const;
  const net::RollbackSession* rollback() const;

 private:
  struct Impl;  // client_sdk/src/client_protocol_impl.h
  explicit ClientProtocol(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rwd::client
