// SPDX-License-Identifier: MIT
#include "rewind/server/server.h"

#include <algorithm>
#include <asio/post.hpp>
#include <csignal>
#include <thread>

#include "rewind/cli/json_text.h"
#include "rewind/server/server_log.h"

namespace rwd::server {
namespace {

// Ended matches still listed by GET /matches and /metrics: enough for a
// backend or a scrape to see how they ended, bounded for a long-lived host.
constexpr size_t kEndedKept = 64;

HttpAnswer json_answer(std::string status, std::string body) {
  HttpAnswer answer;
  answer.status = std::move(status);
  answer.body = std::move(body) + "\n";
  return answer;
}

HttpAnswer json_error(std::string status, std::string_view message) {
  return json_answer(std::move(status), "{\"error\":" + cli::json_string(message) + "}");
}

}  // namespace

Result<std::unique_ptr<Server>> Server::create(const ServerConfig& config) {
  auto bad = [](const std::string& message) {
    return Status::Error(ErrorCode::kInvalidArgument, message);
  };
  if (config.max_matches < 1 || config.max_matches > 256) {
    return bad("max matches must be in [1, 256]");
  }
  if (config.matches > config.max_matches) return bad("more matches than max matches");
  if (config.matches == 0 && !config.control) return bad("no matches to host (0 without control)");
  if (config.control && !config.metrics) return bad("the control API needs the metrics endpoint");
  if (config.port != 0 && config.port + config.matches - 1 > 65535) {
    return bad("ports " + std::to_string(config.port) + "+" + std::to_string(config.matches) +
               " run past 65535");
  }
  if (config.threads > 64) return bad("threads must be in [0, 64]");
  if (!(config.tick_budget > 0.0 && config.tick_budget <= 1.0)) {
    return bad("tick budget must be in (0, 1]");
  }
  auto server = std::make_unique<Server>(config);
  // Checked once up front so a bad shared setting names itself, not match-1.
  MatchConfig first = server->config_for(config.match, config.match.match_id);
  first.secure = config.server_key.has_value();
  if (Status status = first.validate(); !status.ok()) return status;
  for (uint32_t i = 0; i < config.matches; ++i) {
    const std::string id = config.matches == 1
                               ? config.match.match_id
                               : config.match.match_id + "-" + std::to_string(i + 1);
    const uint16_t port = config.port == 0 ? 0 : static_cast<uint16_t>(config.port + i);
    auto runner = server->add_match(server->config_for(config.match, id), port);
    if (!runner.ok()) return runner.status();
    server->launch_ports_.push_back((*runner)->port());
    server->launch_.push_back(*runner);
  }
  if (config.metrics) {
    Server* self = server.get();
    auto metrics = MetricsHttp::open(
        server->strand_, config.metrics->address, config.metrics->port,
        [self] {
          const ProcessSample process = self->process_sample();
          return render_metrics(self->samples(), &process);
        },
        {},
        [self](std::string_view method, std::string_view target) {
          return self->route(method, target);
        });
    if (!metrics.ok()) return metrics.status();
    server->metrics_ = std::move(*metrics);
  }
  const uint32_t cores = std::max(1u, std::thread::hardware_concurrency());
  const uint32_t most = std::max(1u, config.control ? config.max_matches : config.matches);
  server->threads_ = config.threads != 0 ? config.threads : std::min(cores, most);
  server->load_->set_threads(server->threads_);
  return server;
}

Server::Server(const ServerConfig& config)
    : config_(config),
      strand_(asio::make_strand(io_)),
      signals_(strand_, SIGINT, SIGTERM),
      load_(config.load
                ? config.load
                : std::make_shared<LoadMonitor>(config.tick_budget, net::SteadyClock::now())) {}

Server::~Server() {
  io_.stop();
}

MatchConfig Server::config_for(const MatchConfig& base, const std::string& id) const {
  MatchConfig match = base;
  match.match_id = id;
  if (!many()) return match;
  if (!match.replay_path.empty()) {
    std::string& path = match.replay_path;
    const size_t placeholder = path.find("{match}");
    if (placeholder != std::string::npos) {
      path.replace(placeholder, 7, id);
    } else {
      const size_t slash = path.find_last_of('/');
      const size_t dot = path.find_last_of('.');
      const bool has_extension =
          dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
      path.insert(has_extension ? dot : path.size(), "-" + id);
    }
  }
  if (!match.desync_dir.empty()) match.desync_dir += "/" + id;
  return match;
}

Result<std::shared_ptr<MatchRunner>> Server::add_match(const MatchConfig& config, uint16_t port) {
  std::lock_guard lock(matches_mutex_);
  size_t alive = 0;
  for (const auto& match : matches_) {
    if (match->ended()) continue;
    ++alive;
    if (match->id() == config.match_id) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "a match named '" + config.match_id + "' is running");
    }
  }
  if (alive >= config_.max_matches) {
    return Status::Error(ErrorCode::kCapacity,
                         "already hosting " + std::to_string(alive) + " matches (the most)");
  }
  MatchRunner::Settings settings;
  settings.match = config;
  settings.bind_address = config_.bind_address;
  settings.port = port;
  settings.server_key = config_.server_key;
  settings.name_in_logs = many();
  settings.load = load_;
  auto runner = MatchRunner::create(
      io_, settings, [this](MatchRunner&) { asio::post(strand_, [this] { on_match_ended(); }); });
  if (!runner.ok()) return runner.status();
  matches_.push_back(*runner);
  // Forget the oldest ended matches beyond the kept few.
  size_t ended = 0;
  for (const auto& match : matches_) ended += match->ended();
  for (auto it = matches_.begin(); ended > kEndedKept && it != matches_.end();) {
    if ((*it)->ended()) {
      it = matches_.erase(it);
      --ended;
    } else {
      ++it;
    }
  }
  return *runner;
}

