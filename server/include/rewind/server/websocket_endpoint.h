// SPDX-License-Identifier: MIT
#pragma once
// Browser players' way in (rewind-server --websocket HOST:PORT): one TCP
// port for every match of the process, where a browser opens
//   ws://HOST:PORT/matches/<match id>      (wss:// with --http-tls-cert)
// and then sends and receives binary messages, each one datagram of the UDP
// protocol. The endpoint hands them to the match's WebSocketPort, and the
// match checks them as it checks UDP datagrams: in a secure match the first
// message is a connect token from the game's backend, then the challenge
// response, then sealed packets. TLS, when on, protects the connection; the
// match's own keys protect the packets either way.
//
// The endpoint runs on a thread of its own (Boost.Beast); a match never
// waits for it. A connection whose outgoing queue is full loses the newest
// datagrams, as a congested UDP path would, instead of growing without
// bound: the protocol repairs loss, and a stalled browser costs the server a
// bounded amount of memory.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include "rewind/core/status.h"
#include "rewind/server/http_endpoint.h"
#include "rewind/server/websocket_port.h"

namespace rwd::server {

struct WebSocketLimits {
  /// Open connections at once, across matches; more are answered 503.
  size_t max_connections = 1024;
  /// From accept to the upgraded connection (TLS and HTTP handshakes).
  std::chrono::milliseconds handshake{5000};
  /// A connection that sends nothing and answers no ping for this long is
  /// closed; the endpoint pings an idle browser halfway through it.
  std::chrono::milliseconds idle{20000};
  /// Bytes waiting to leave on one connection at most; see above.
  size_t max_queued_bytes = 256 * 1024;
};

class WebSocketEndpoint {
 public:
  /// The port of the match named `match_id`; null when no such match runs
  /// here or it takes no browsers. Called on the endpoint's thread.
  using FindPort = std::function<std::shared_ptr<WebSocketPort>(std::string_view match_id)>;
  using Limits = WebSocketLimits;

  /// Counters since open(), readable from any thread.
  struct Stats {
    uint64_t upgraded = 0;      ///< connections handed to a match
    uint64_t not_found = 0;     ///< 404: no such match, or it has ended
    uint64_t not_upgrade = 0;   ///< 426: a plain HTTP request, or a bad one
    uint64_t busy = 0;          ///< 503: max_connections open
    uint64_t tls_failures = 0;  ///< TLS handshakes that failed
    uint64_t timed_out = 0;     ///< handshakes or idle connections past their limit
    uint64_t refused = 0;       ///< text or oversized messages: the connection was closed
    uint64_t dropped_out = 0;   ///< datagrams lost to a full outgoing queue
    uint64_t bytes_in = 0;      ///< message payloads read
    uint64_t bytes_out = 0;     ///< message payloads written
  };

  /// Listens on `address` (an IPv4 or IPv6 literal) and `port` (0: any free
  /// port, see port()); with `tls`, only wss://. kInvalidArgument for a bad
  /// address, limit or TLS file, kIo when the port cannot be bound.
  static Result<std::unique_ptr<WebSocketEndpoint>> open(std::string_view address, uint16_t port,
                                                         FindPort find, Limits limits = {},
                                                         const std::optional<HttpTls>& tls = {});
  ~WebSocketEndpoint();
  WebSocketEndpoint(const WebSocketEndpoint&) = delete;
  WebSocketEndpoint& operator=(const WebSocketEndpoint&) = delete;

  uint16_t port() const { return port_; }
  /// Stops accepting, closes every connection and joins the thread.
  /// Idempotent; not from the endpoint's own thread.
  void close();
  Stats stats() const;

  struct Impl;

 private:
  explicit WebSocketEndpoint(std::shared_ptr<Impl> impl);
  std::shared_ptr<Impl> impl_;
  uint16_t port_ = 0;
};

}  // namespace rwd::server
