// SPDX-License-Identifier: MIT
#pragma once
// The process shell around a MatchHost: owns the io_context, the UDP
// socket, the tick timer, the signal set and the optional metrics endpoint
// (Asio's layered-server shape).
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>
#include <memory>
#include <optional>
#include <string>

#include "rewind/net/udp_endpoint.h"
#include "rewind/server/match_host.h"
#include "rewind/server/metrics_http.h"
#include "rewind/server/metrics_text.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/server/tick_histogram.h"

namespace rwd::server {

struct ServerConfig {
  MatchConfig match;
  std::string bind_address = "0.0.0.0";
  uint16_t port = 7777;
  /// The key shared with the match backend that mints connect tokens
  /// (rewind-token). Set: secure connections only. Empty: tokenless.
  std::optional<net::Key> server_key;
  /// Where GET /metrics is served over HTTP (Prometheus text); unset: no
  /// endpoint. Port 0 takes any free port (see Server::metrics_port()).
  struct MetricsBind {
    std::string address;
    uint16_t port = 0;
  };
  std::optional<MetricsBind> metrics;
};

class Server {
 public:
  /// Binds the socket and prepares the match. Errors name what failed
  /// (bad config, port in use, replay path not writable).
  static Result<std::unique_ptr<Server>> create(const ServerConfig& config);
  /// Runs until the match ends (tick budget, lobby timeout, SIGINT/SIGTERM).
  void run();
  /// The match's counters, with the secure gateway's folded in.
  MatchStats stats() const;
  uint16_t port() const { return socket_->local_port(); }
  /// The metrics endpoint's TCP port; 0 when there is none.
  uint16_t metrics_port() const { return metrics_ ? metrics_->port() : 0; }
  /// What a scrape of the metrics endpoint reports now.
  MetricsSample metrics_sample() const;

  Server(const ServerConfig& config, std::unique_ptr<asio::io_context> io,
         std::optional<net::UdpEndpoint> socket);

 private:
  void schedule_tick();
  void on_tick_timer();

  ServerConfig config_;
  std::unique_ptr<asio::io_context> io_;
  std::optional<net::UdpEndpoint> socket_;
  std::unique_ptr<SecureGateway> gateway_;  ///< null in tokenless mode
  std::unique_ptr<MatchHost> host_;
  std::unique_ptr<MetricsHttp> metrics_;  ///< null without ServerConfig::metrics
  asio::steady_timer timer_;
  asio::signal_set signals_;
  std::chrono::nanoseconds period_;
  TimePoint next_tick_;
  TickHistogram tick_time_;  ///< wall time of each MatchHost::on_tick
};

}  // namespace rwd::server