Result<std::shared_ptr<MatchRunner>> Server::allocate(const MatchRequest& request) {
  // A match more would slow every match already here: refused while the
  // threads are busy past the budget or ticks already slip.
  if (std::string reason = load_->overload_reason(net::SteadyClock::now()); !reason.empty()) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    write_log(LogLevel::kWarning, "refused match '" + request.match.match_id + "': " + reason);
    return Status::Error(ErrorCode::kCapacity, reason);
  }
  MatchConfig config = config_for(request.match, request.match.match_id);
  auto runner = add_match(config, request.port);
  if (!runner.ok()) return runner.status();
  (*runner)->start();
  write_log(LogLevel::kInfo, "allocated match '" + (*runner)->id() + "' ('" + config.game + "', " +
                                 std::to_string(config.players) + " players) on port " +
                                 std::to_string((*runner)->port()));
  return runner;
}

bool Server::healthy() const {
  return load_->healthy(net::SteadyClock::now());
}

ProcessSample Server::process_sample() const {
  const net::TimePoint now = net::SteadyClock::now();
  ProcessSample out;
  out.tick_load = load_->load(now).busy;
  out.tick_budget = load_->tick_budget();
  out.overloaded = !load_->overload_reason(now).empty();
  out.healthy = load_->healthy(now);
  out.matches_refused = refused_.load(std::memory_order_relaxed);
  return out;
}

std::vector<MetricsSample> Server::samples() const {
  std::vector<std::shared_ptr<MatchRunner>> matches;
  {
    std::lock_guard lock(matches_mutex_);
    matches = matches_;
  }
  std::vector<MetricsSample> out;
  out.reserve(matches.size());
  for (const auto& match : matches) out.push_back(match->sample());
  return out;
}

MatchStats Server::stats() const {
  std::lock_guard lock(matches_mutex_);
  return matches_.empty() ? MatchStats{} : matches_.front()->sample().stats;
}

void Server::run() {
  signals_.async_wait([this](const std::error_code& error, int signal) {
    if (error) return;
    const std::string reason =
        std::string("stopped by signal ") + (signal == SIGINT ? "SIGINT" : "SIGTERM");
    write_log(LogLevel::kInfo, reason + "; ending every match");
    if (!stopping_) stop_all(reason);
  });
  const std::vector<std::shared_ptr<MatchRunner>> launch = std::move(launch_);
  const std::string mode = config_.server_key
                               ? "secure connections (connect tokens)"
                               : "TOKENLESS (any address takes a free slot: local tests only)";
  for (const auto& match : launch) {
    const MatchConfig& c = match->config();
    LogMatchScope scope(launch.size() > 1 ? match->id() : std::string_view());
    write_log(LogLevel::kInfo, "hosting '" + c.game + "' for " + std::to_string(c.players) +
                                   " players on " + config_.bind_address + ":" +
                                   std::to_string(match->port()) + " at " +
                                   std::to_string(c.tick_rate_hz) + " Hz, window " +
                                   std::to_string(c.window_ticks) + ", " + mode);
    match->start();
  }
  if (metrics_) {
    const std::string& address = config_.metrics->address;
    const bool v6 = address.find(':') != std::string::npos;
    write_log(LogLevel::kInfo, std::string(config_.control ? "metrics and control" : "metrics") +
                                   " on http://" + (v6 ? "[" + address + "]" : address) + ":" +
                                   std::to_string(metrics_->port()) + "/" +
                                   (config_.control ? " (/metrics, /matches)" : "metrics"));
  }
  if (launch.size() > 1 || config_.control) {
    write_log(LogLevel::kInfo, std::to_string(launch.size()) + " matches at launch, at most " +
                                   std::to_string(config_.max_matches) + ", on " +
                                   std::to_string(threads_) + " threads, " + mode);
  }
  std::vector<std::thread> pool;
  for (uint32_t i = 1; i < threads_; ++i) pool.emplace_back([this] { io_.run(); });
  io_.run();
  for (std::thread& thread : pool) thread.join();
}

