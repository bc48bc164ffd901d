// SPDX-License-Identifier: MIT
#pragma once
// One hosted match inside a server process: its UDP socket, its front door
// (the secure gateway, or the tokenless one), its MatchHost and its tick
// timer, all on one strand of the process's io_context, so several matches
// tick in parallel on a pool of threads while each match's handlers run one
// at a time. A failure of the game logic (anything thrown out of the match)
// ends this match only: its clients hear the end, its replay is finished as
// far as it was final, and the process and its other matches go on.
#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>
#include <asio/strand.hpp>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "rewind/net/polled_udp_socket.h"
#include "rewind/server/load_monitor.h"
#include "rewind/server/match_host.h"
#include "rewind/server/metrics_text.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/server/tick_histogram.h"
#include "rewind/server/tick_schedule.h"
#include "rewind/server/tokenless_gateway.h"
#include "rewind/server/websocket_port.h"

namespace rwd::server {

class MatchRunner : public std::enable_shared_from_this<MatchRunner> {
 public:
  struct Settings {
    MatchConfig match;
    std::string bind_address = "0.0.0.0";
    uint16_t port = 0;  ///< 0: any free port (see port())
    /// Set: secure connections only (tokens must name match.match_id).
    std::optional<net::Key> server_key;
    /// Prefix this match's log lines with its id (a process hosting more
    /// than one match does).
    bool name_in_logs = false;
    /// The control API caller that allocated the match; empty for launch
    /// matches.
    std::string owner;
    /// Where the match reports each tick's start, work and lateness (the
    /// process's load); none when null.
    std::shared_ptr<LoadMonitor> load;
    /// Also takes browser players: the process's WebSocket endpoint reaches
    /// the match through websocket_port().
    bool websocket = false;
  };
  /// Called once, on the match's strand, after the match has ended and its
  /// socket is closed. The runner may be released from there.
  using EndedFn = std::function<void(MatchRunner& runner)>;

  /// Binds the socket and builds the match (nothing runs until start()).
  /// Errors name what failed: bad config, port in use, replay not writable.
  static Result<std::shared_ptr<MatchRunner>> create(asio::io_context& io, const Settings& settings,
                                                     EndedFn on_ended);
  /// Starts receiving and ticking. Call once; thread-safe.
  void start();
  /// Ends the match (its clients are told), as a signal or an operator
  /// would. Thread-safe; nothing happens when it has already ended.
  void stop(std::string reason);

  const std::string& id() const { return settings_.match.match_id; }
  const MatchConfig& config() const { return settings_.match; }
  const std::string& owner() const { return settings_.owner; }
  uint16_t port() const { return port_; }
  bool ended() const { return ended_.load(std::memory_order_acquire); }
  /// What the match reports now (published after every tick), from any
  /// thread: the stats with the gateway's folded in, phase, players, tick
  /// times.
  MetricsSample sample() const;
  /// What browsers spectating the match read (MatchConfig::live); null
  /// without. Set at create(), never changed: safe from any thread.
  std::shared_ptr<const LiveFeed> live_feed() const { return live_; }
  /// Where the WebSocket endpoint hands this match its browsers' datagrams;
  /// null without Settings::websocket. Set at create(), never changed.
  std::shared_ptr<WebSocketPort> websocket_port() const { return websocket_; }

  MatchRunner(asio::io_context& io, const Settings& settings, EndedFn on_ended);
  MatchRunner(const MatchRunner&) = delete;
  MatchRunner& operator=(const MatchRunner&) = delete;

 private:
  void schedule_tick();
  void on_tick_timer();
  void on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, TimePoint now);
  /// Sends a datagram over the transport its peer came by.
  void send_raw(std::span<const uint8_t> bytes, const Endpoint& to);
  /// Runs `work` on the match; anything it throws ends the match.
  template <typename Work>
  void guarded(const char* what, Work&& work);
  void fail(const std::string& reason);
  void finish();
  void publish();
  std::string_view log_name() const {
    return settings_.name_in_logs ? std::string_view(id()) : std::string_view();
  }

  Settings settings_;
  asio::strand<asio::io_context::executor_type> strand_;
  asio::steady_timer timer_;
  std::optional<net::PolledUdpSocket> socket_;  ///< read once a tick, see on_tick_timer()
  uint16_t port_ = 0;
  std::shared_ptr<WebSocketPort> websocket_;     ///< null without Settings::websocket
  std::unique_ptr<SecureGateway> gateway_;       ///< null in tokenless mode
  std::unique_ptr<TokenlessGateway> tokenless_;  ///< null in secure mode
  std::unique_ptr<MatchHost> host_;
  std::shared_ptr<LiveFeed> live_;  ///< null without MatchConfig::live
  EndedFn on_ended_;
  TickSchedule schedule_;    ///< when ticks are due, how late they start
  TickHistogram tick_time_;  ///< wall time of each tick: datagrams in, MatchHost::on_tick, out
  bool started_ = false;
  bool finished_ = false;
  std::atomic<bool> ended_{false};
  std::string failure_;  ///< why the game logic failed; empty when it did not

  mutable std::mutex published_mutex_;
  MetricsSample published_;
};

}  // namespace rwd::server
