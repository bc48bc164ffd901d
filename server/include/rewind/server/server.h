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
#include <vector>

#include "rewind/server/load_monitor.h"
#include "rewind/server/match_request.h"
#include "rewind/server/match_runner.h"
#include "rewind/server/metrics_http.h"
#include "rewind/server/metrics_text.h"

namespace rwd::server {

struct ServerConfig {
  /// Every match's settings. With more than one match in the process, the
  /// launch matches are named match_id-1, match_id-2, ..., a replay path
  /// has "{match}" replaced by the match id (or the id inserted before its
  /// extension), and desync reports go to desync_dir/<match id>/.
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
  /// (rewind-token). Set: secure connections only. Empty: tokenless.
  std::optional<net::Key> server_key;
  /// Where GET /metrics is served over HTTP (Prometheus text); unset: no
  /// endpoint. Port 0 takes any free port (see Server::metrics_port()).
  struct MetricsBind {
    std::string address;
    uint16_t port = 0;
  };
  std::optional<MetricsBind> metrics;
  /// Serves the control API (GET/POST /matches, DELETE /matches/<id>) on
  /// the metrics endpoint, which must be set; the process then runs until
  /// signalled instead of ending with its last match. Bind it to a private
  /// address: whoever reaches it can start and stop matches.
  bool control = false;
  /// The share of the match threads' time spent ticking (over the last
  /// LoadMonitor::kWindowS seconds) beyond which allocate() refuses new
  /// matches, in (0, 1]. Ticks slipping refuse them too.
  double tick_budget = 0.75;
  /// Where the matches report their ticks; null: the server makes its own
  /// with tick_budget. Shared so that a health check living longer than
  /// the Server (the Agones pinger) can read it.
  std::shared_ptr<LoadMonitor> load;
};

class Server {
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
  /// cannot be bound.
  Result<std::shared_ptr<MatchRunner>> allocate(const MatchRequest& request);
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
  /// Threads run() uses.
  uint32_t threads() const { return threads_; }

  explicit Server(const ServerConfig& config);
  ~Server();

 private:
  /// The match config for `id`, with its replay and desync paths.
  MatchConfig config_for(const MatchConfig& base, const std::string& id) const;
  Result<std::shared_ptr<MatchRunner>> add_match(const MatchConfig& config, uint16_t port);
  void on_match_ended();
  void stop_all(const std::string& reason);
  void maybe_finish();
  std::optional<HttpAnswer> route(std::string_view method, std::string_view target);
  std::string matches_json() const;
  bool many() const { return config_.matches > 1 || config_.control; }

  ServerConfig config_;
  asio::io_context io_;
  asio::strand<asio::io_context::executor_type> strand_;  ///< signals, HTTP, bookkeeping
  asio::signal_set signals_;
  std::unique_ptr<MetricsHttp> metrics_;  ///< null without ServerConfig::metrics
  uint32_t threads_ = 1;
  std::shared_ptr<LoadMonitor> load_;
  std::atomic<uint64_t> refused_{0};  ///< allocations refused as overloaded
  std::vector<uint16_t> launch_ports_;
  std::vector<std::shared_ptr<MatchRunner>> launch_;  ///< started by run()
  bool stopping_ = false;  ///< on the strand: a signal came, matches are ending
  bool finished_ = false;  ///< on the strand: run() is returning

  mutable std::mutex matches_mutex_;
  std::vector<std::shared_ptr<MatchRunner>> matches_;  ///< creation order
};

}  // namespace rwd::server
