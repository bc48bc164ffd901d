// SPDX-License-Identifier: MIT
#pragma once
// ClientProtocol on a UDP socket: the session opens the socket, reads the
// steady clock for what it receives, puts the protocol's datagrams on the
// wire (through simulated network faults when ClientConfig::faults asks for
// them) and otherwise forwards to the protocol (client_protocol.h says what
// the protocol does).
//
// Threading: everything runs on the caller's io_context thread. Call
// update(now) regularly (every frame, or every millisecond or so from a
// timer); it steps as many ticks as the tick clock says are due.
//
// A session made with create_detached() has no socket: it hands its
// datagrams to a callback and takes the server's through receive(), and
// its only clock is the times it is given (another transport, or a
// simulated clock in headless tests).
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "rewind/client/client_config.h"
#include "rewind/client/client_event.h"
#include "rewind/client/client_protocol.h"

namespace asio {
class io_context;  // asio/io_context.hpp, needed only by callers of create()
}  // namespace asio

namespace rwd::client {

class ClientSession {
 public:
  using InputProvider = ClientProtocol::InputProvider;
  using Phase = ClientPhase;

  /// Opens a UDP socket on an ephemeral port. `io` must outlive the
  /// session. Errors (kInvalidArgument): bad address, bad fault
  /// configuration, those of ClientProtocol::create(); socket errors.
  static Result<std::unique_ptr<ClientSession>> create(asio::io_context& io,
                                                       const ClientConfig& config);
  /// Datagrams for the server, from a detached session.
  using SendFn = std::function<void(std::span<const uint8_t> datagram)>;
  /// A session without a socket: every datagram for the server goes to
  /// `send`, and the server's datagrams come in through receive(). The
  /// address fields of `config` are unused; `config.faults` needs a socket
  /// and is refused (kInvalidArgument), as are an empty `send` and the
  /// errors of ClientProtocol::create().
  static Result<std::unique_ptr<ClientSession>> create_detached(const ClientConfig& config,
                                                                SendFn send);
  /// Hands the session one datagram from the server, received at `now`.
  /// Sessions with a socket receive on their own.
  void receive(std::span<const uint8_t> datagram, TimePoint now);

  /// Starts joining (JoinRequest resent until answered).
  void connect(TimePoint now);
  /// Sets the input provider; by default the last set_input() value is held.
  void set_input_provider(InputProvider provider) {
    protocol_.set_input_provider(std::move(provider));
  }
  /// The input used for every tick from now on (when no provider is set).
  Status set_input(const rwd::PlayerInput& input) { return protocol_.set_input(input); }
  /// Advances the tick clock, steps due ticks, verifies final ticks, sends
  /// what is due. Returns the number of ticks stepped.
  int update(TimePoint now);
  /// Pops the oldest pending event.
  bool poll_event(ClientEvent& out) { return protocol_.poll_event(out); }
  /// Sends a Disconnect and stops.
  void disconnect(const std::string& reason, TimePoint now);

  Phase phase() const { return protocol_.phase(); }
  uint32_t player() const { return protocol_.player(); }
  /// The protocol's figures, plus datagrams from other addresses counted
  /// as received and rejected.
  ClientStats stats() const;
  /// The local simulation (predicted present), or nullptr before joining.
  const game::Simulation* simulation() const { return protocol_.simulation(); }
  const net::RollbackSession* rollback() const { return protocol_.rollback(); }
  /// The socket's port; 0 for a detached session.
  uint16_t local_port() const;

  ClientSession(const ClientSession&) = delete;
  ClientSession& operator=(const ClientSession&) = delete;
  ~ClientSession();

 private:
  struct Socket;  // client_session.cpp: the socket, the server's address, the faults

  ClientSession(ClientProtocol protocol, SendFn send);
  /// Puts what the protocol queued on the wire (or the detached sender).
  void flush();
  /// A datagram from the socket (after the inbound faults).
  void on_socket_datagram(std::span<const uint8_t> bytes, bool from_server);

  ClientProtocol protocol_;
  SendFn send_;  // set for a detached session
  std::unique_ptr<Socket> socket_;
  uint64_t foreign_datagrams_ = 0;  // from addresses other than the server's
};

}  // namespace rwd::client
