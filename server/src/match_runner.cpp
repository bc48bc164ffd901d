// SPDX-License-Identifier: MIT
#include "rewind/server/match_runner.h"

#include <asio/post.hpp>
#include <chrono>
#include <cmath>
#include <exception>

#include "rewind/server/server_log.h"

namespace rwd::server {
namespace {

int64_t unix_seconds() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Result<std::shared_ptr<MatchRunner>> MatchRunner::create(asio::io_context& io,
                                                         const Settings& given, EndedFn on_ended) {
  Settings settings = given;
  settings.match.secure = settings.server_key.has_value();
  if (Status status = settings.match.validate(); !status.ok()) return status;
  auto runner = std::make_shared<MatchRunner>(io, settings, std::move(on_ended));
  MatchRunner* self = runner.get();
  auto socket = net::PolledUdpSocket::open(settings.bind_address, settings.port);
  if (!socket.ok()) return socket.status();
  runner->socket_ = std::move(*socket);
  runner->port_ = runner->socket_->local_port();
  if (settings.websocket) runner->websocket_ = std::make_shared<WebSocketPort>();
  // The callbacks below run on the strand only (from the match's own
  // handlers), and the runner outlives them: they die with its members.
  const auto send_raw = [self](const Endpoint& to, std::span<const uint8_t> bytes) {
    self->send_raw(bytes, to);
  };
  if (settings.server_key) {
    SecureGateway::Options options;
    options.slots = settings.match.players + settings.match.max_spectators;
    // The gateway lets another client's token take a slot when the match
    // has dropped its holder, and asks the match which that is.
    options.join_grace_s = static_cast<int64_t>(std::ceil(settings.match.peer_timeout_s));
    options.seated = [self](uint32_t slot, const Endpoint& endpoint) {
      return self->host_->seated(slot, endpoint);
    };
    runner->gateway_ = std::make_unique<SecureGateway>(
        *settings.server_key, settings.match.match_id, std::move(options), send_raw);
  } else {
    runner->tokenless_ = std::make_unique<TokenlessGateway>(send_raw);
  }
  LogMatchScope scope(runner->log_name());
  auto host = MatchHost::create(
      settings.match,
      [self](const Endpoint& to, std::span<const uint8_t> bytes) {
        if (self->gateway_) {
          self->gateway_->send(to, bytes);
        } else {
          self->send_raw(bytes, to);
        }
      },
      net::SteadyClock::now());
  if (!host.ok()) return host.status();
  runner->host_ = std::move(*host);
  if (settings.match.live) {
    LiveFeed::Info info;
    info.match_id = settings.match.match_id;
    info.game = settings.match.game;
    info.setup = runner->host_->session().simulation().setup();
    info.tick_rate_hz = settings.match.tick_rate_hz;
    info.keyframe_ticks = settings.match.live_keyframe_ticks;
    info.delay_ticks = settings.match.live_delay_ticks;
    runner->live_ = std::make_shared<LiveFeed>(std::move(info));
    runner->host_->attach_live_feed(runner->live_);
  }
  runner->publish();
  return runner;
}

MatchRunner::MatchRunner(asio::io_context& io, const Settings& settings, EndedFn on_ended)
    : settings_(settings),
      strand_(asio::make_strand(io)),
      timer_(strand_),
      on_ended_(std::move(on_ended)),
      schedule_(std::chrono::nanoseconds(1'000'000'000LL / settings.match.tick_rate_hz)) {}

void MatchRunner::start() {
  asio::post(strand_, [self = shared_from_this()] {
    if (self->started_ || self->finished_) return;
    self->started_ = true;
    const TimePoint now = net::SteadyClock::now();
    self->schedule_.start(now);
    if (self->settings_.load) self->settings_.load->match_started(now);
    self->schedule_tick();
  });
}

void MatchRunner::stop(std::string reason) {
  asio::post(strand_, [self = shared_from_this(), reason = std::move(reason)] {
    if (self->finished_) return;
    if (!self->started_) {
      // Never ticked: nobody to tell; end it now.
      self->guarded("ending", [&] { self->host_->end(reason, net::SteadyClock::now()); });
      self->finish();
      return;
    }
    self->guarded("ending", [&] { self->host_->end(reason, net::SteadyClock::now()); });
    if (!self->finished_) self->socket_->flush_sends();
  });
}

MetricsSample MatchRunner::sample() const {
  std::lock_guard lock(published_mutex_);
  return published_;
}

template <typename Work>
void MatchRunner::guarded(const char* what, Work&& work) {
  LogMatchScope scope(log_name());
  try {
    work();
    return;
  } catch (const std::exception& error) {
    fail(std::string("game logic failed while ") + what + ": " + error.what());
  } catch (...) {
    fail(std::string("game logic failed while ") + what + ": unknown exception");
  }
}

void MatchRunner::fail(const std::string& reason) {
  if (!failure_.empty()) return;
  failure_ = reason;
  write_log(LogLevel::kError, reason + "; ending this match (the process goes on)");
  // The simulation may be half stepped: nothing more runs on it. end()
  // tells the clients and closes the replay after the last final tick,
  // which was made before the failure.
  try {
    host_->end(reason, net::SteadyClock::now());
  } catch (...) {
    write_log(LogLevel::kError, "ending the failed match failed too; its replay may be cut short");
  }
  finish();
}

void MatchRunner::on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, TimePoint now) {
  if (finished_) return;
  if (!gateway_) {
    guarded("handling a datagram", [&] {
      tokenless_->on_datagram(
          bytes, from, now,
          [this, now](std::span<const uint8_t> envelope, const Endpoint& sender,
                      const Admission* who) { host_->on_datagram(envelope, sender, now, who); });
    });
    return;
  }
  guarded("handling a datagram", [&] {
    gateway_->on_datagram(
        bytes, from, unix_seconds(),
        [this, now](std::span<const uint8_t> envelope, const Endpoint& sender,
                    const Admission& who) { host_->on_datagram(envelope, sender, now, &who); });
  });
}

void MatchRunner::send_raw(std::span<const uint8_t> bytes, const Endpoint& to) {
  if (websocket_ && WebSocketPort::is_websocket_endpoint(to)) {
    websocket_->send(bytes, to);
  } else {
    socket_->queue_send(bytes, to);
  }
}

void MatchRunner::schedule_tick() {
  timer_.expires_at(schedule_.due());
  timer_.async_wait([self = shared_from_this()](const std::error_code& error) {
    if (!error) self->on_tick_timer();
  });
}

// The match reads its socket once a tick, right before ticking, instead of
// waking for every datagram: one wake-up a tick rather than one for each of
// every player's packets, and the datagrams it sends in answer leave
// together with the tick's broadcast. Nothing is later for it: the host
// takes inputs into the tick they arrived before either way, and answers
// joins and handshakes within a tick.
void MatchRunner::on_tick_timer() {
  if (finished_) return;
  const TimePoint now = net::SteadyClock::now();
  schedule_.begin(now);
  socket_->drain([this, now](std::span<const uint8_t> bytes, const Endpoint& from) {
    // No real peer has a browser's endpoint: one that claims it is forged.
    if (!WebSocketPort::is_websocket_endpoint(from)) on_datagram(bytes, from, now);
  });
  if (websocket_ && !finished_) {
    websocket_->drain([this, now](std::span<const uint8_t> bytes, const Endpoint& from) {
      on_datagram(bytes, from, now);
    });
  }
  if (!finished_) guarded("ticking", [&] { host_->on_tick(now); });
  if (!finished_) socket_->flush_sends();
  // Wall time, for operators and the load policy only: nothing in the
  // match reads it.
  const TimePoint done = net::SteadyClock::now();
  tick_time_.observe(done - now);
  // Ticks stay on their absolute grid, so they never drift: a late loop
  // runs the due ticks back to back, and after a long stall (a stopped
  // process, a starved thread) the grid restarts instead of bursting.
  const int64_t dropped = finished_ ? 0 : schedule_.end(done);
  if (settings_.load) {
    settings_.load->record_tick(now, done - now, schedule_.behind() > 0,
                                static_cast<uint64_t>(dropped));
  }
  if (finished_) return;
  if (dropped > 0) {
    LogMatchScope scope(log_name());
    write_log(LogLevel::kWarning, "tick loop stalled; dropped " + std::to_string(dropped) +
                                      " ticks and restarted the schedule");
  }
  publish();
  if (host_->phase() == MatchHost::Phase::kEnded) {
    finish();
    return;
  }
  schedule_tick();
}

void MatchRunner::finish() {
  if (finished_) return;
  finished_ = true;
  timer_.cancel();
  if (started_ && settings_.load) settings_.load->match_ended();
  socket_->flush_sends();  // the match's last words: its end, to every client
  socket_->close();
  if (websocket_) websocket_->close();  // after its last words too
  publish();
  ended_.store(true, std::memory_order_release);
  if (on_ended_) on_ended_(*this);
}

void MatchRunner::publish() {
  MetricsSample sample;
  sample.match = id();
  sample.stats = host_->stats();
  if (gateway_) {
    const SecureGateway::Stats& g = gateway_->stats();
    sample.stats.secure = true;
    sample.stats.secure_challenges = g.challenges;
    sample.stats.secure_sessions = g.connects;
    sample.stats.secure_refused = g.refused;
    sample.stats.secure_dropped = g.dropped;
  } else if (tokenless_) {
    sample.stats.address_cookies = tokenless_->stats().cookies;
    sample.stats.cookies_refused = tokenless_->stats().refused;
  }
  if (!failure_.empty()) sample.stats.end_reason = failure_;
  const net::PolledUdpSocket::Stats& udp = socket_->stats();
  sample.stats.udp_bytes_in = udp.bytes_received;
  sample.stats.udp_bytes_out = udp.bytes_sent;
  if (websocket_) {
    const WebSocketPort::Stats ws = websocket_->stats();
    sample.stats.websocket_connections = ws.connections;
    sample.stats.websocket_bytes_in = ws.bytes_in;
    sample.stats.websocket_bytes_out = ws.bytes_out;
  }
  sample.phase = finished_ ? MatchHost::Phase::kEnded : host_->phase();
  sample.players_connected = finished_ ? 0 : host_->players_connected();
  sample.tick_time = tick_time_;
  sample.tick_lateness = schedule_.lateness();
  sample.ticks_behind = schedule_.behind();
  sample.stats.ticks_late = schedule_.late();
  sample.stats.ticks_missed = schedule_.missed();
  sample.stats.tick_lateness_max_s = static_cast<double>(schedule_.lateness().max_ns()) / 1e9;
  std::lock_guard lock(published_mutex_);
  published_ = std::move(sample);
}

}  // namespace rwd::server