void Server::shutdown(const std::string& reason) {
  asio::post(strand_, [this, reason] {
    if (!stopping_) stop_all(reason);
  });
}

void Server::on_match_ended() {
  maybe_finish();
}

void Server::stop_all(const std::string& reason) {
  stopping_ = true;
  std::vector<std::shared_ptr<MatchRunner>> matches;
  {
    std::lock_guard lock(matches_mutex_);
    matches = matches_;
  }
  for (const auto& match : matches) match->stop(reason);
  maybe_finish();
}

// On the strand. The process ends when its last match has: at once without
// the control API, after a signal with it.
void Server::maybe_finish() {
  if (finished_) return;
  if (config_.control && !stopping_) return;
  {
    std::lock_guard lock(matches_mutex_);
    for (const auto& match : matches_) {
      if (!match->ended()) return;
    }
  }
  finished_ = true;
  if (metrics_) metrics_->close();
  signals_.cancel();
  // Nothing is left but the closed sockets' last handlers.
  io_.stop();
}

std::optional<HttpAnswer> Server::route(std::string_view method, std::string_view target) {
  if (!config_.control) return std::nullopt;
  const size_t question = target.find('?');
  const std::string_view path = target.substr(0, question);
  const std::string_view query =
      question == std::string_view::npos ? std::string_view() : target.substr(question + 1);
  if (path == "/matches") {
    if (method == "GET" || method == "HEAD") return json_answer("200 OK", matches_json());
    if (method != "POST") return json_error("405 Method Not Allowed", "GET or POST /matches");
    if (stopping_) return json_error("503 Service Unavailable", "the server is stopping");
    auto request = parse_match_request(query, config_.match);
    if (!request.ok()) return json_error("400 Bad Request", request.status().message());
    auto runner = allocate(*request);
    if (!runner.ok()) {
      const ErrorCode code = runner.status().code();
      return json_error(code == ErrorCode::kCapacity          ? "503 Service Unavailable"
                        : code == ErrorCode::kInvalidArgument ? "409 Conflict"
                                                              : "500 Internal Server Error",
                        runner.status().message());
    }
    return json_answer("201 Created", "{\"id\":" + cli::json_string((*runner)->id()) +
                                          ",\"port\":" + std::to_string((*runner)->port()) + "}");
  }
  if (path.starts_with("/matches/")) {
    const std::string_view id = path.substr(9);
    if (method != "DELETE") return json_error("405 Method Not Allowed", "DELETE /matches/<id>");
    std::shared_ptr<MatchRunner> found;
    {
      std::lock_guard lock(matches_mutex_);
      for (const auto& match : matches_) {
        if (match->id() == id && !match->ended()) found = match;
      }
    }
    if (!found) return json_error("404 Not Found", "no running match with that id");
    found->stop("stopped by the control API");
    return json_answer("202 Accepted",
                       "{\"id\":" + cli::json_string(found->id()) + ",\"stopping\":true}");
  }
  return std::nullopt;
}

std::string Server::matches_json() const {
  std::vector<std::shared_ptr<MatchRunner>> matches;
  {
    std::lock_guard lock(matches_mutex_);
    matches = matches_;
  }
  std::string out = "[";
  for (const auto& match : matches) {
    const MetricsSample s = match->sample();
    if (out.size() > 1) out += ",";
    out += "{\"id\":" + cli::json_string(match->id()) +
           ",\"port\":" + std::to_string(match->port()) +
           ",\"game\":" + cli::json_string(match->config().game) +
           ",\"players\":" + std::to_string(match->config().players) + ",\"phase\":\"" +
           phase_name(s.phase) + "\"" +
           ",\"players_connected\":" + std::to_string(s.players_connected) +
           ",\"ticks_final\":" + std::to_string(s.stats.ticks_final) +
           ",\"end_reason\":" + cli::json_string(s.stats.end_reason) + "}";
  }
  return out + "]";
}

}  // namespace rwd::server
