// SPDX-License-Identifier: MIT
#pragma once
// A minimal HTTP/1.1 responder for Prometheus scrapes and the control API,
// on one executor (the server's process strand): GET /metrics answers the
// exposition text, other targets go to an optional router (404 without one
// or when it declines), a malformed or oversized request 400. One request per
// connection. Every connection has a deadline and their number is capped,
// so a slow or hostile client holds a socket for at most the deadline and
// never blocks the tick loop: nothing here waits except asynchronously.
#include <asio/any_io_executor.hpp>
#include <asio/io_context.hpp>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "rewind/sim/status.h"

namespace rwd::server {

struct MetricsHttpLimits {
  /// A request line and headers longer than this get 400.
  size_t max_header_bytes = 8 * 1024;
  /// From accept to close: reading the request, writing the answer.
  std::chrono::milliseconds deadline{2000};
  /// Connections beyond this are closed at once (after a 503).
  size_t max_connections = 16;
};

/// A routed request's answer.
struct HttpAnswer {
  std::string status = "200 OK";  ///< "201 Created", "409 Conflict", ...
  std::string content_type = "application/json";
  std::string body;
};

class MetricsHttp {
 public:
  /// Builds the body of a 200 answer; called once per GET /metrics.
  using RenderFn = std::function<std::string()>;
  /// Answers a request for any target but /metrics (`target` is the path
  /// with its query, as sent); nullopt: 404. Request bodies are not read:
  /// arguments travel in the query.
  using RouteFn =
      std::function<std::optional<HttpAnswer>(std::string_view method, std::string_view target)>;
  using Limits = MetricsHttpLimits;

  /// Counters since open().
  struct Stats {
    uint64_t answered = 0;      ///< 2xx
    uint64_t not_found = 0;     ///< 404s
    uint64_t bad_requests = 0;  ///< other answers: 400s, refused control calls
    uint64_t timed_out = 0;     ///< closed at the deadline before a full request arrived
    uint64_t busy = 0;          ///< refused: max_connections were open
  };

  /// Listens on `address` (IPv4 or IPv6 literal) and `port` (0 = any free
  /// port; see port()) and starts accepting on `io`. Errors: kInvalidArgument
  /// for an unparsable address, kIo when the OS refuses the bind.
  static Result<std::unique_ptr<MetricsHttp>> open(asio::io_context& io, std::string_view address,
                                                   uint16_t port, RenderFn render,
                                                   Limits limits = {}, RouteFn route = {});
  /// The same on `executor`: every handler, render and route call runs
  /// there, one at a time when it is a strand.
  static Result<std::unique_ptr<MetricsHttp>> open(const asio::any_io_executor& executor,
                                                   std::string_view address, uint16_t port,
                                                   RenderFn render, Limits limits = {},
                                                   RouteFn route = {});

  /// The whole answer to one request head (the request line and headers
  /// through the blank line), with `Connection: close`.
  static std::string respond(std::string_view head, const RenderFn& render,
                             const RouteFn& route = {});

  /// Stops accepting and closes every open connection. Idempotent; no
  /// handler touches this object afterwards, even if the io_context runs on.
  /// Call it on the executor given to open().
  void close();
  uint16_t port() const { return port_; }
  const Stats& stats() const;

  MetricsHttp(const MetricsHttp&) = delete;
  MetricsHttp& operator=(const MetricsHttp&) = delete;
  ~MetricsHttp();

 private:
  struct State;
  class Connection;
  MetricsHttp(std::shared_ptr<State> state, uint16_t port);
  static void accept_next(const std::shared_ptr<State>& state);

  // Shared with pending operations, which may complete after this is gone.
  std::shared_ptr<State> state_;
  uint16_t port_;
};

}  // namespace rwd::server
