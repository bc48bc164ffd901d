// SPDX-License-Identifier: MIT
#pragma once
// The process shell: one io_context run by a pool of threads, the signal
// set, the optional metrics and control endpoint, and the matches it hosts
// (MatchRunner, each on its own strand and UDP port). Matches are started
// at launch (ServerConfig::matches) or allocated by a control call
// (POST /matches); a match whose game logic fails ends alone.
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>
#include <asio/strand.hpp>
#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/server/api_keys.h"
#include "rewind/server/control_api.h"
#include "rewind/server/http_endpoint.h"
#include "rewind/server/live_api.h"
#include "rewind/server/load_monitor.h"
#include "rewind/server/match_request.h"
#include "rewind/server/match_runner.h"
#include "rewind/server/metrics_text.h"
#include "rewind/server/websocket_endpoint.h"

namespace rwd::server {

struct ServerConfig {
  /// Every match's settings. With more than one match in the process, the
  /// launch matches are named match_id-1, match_id-2, ..., a replay path
  /// has "{match}" replaced by the match id (or the id inserted before its
  /// extension), and desync reports go to `desync_dir/<match id>/`.
  MatchConfig match;
  std::string bind_address = "0.0.0.0";
  /// The first launch match's UDP port; match i binds port + i. 0: each
  /// binds any free port (see ports()).
  uint16_t port = 7777;
  /// Matches started at launch, [0, max_matches]; 0 only with control.
  uint32_t matches = 1;
  /// Most matches alive at once, launch and control together, [1, 256].
  uint32_t max_matches = 16;
  /// Threads running the matches; 0: one per core, at most one per match.
  uint32_t threads = 0;
  /// The key shared with the match backend that mints connect tokens
  /// (rewind-token). Set: secure connections only. Empty: tokenless, which
  /// is refused on a non-loopback bind_address unless
  /// insecure_tokenless_public is set.
  std::optional<net::Key> server_key;
  /// Allows tokenless mode on an address other hosts reach (a network the
  /// operator trusts); run() then warns loudly.
  bool insecure_tokenless_public = false;
  /// An HTTP endpoint's address: an IPv4 or IPv6 literal and a TCP port
  /// (0: any free port).
  struct HttpBind {
    std::string address;
    uint16_t port = 0;
  };
  using MetricsBind = HttpBind;
  /// Where GET /metrics is served (Prometheus text); unset: no endpoint.
  /// On an address other than loopback it needs metrics_keys.
  std::optional<HttpBind> metrics;
  /// Set: every scrape must carry a bearer key of this file.
  std::optional<ApiKeys> metrics_keys;
  /// Set: both HTTP endpoints speak only HTTPS; with a client CA, mutual
  /// TLS (which also lets /metrics leave loopback without metrics_keys).
  std::optional<HttpTls> http_tls;
  /// Serves the control API (ControlApi: GET/POST /matches, DELETE
  /// `/matches/<id>`) on control_bind, with control_keys required; the
  /// process then runs until signalled instead of ending with its last
  /// match.
  bool control = false;
  HttpBind control_bind{"127.0.0.1", 7790};
  std::optional<ApiKeys> control_keys;
  ControlPolicy control_policy;
  /// Serves browsers spectating every match (LiveApi): each match
  /// publishes to a LiveFeed (MatchConfig::live is set for all). Read-only
  /// and without keys, like a broadcast: with hidden information in a
  /// game, hold spectators back with MatchConfig::live_delay_ticks.
  std::optional<HttpBind> live;
  /// Where browser players connect (WebSocketEndpoint): every match takes
  /// them at `/matches/<match id>` beside its UDP players. wss:// with
  /// http_tls's certificate (never mutual: browsers bring no client
  /// certificate); unset: UDP only.
  std::optional<HttpBind> websocket;
  WebSocketLimits websocket_limits;
  /// The built viewer (the build's viewer_web) served on the live
  /// endpoint; empty: the data routes and the listing only.
  std::string live_viewer_dir;
  /// Seconds the live endpoint may stay up after the last match ended, so
  /// spectators see its last ticks and its end, [0, 60]: it closes once no
  /// spectator has polled for 2 s.
  double live_linger_s = 10.0;
  /// The share of the match threads' time spent ticking (over the last
  /// LoadMonitor::kWindowS seconds) beyond which allocate() refuses new
  /// matches, in (0, 1]. Ticks slipping refuse them too.
  double tick_budget = 0.75;
  /// Where the matches report their ticks; null: the server makes its own
  /// with tick_budget. Shared so that a health check living longer than
  /// the Server (the Agones pinger) can read it.
  std::shared_ptr<LoadMonitor> load;
};

/// kInvalidArgument when `config` is tokenless on an address that parses
/// and is not loopback, without insecure_tokenless_public; the message says
/// how to run secure. Server::create checks it; a caller that does work
/// before creating the server (an Agones lifecycle) checks it first.
Status check_tokenless_exposure(const ServerConfig& config);

class Server final : private ControlTarget {
 public:
  /// Binds every launch match's socket and the metrics endpoint. Errors
  /// name what failed (bad config, port in use, replay path not writable).
  static Result<std::unique_ptr<Server>> create(const ServerConfig& config);
  /// Runs until every match has ended (tick budgets, lobby timeouts, game
  /// logic failures) or, with control, until SIGINT/SIGTERM; a signal ends
  /// every match (its clients are told) and then the process.
  void run();
  /// Ends every match (its clients are told) and then run(), as SIGTERM
  /// does. Thread-safe; for embedders and tests.
  void shutdown(const std::string& reason);
  /// Allocates and starts a match; thread-safe. kInvalidArgument for a bad
  /// config or an id already alive, kCapacity when max_matches are
  /// alive or the server is overloaded ("overloaded: ...": the tick load is
  /// over ServerConfig::tick_budget, or ticks slip), kIo when the port
  /// cannot be bound. `owner`: the control API caller asking; empty for
  /// the process itself.
  Result<std::shared_ptr<MatchRunner>> allocate(const MatchRequest& request,
                                                const std::string& owner = {});
  /// False while the matches' ticks slip persistently or the tick loop
  /// stalled (LoadMonitor::healthy); thread-safe.
  bool healthy() const;
  /// The process's load, as /metrics reports it; thread-safe.
  ProcessSample process_sample() const;

