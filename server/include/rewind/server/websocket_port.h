// SPDX-License-Identifier: MIT
#pragma once
// A match's door for browser players. Browsers cannot send UDP, so the
// server's WebSocket endpoint (websocket_endpoint.h) carries each of their
// datagrams as one binary message, and hands it to the match through this
// port: the match reads it once a tick beside its UDP socket, with the same
// call, and answers through it. The bytes are the UDP path's bytes: a
// secure match's browser sends connect tokens, challenge responses and
// sealed packets, and the match's gateway checks them exactly as it checks
// a UDP peer's.
//
// Each connection gets an endpoint of its own in the IPv6 discard prefix
// 100::/64 (RFC 6666), which no real peer has: the match tells its peers
// apart by endpoint and never needs to know which transport one came over.
//
// Thread-safe: the endpoint's thread attaches, delivers and detaches; the
// match's strand drains and sends.
#include <asio/ip/udp.hpp>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::server {

/// One WebSocket connection as a match sees it; the endpoint implements it.
class WebSocketPeer {
 public:
  virtual ~WebSocketPeer() = default;
  /// Sends one datagram as one binary message. Thread-safe, never blocks:
  /// the message is queued for the endpoint's thread, and dropped (like a
  /// lost datagram) when the connection's queue is full or it has closed.
  virtual void send(std::vector<uint8_t> message) = 0;
  /// Closes the connection once what was sent before has left. Thread-safe.
  virtual void close() = 0;
};

class WebSocketPort {
 public:
  using Endpoint = asio::ip::udp::endpoint;
  /// `bytes` and `from` are valid only during the call.
  using ReceiveHandler = std::function<void(std::span<const uint8_t> bytes, const Endpoint& from)>;

  /// Datagrams waiting for the match at most; more are dropped (counted)
  /// until it drains: a flood from browsers costs the match no more memory
  /// than a full UDP receive buffer would.
  static constexpr size_t kMaxWaiting = 4096;
  /// Connections at once per match, spectators included.
  static constexpr size_t kMaxConnections = 256;

  /// True for the endpoints this port hands out, and for no UDP peer.
  static bool is_websocket_endpoint(const Endpoint& endpoint);

  /// Counters since creation, readable from any thread.
  struct Stats {
    uint64_t connections = 0;   ///< ever attached
    uint64_t open = 0;          ///< attached now
    uint64_t refused = 0;       ///< attach() refused: closed, or kMaxConnections open
    uint64_t datagrams_in = 0;  ///< delivered to the match
    uint64_t bytes_in = 0;
    uint64_t dropped_in = 0;  ///< kMaxWaiting reached, or the port closed
    uint64_t datagrams_out = 0;
    uint64_t bytes_out = 0;
    uint64_t dropped_out = 0;  ///< sent to a connection that has gone
  };

  // --- The endpoint's side -------------------------------------------------

  /// Registers a new connection; `tcp_port` is the browser's own port, kept
  /// in the endpoint for logs. kNotFound once the port is closed,
  /// kCapacity at kMaxConnections.
  Result<Endpoint> attach(std::shared_ptr<WebSocketPeer> peer, uint16_t tcp_port);
  /// The connection has ended: the match's sends to it are dropped from
  /// now on (its seat times out as a silent UDP peer's does).
  void detach(const Endpoint& endpoint);
  /// One message from a connection, copied for the match.
  void deliver(const Endpoint& from, std::span<const uint8_t> bytes);

  // --- The match's side ----------------------------------------------------

  /// Hands every datagram waiting now to `handler`, in arrival order;
  /// returns how many. Same contract as PolledUdpSocket::drain.
  size_t drain(const ReceiveHandler& handler);
  /// Sends one datagram to the connection behind `to`.
  void send(std::span<const uint8_t> bytes, const Endpoint& to);
  /// Refuses new connections and closes every open one after what was
  /// already sent (the match's last words). Idempotent.
  void close();

  Stats stats() const;

 private:
  struct Waiting {
    Endpoint from;
    size_t offset = 0;
    size_t size = 0;
  };

  mutable std::mutex mutex_;
  bool closed_ = false;
  uint64_t next_serial_ = 1;
  std::unordered_map<uint64_t, std::shared_ptr<WebSocketPeer>> peers_;  // by serial
  std::vector<Waiting> waiting_;
  std::vector<uint8_t> waiting_bytes_;
  // Swapped with the two above by drain(), so the handler runs unlocked
  // and neither side allocates once both have grown.
  std::vector<Waiting> draining_;
  std::vector<uint8_t> draining_bytes_;
  Stats stats_;
};

}  // namespace rwd::server
