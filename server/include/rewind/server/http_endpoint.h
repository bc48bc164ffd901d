// SPDX-License-Identifier: MIT
#pragma once
// One HTTP/1.1 listener with its own thread and its own connection budget
// (Boost.Beast on Boost.Asio). The server opens one for /metrics and one
// for the control API, so neither can starve the other and neither runs
// on a thread that ticks matches. One request per connection.
//
// A hostile client cannot hold the endpoint: every connection has a
// deadline from accept to close; at the connection cap the newest arrival
// evicts the connection that has been waiting longest without sending a
// whole request (or that is done and only draining), so sockets opened and
// left silent give way to a scraper that sends its request at once; only
// when every connection is mid-request does a newcomer get 503.
//
// Beast stays inside http_endpoint.cpp: this header names no Boost type.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::server {

/// A request as the handler sees it: whole, parsed and size-checked.
struct HttpRequest {
  std::string method;         ///< "GET", "POST", ...
  std::string target;         ///< path and query as sent, e.g. "/matches?id=duel-7"
  std::string authorization;  ///< the Authorization header's value; empty when absent
  std::string body;
  std::string peer;  ///< the client's address, e.g. "127.0.0.1"

  /// The target up to '?', and what follows it (empty without one).
  std::string_view path() const;
  std::string_view query() const;
};

struct HttpReply {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
  /// Extra headers, e.g. {"WWW-Authenticate", "Bearer"}.
  std::vector<std::pair<std::string, std::string>> headers;
};

struct HttpEndpointLimits {
  /// Request line and headers longer than this: 431.
  size_t max_header_bytes = 8 * 1024;
  /// Request bodies longer than this: 413.
  size_t max_body_bytes = 4 * 1024;
  /// From accept to close: reading the request, answering, draining.
  std::chrono::milliseconds deadline{2000};
  /// Open connections at once; see the eviction rule above.
  size_t max_connections = 16;
};

/// TLS for an endpoint, from PEM files read once at open().
struct HttpTls {
  std::string certificate_file;  ///< the server's certificate chain
  std::string private_key_file;  ///< its private key (unencrypted)
  /// Set: mutual TLS. A client must present a certificate this CA signed,
  /// or the handshake fails before any request is read.
  std::string client_ca_file;
};

class HttpEndpoint {
 public:
  /// Answers one request; runs on the endpoint's thread, one at a time.
  /// It must not block for long: the endpoint serves nobody meanwhile.
  using Handler = std::function<HttpReply(const HttpRequest&)>;
  using Limits = HttpEndpointLimits;

  /// Counters since open(), readable from any thread.
  struct Stats {
    uint64_t answered = 0;      ///< 2xx
    uint64_t refused = 0;       ///< 4xx/5xx from the handler (401, 403, 404, 409, ...)
    uint64_t bad_requests = 0;  ///< requests that did not parse or were too large
    uint64_t timed_out = 0;     ///< closed at the deadline before a whole request arrived
    uint64_t evicted = 0;       ///< closed to make room for a newer connection
    uint64_t busy = 0;          ///< refused with 503: every connection was mid-request
    uint64_t tls_failures = 0;  ///< TLS handshakes that failed (no or a foreign certificate)
  };

  /// Listens on `address` (an IPv4 or IPv6 literal) and `port` (0: any free
  /// port, see port()) and serves on a thread of its own until close().
  /// `name` ("metrics", "control") prefixes errors. With `tls` every
  /// connection is HTTPS. kInvalidArgument for an unparsable address or a
  /// TLS file that does not load, kIo when the OS refuses the bind.
  static Result<std::unique_ptr<HttpEndpoint>> open(std::string_view name, std::string_view address,
                                                    uint16_t port, Handler handler,
                                                    Limits limits = {},
                                                    const std::optional<HttpTls>& tls = {});

  uint16_t port() const { return port_; }
  Stats stats() const;
  /// Stops serving, closes every connection and joins the thread: no
  /// handler runs after it returns. Idempotent; call it from any thread
  /// but the endpoint's own (a handler must not close its endpoint).
  void close();

  HttpEndpoint(const HttpEndpoint&) = delete;
  HttpEndpoint& operator=(const HttpEndpoint&) = delete;
  ~HttpEndpoint();

  struct Impl;

 private:
  explicit HttpEndpoint(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  uint16_t port_ = 0;
};

/// Parses one whole request from `bytes` as the endpoint does, within
/// `limits`: kCapacity when the head or body is too large, kCorrupt when it
/// is not a complete HTTP/1.x request with a path target. For tests and
/// fuzzing; the endpoint reads its sockets with the same parser.
Result<HttpRequest> parse_http_request(std::string_view bytes,
                                       const HttpEndpointLimits& limits = {});

/// True for 127.0.0.0/8, ::1 and IPv4-mapped loopback; false for anything
/// else, including text that is not an address literal.
bool is_loopback_address(std::string_view address);

}  // namespace rwd::server