  /// Every match's report, launch matches first, then in allocation order
  /// (ended ones too, the newest 64 of them).
  std::vector<MetricsSample> samples() const;
  /// The first launch match's counters (the only match in the common case).
  MatchStats stats() const;
  /// The launch matches' UDP ports, in order.
  std::vector<uint16_t> ports() const { return launch_ports_; }
  uint16_t port() const { return launch_ports_.empty() ? 0 : launch_ports_.front(); }
  /// The metrics endpoint's TCP port; 0 when there is none.
  uint16_t metrics_port() const { return metrics_ ? metrics_->port() : 0; }
  /// The live endpoint's TCP port; 0 without it.
  uint16_t live_port() const { return live_ ? live_->port() : 0; }
  /// The WebSocket endpoint's TCP port; 0 without it.
  uint16_t websocket_port() const { return websocket_ ? websocket_->port() : 0; }
  /// The control API's TCP port; 0 without it.
  uint16_t control_port() const { return control_ ? control_->port() : 0; }
  /// Threads run() uses.
  uint32_t threads() const { return threads_; }

  explicit Server(const ServerConfig& config);
  ~Server();

 private:
  /// The match config for `id`, with its replay and desync paths.
  MatchConfig config_for(const MatchConfig& base, const std::string& id) const;
  Result<std::shared_ptr<MatchRunner>> add_match(const MatchConfig& config, uint16_t port,
                                                 const std::string& owner = {});
  void on_match_ended();
  void stop_all(const std::string& reason);
  void maybe_finish();
  HttpReply serve_metrics(const HttpRequest& request);
  void close_endpoints();
  /// Opens the live endpoint (ServerConfig::live) with its viewer files.
  Status open_live();
  /// Opens the WebSocket endpoint (ServerConfig::websocket).
  Status open_websocket();
  static MatchListing listing_of(const MatchRunner& match);
  // ControlTarget, on the control endpoint's thread.
  const MatchConfig& match_defaults() const override { return config_.match; }
  Result<MatchListing> allocate_match(const MatchRequest& request,
                                      const std::string& owner) override;
  std::vector<MatchListing> list_matches() const override;
  Status stop_match(std::string_view id, const std::string& reason) override;
  bool stopping() const override { return stopping_.load(std::memory_order_acquire); }
  bool many() const { return config_.matches > 1 || config_.control; }

  ServerConfig config_;
  asio::io_context io_;
  asio::strand<asio::io_context::executor_type> strand_;  ///< signals, HTTP, bookkeeping
  asio::signal_set signals_;
  // Each on its own thread, so scrapes, control calls and ticks never
  // wait for one another.
  std::unique_ptr<HttpEndpoint> metrics_;  ///< null without ServerConfig::metrics
  std::unique_ptr<ControlApi> control_api_;
  std::unique_ptr<HttpEndpoint> control_;  ///< null without ServerConfig::control
  std::unique_ptr<LiveApi> live_api_;
  std::unique_ptr<HttpEndpoint> live_;            ///< null without ServerConfig::live
  std::unique_ptr<WebSocketEndpoint> websocket_;  ///< null without ServerConfig::websocket
  uint32_t threads_ = 1;
  std::shared_ptr<LoadMonitor> load_;
  std::atomic<uint64_t> refused_{0};  ///< allocations refused as overloaded
  std::vector<uint16_t> launch_ports_;
  std::vector<std::shared_ptr<MatchRunner>> launch_;  ///< started by run()
  std::atomic<bool> stopping_{false};                 ///< a signal came, matches are ending
  bool finished_ = false;                             ///< on the strand: run() is returning

  mutable std::mutex matches_mutex_;
  std::vector<std::shared_ptr<MatchRunner>> matches_;  ///< creation order
};

}  // namespace rwd::server
