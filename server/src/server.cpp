// SPDX-License-Identifier: MIT
#include "rewind/server/server.h"

#include <chrono>
#include <csignal>

#include "rewind/server/server_log.h"

namespace rwd::server {

namespace {

int64_t unix_seconds() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Result<std::unique_ptr<Server>> Server::create(const ServerConfig& given) {
  ServerConfig config = given;
  config.match.secure = config.server_key.has_value();
  if (Status status = config.match.validate(); !status.ok()) return status;
  auto io = std::make_unique<asio::io_context>(1);
  auto socket = net::UdpEndpoint::open(*io, config.bind_address, config.port);
  if (!socket.ok()) return socket.status();
  auto server = std::make_unique<Server>(config, std::move(io), std::move(*socket));
  Server* self = server.get();
  if (config.server_key) {
    server->gateway_ =
        std::make_unique<SecureGateway>(*config.server_key, config.match.match_id,
                                        config.match.players + config.match.max_spectators,
                                        [self](const Endpoint& to, std::span<const uint8_t> bytes) {
                                          self->socket_->send_to(bytes, to);
                                        });
  }
  auto host = MatchHost::create(
      config.match,
      [self](const Endpoint& to, std::span<const uint8_t> bytes) {
        if (self->gateway_) {
          self->gateway_->send(to, bytes);
        } else {
          self->socket_->send_to(bytes, to);
        }
      },
      net::SteadyClock::now());
  if (!host.ok()) return host.status();
  server->host_ = std::move(*host);
  if (config.metrics) {
    auto metrics = MetricsHttp::open(*server->io_, config.metrics->address, config.metrics->port,
                                     [self] { return render_metrics(self->metrics_sample()); });
    if (!metrics.ok()) return metrics.status();
    server->metrics_ = std::move(*metrics);
  }
  return server;
}

MatchStats Server::stats() const {
  MatchStats stats = host_->stats();
  if (gateway_) {
    const SecureGateway::Stats& g = gateway_->stats();
    stats.secure = true;
    stats.secure_challenges = g.challenges;
    stats.secure_sessions = g.connects;
    stats.secure_refused = g.refused;
    stats.secure_dropped = g.dropped;
  }
  return stats;
}

MetricsSample Server::metrics_sample() const {
  MetricsSample sample;
  sample.stats = stats();
  sample.phase = host_->phase();
  sample.players_connected = host_->players_connected();
  sample.tick_time = tick_time_;
  return sample;
}

Server::Server(const ServerConfig& config, std::unique_ptr<asio::io_context> io,
               std::optional<net::UdpEndpoint> socket)
    : config_(config),
      io_(std::move(io)),
      socket_(std::move(socket)),
      timer_(*io_),
      signals_(*io_, SIGINT, SIGTERM),
      period_(std::chrono::nanoseconds(1'000'000'000LL / config.match.tick_rate_hz)) {}

void Server::run() {
  socket_->start_receiving([this](std::span<const uint8_t> bytes, const Endpoint& from) {
    const TimePoint now = net::SteadyClock::now();
    if (!gateway_) {
      host_->on_datagram(bytes, from, now);
      return;
    }
    gateway_->on_datagram(
        bytes, from, unix_seconds(),
        [this, now](std::span<const uint8_t> envelope, const Endpoint& sender,
                    const Admission& who) { host_->on_datagram(envelope, sender, now, &who); });
  });
  signals_.async_wait([this](const std::error_code& error, int signal) {
    if (error) return;
    host_->end(std::string("stopped by signal ") + (signal == SIGINT ? "SIGINT" : "SIGTERM"),
               net::SteadyClock::now());
  });
  std::string hosting = "hosting '" + config_.match.game + "' for " +
                        std::to_string(config_.match.players) + " players on " +
                        config_.bind_address + ":" + std::to_string(socket_->local_port()) +
                        " at " + std::to_string(config_.match.tick_rate_hz) + " Hz, window " +
                        std::to_string(config_.match.window_ticks) + ", " +
                        (gateway_ ? "secure connections (connect tokens)"
                                  : "TOKENLESS (any address takes a free slot: local tests only)");
  if (metrics_) {
    const std::string& address = config_.metrics->address;
    const bool v6 = address.find(':') != std::string::npos;
    hosting += "; metrics on http://" + (v6 ? "[" + address + "]" : address) + ":" +
               std::to_string(metrics_->port()) + "/metrics";
  }
  write_log(LogLevel::kInfo, hosting);
  next_tick_ = net::SteadyClock::now() + period_;
  schedule_tick();
  io_->run();
}

void Server::schedule_tick() {
  timer_.expires_at(next_tick_);
  timer_.async_wait([this](const std::error_code& error) {
    if (!error) on_tick_timer();
  });
}

void Server::on_tick_timer() {
  const TimePoint now = net::SteadyClock::now();
  host_->on_tick(now);
  // Wall time, for operators only: nothing in the match reads it.
  tick_time_.observe(net::SteadyClock::now() - now);
  if (host_->phase() == MatchHost::Phase::kEnded) {
    // Let the last datagrams leave, then stop everything.
    if (metrics_) metrics_->close();
    signals_.cancel();
    socket_->close();
    io_->stop();
    return;
  }
  // Ticks are scheduled on an absolute grid so they never drift; after a
  // long stall (a stopped process) the grid restarts instead of bursting.
  next_tick_ += period_;
  if (now - next_tick_ > 10 * period_) {
    write_log(LogLevel::kInfo, "tick loop stalled; resetting the schedule");
    next_tick_ = now + period_;
  }
  schedule_tick();
}

}  // namespace rwd::server
