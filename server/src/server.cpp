// SPDX-License-Identifier: MIT
#include "rewind/server/server.h"

#include <algorithm>
#include <asio/ip/address.hpp>
#include <asio/post.hpp>
#include <csignal>
#include <filesystem>
#include <thread>

#include "rewind/server/server_log.h"

namespace rwd::server {
namespace {

// Ended matches still listed by GET /matches and /metrics: enough for a
// backend or a scrape to see how they ended, bounded for a long-lived host.
constexpr size_t kEndedKept = 64;

std::string bracketed(const std::string& address) {
  return address.find(':') != std::string::npos ? "[" + address + "]" : address;
}

}  // namespace

Status check_tokenless_exposure(const ServerConfig& config) {
  if (config.server_key || config.insecure_tokenless_public) return Status::Ok();
  // An address that does not parse fails to bind, with its own message.
  const auto exposed = [](const std::string& address) {
    std::error_code error;
    (void)asio::ip::make_address(address, error);
    return !error && !is_loopback_address(address);
  };
  std::string address;
  if (exposed(config.bind_address)) {
    address = config.bind_address;
  } else if (config.websocket && exposed(config.websocket->address)) {
    address = config.websocket->address + " (--websocket)";
  } else {
    return Status::Ok();
  }
  return Status::Error(
      ErrorCode::kInvalidArgument,
      "refusing to run tokenless on " + address +
          ", an address other hosts can reach: without connect tokens anyone who reaches the "
          "port takes a free seat. Run secure: make a server key (rewind-token keygen --out "
          "server.key), start with --key-file server.key and give each client a connect token "
          "minted with the same key (rewind-token mint). For local tests bind 127.0.0.1; on a "
          "network you trust, --insecure-tokenless-on-public-address allows it");
}

Result<std::unique_ptr<Server>> Server::create(const ServerConfig& config) {
  auto bad = [](const std::string& message) {
    return Status::Error(ErrorCode::kInvalidArgument, message);
  };
  if (config.max_matches < 1 || config.max_matches > 256) {
    return bad("max matches must be in [1, 256]");
  }
  if (config.matches > config.max_matches) return bad("more matches than max matches");
  if (config.matches == 0 && !config.control) return bad("no matches to host (0 without control)");
  if (config.control && !config.control_keys) {
    return bad(
        "the control API needs --control-keys FILE: bearer keys, one caller a line "
        "(rewind-token api-key makes one); whoever reaches it can start and stop matches");
  }
  if (config.control) {
    if (Status status = config.control_policy.validate(); !status.ok()) return status;
  }
  for (const auto& [name, bind] :
       {std::pair{"metrics", config.metrics},
        std::pair{"control", std::optional(config.control_bind)}, std::pair{"live", config.live}}) {
    std::error_code error;
    if (bind) asio::ip::make_address(bind->address, error);
    if (error) {
      return bad(std::string(name) + ": bad address '" + bind->address + "': " + error.message());
    }
  }
  const bool mutual_tls = config.http_tls && !config.http_tls->client_ca_file.empty();
  if (config.metrics && !config.metrics_keys && !mutual_tls &&
      !is_loopback_address(config.metrics->address)) {
    return bad("refusing to serve /metrics on " + config.metrics->address +
               " without --metrics-keys FILE: on an address other than loopback every scrape "
               "must carry a bearer key or a client certificate (--http-tls-client-ca), or bind "
               "127.0.0.1");
  }
  if (config.port != 0 && config.port + config.matches - 1 > 65535) {
    return bad("ports " + std::to_string(config.port) + "+" + std::to_string(config.matches) +
               " run past 65535");
  }
  if (config.threads > 64) return bad("threads must be in [0, 64]");
  if (!(config.live_linger_s >= 0.0 && config.live_linger_s <= 60.0)) {
    return bad("live linger must be in [0, 60] s");
  }
  if (!(config.tick_budget > 0.0 && config.tick_budget <= 1.0)) {
    return bad("tick budget must be in (0, 1]");
  }
  auto server = std::make_unique<Server>(config);
  // Checked once up front so a bad shared setting names itself, not match-1.
  MatchConfig first = server->config_for(config.match, config.match.match_id);
  first.secure = config.server_key.has_value();
  if (Status status = first.validate(); !status.ok()) return status;
  if (Status status = check_tokenless_exposure(config); !status.ok()) return status;
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
  Server* self = server.get();
  if (config.metrics) {
    auto metrics = HttpEndpoint::open(
        "metrics", config.metrics->address, config.metrics->port,
        [self](const HttpRequest& request) { return self->serve_metrics(request); }, {},
        config.http_tls);
    if (!metrics.ok()) return metrics.status();
    server->metrics_ = std::move(*metrics);
  }
  if (config.control) {
    server->control_api_ = std::make_unique<ControlApi>(
        static_cast<ControlTarget&>(*server), *config.control_keys, config.control_policy);
    auto control = HttpEndpoint::open(
        "control", config.control_bind.address, config.control_bind.port,
        [self](const HttpRequest& request) { return self->control_api_->handle(request); }, {},
        config.http_tls);
    if (!control.ok()) return control.status();
    server->control_ = std::move(*control);
  }
  if (config.live) {
    if (Status status = server->open_live(); !status.ok()) return status;
  }
  if (config.websocket) {
    if (Status status = server->open_websocket(); !status.ok()) return status;
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
  // The endpoints' handlers reach into this server: they stop first.
  close_endpoints();
  io_.stop();
}

void Server::close_endpoints() {
  if (metrics_) metrics_->close();
  if (control_) control_->close();
  if (live_) live_->close();
  if (websocket_) websocket_->close();
}

Status Server::open_live() {
  std::optional<StaticFiles> viewer;
  if (!config_.live_viewer_dir.empty()) {
    auto files = StaticFiles::load_viewer(config_.live_viewer_dir);
    if (!files.ok())
      return Status::Error(ErrorCode::kInvalidArgument, "live: " + files.status().message());
    viewer = std::move(*files);
  }
  const Server* self = this;
  live_api_ = std::make_unique<LiveApi>(
      [self](std::string_view id) -> std::shared_ptr<const LiveFeed> {
        std::lock_guard lock(self->matches_mutex_);
        for (const auto& match : self->matches_) {
          if (match->id() == id) return match->live_feed();
        }
        return nullptr;
      },
      [self] {
        std::vector<std::shared_ptr<const LiveFeed>> feeds;
        std::lock_guard lock(self->matches_mutex_);
        for (const auto& match : self->matches_) {
          if (auto feed = match->live_feed()) feeds.push_back(std::move(feed));
        }
        return feeds;
      },
      std::move(viewer));
  // Viewers poll several times a second, and a joining one loads a state:
  // more connections and a longer deadline than the other endpoints.
  HttpEndpointLimits limits;
  limits.max_connections = 64;
  limits.deadline = std::chrono::milliseconds(10000);
  const LiveApi* api = live_api_.get();
  auto endpoint = HttpEndpoint::open(
      "live", config_.live->address, config_.live->port,
      [api](const HttpRequest& request) { return api->handle(request); }, limits, config_.http_tls);
  if (!endpoint.ok()) return endpoint.status();
  live_ = std::move(*endpoint);
  return Status::Ok();
}

Status Server::open_websocket() {
  std::optional<HttpTls> tls = config_.http_tls;
  if (tls) tls->client_ca_file.clear();
  const Server* self = this;
  auto endpoint = WebSocketEndpoint::open(
      config_.websocket->address, config_.websocket->port,
      [self](std::string_view id) -> std::shared_ptr<WebSocketPort> {
        std::lock_guard lock(self->matches_mutex_);
        for (const auto& match : self->matches_) {
          if (match->id() == id && !match->ended()) return match->websocket_port();
        }
        return nullptr;
      },
      config_.websocket_limits, tls);
  if (!endpoint.ok()) return endpoint.status();
  websocket_ = std::move(*endpoint);
  return Status::Ok();
}

MatchConfig Server::config_for(const MatchConfig& base, const std::string& id) const {
  MatchConfig match = base;
  match.match_id = id;
  match.live = match.live || config_.live.has_value();
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

Result<std::shared_ptr<MatchRunner>> Server::add_match(const MatchConfig& config, uint16_t port,
                                                       const std::string& owner) {
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
  settings.owner = owner;
  settings.load = load_;
  settings.websocket = config_.websocket.has_value();
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

Result<std::shared_ptr<MatchRunner>> Server::allocate(const MatchRequest& request,
                                                      const std::string& owner) {
  // A match more would slow every match already here: refused while the
  // threads are busy past the budget or ticks already slip.
  if (std::string reason = load_->overload_reason(net::SteadyClock::now()); !reason.empty()) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    write_log(LogLevel::kWarning, "refused match '" + request.match.match_id + "': " + reason);
    return Status::Error(ErrorCode::kCapacity, reason);
  }
  MatchConfig config = config_for(request.match, request.match.match_id);
  // A finished match's replay is its record: a new match under the same id
  // would overwrite it, so the id stays taken while the file exists.
  std::error_code ignored;
  if (!config.replay_path.empty() && std::filesystem::exists(config.replay_path, ignored)) {
    return Status::Error(ErrorCode::kInvalidArgument, "match id '" + config.match_id +
                                                          "' has a replay (" + config.replay_path +
                                                          "): ids are not reused while it exists");
  }
  auto runner = add_match(config, request.port, owner);
  if (!runner.ok()) return runner.status();
  (*runner)->start();
  write_log(LogLevel::kInfo, "allocated match '" + (*runner)->id() + "' ('" + config.game + "', " +
                                 std::to_string(config.players) + " players) on port " +
                                 std::to_string((*runner)->port()) +
                                 (owner.empty() ? std::string() : " for " + owner));
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
  const bool loopback = is_loopback_address(config_.bind_address);
  const std::string mode =
      config_.server_key ? "secure connections (connect tokens)"
      : loopback         ? "TOKENLESS on loopback (any local process takes a free slot: local "
                           "tests only)"
                 : "TOKENLESS ON A PUBLIC ADDRESS (any host that reaches the port takes a free "
                   "slot)";
  if (!config_.server_key && !loopback) {
    write_log(LogLevel::kWarning,
              "INSECURE: tokenless on " + config_.bind_address +
                  " (--insecure-tokenless-on-public-address): nothing authenticates a client; "
                  "anyone who sees the traffic can act for a player. Use --key-file with "
                  "connect tokens outside a trusted network");
  }
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
  const std::string scheme = config_.http_tls ? "https://" : "http://";
  const std::string tls_note = !config_.http_tls                          ? ""
                               : config_.http_tls->client_ca_file.empty() ? ", TLS"
                                                                          : ", mutual TLS";
  if (metrics_) {
    write_log(LogLevel::kInfo, "metrics on " + scheme + bracketed(config_.metrics->address) + ":" +
                                   std::to_string(metrics_->port()) + "/metrics" +
                                   (config_.metrics_keys ? " (bearer keys required" + tls_note + ")"
                                    : tls_note.empty()   ? ""
                                                         : " (" + tls_note.substr(2) + ")"));
  }
  if (live_) {
    write_log(LogLevel::kInfo,
              "live spectating on " + scheme + bracketed(config_.live->address) + ":" +
                  std::to_string(live_->port()) + "/" +
                  (config_.live_viewer_dir.empty() ? " (no viewer files: data routes only)" : "") +
                  (config_.match.live_delay_ticks > 0
                       ? ", " + std::to_string(config_.match.live_delay_ticks) + " ticks behind"
                       : ""));
  }
  if (websocket_) {
    write_log(LogLevel::kInfo, std::string("browsers on ") +
                                   (config_.http_tls ? "wss://" : "ws://") +
                                   bracketed(config_.websocket->address) + ":" +
                                   std::to_string(websocket_->port()) + "/matches/<match id>");
  }
  if (control_) {
    write_log(LogLevel::kInfo,
              "control API on " + scheme + bracketed(config_.control_bind.address) + ":" +
                  std::to_string(control_->port()) + "/matches (" +
                  std::to_string(config_.control_keys->size()) + " bearer keys" + tls_note + ")");
    if (!config_.http_tls && !is_loopback_address(config_.control_bind.address)) {
      write_log(LogLevel::kWarning,
                "the control API is on " + config_.control_bind.address +
                    " over plain HTTP: its bearer keys cross the network in the clear; give it "
                    "--http-tls-cert/--http-tls-key (and --http-tls-client-ca) or keep it on a "
                    "private network");
    }
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
  // Spectators poll: while they still do, give them the last ticks and
  // the end before the endpoint goes, for at most live_linger_s (not after
  // a signal, which wants the process gone). A viewer stops polling once it
  // has seen the end; none polling for 2 s means none is left.
  if (live_ && !stopping_ && config_.live_linger_s > 0) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point until =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(config_.live_linger_s));
    while (Clock::now() < until &&
           Clock::now() - live_api_->last_request() < std::chrono::seconds(2)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  close_endpoints();
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
  signals_.cancel();
  // Nothing is left but the closed sockets' last handlers.
  io_.stop();
}

HttpReply Server::serve_metrics(const HttpRequest& request) {
  if (request.path() != "/metrics") {
    return HttpReply{404, "text/plain; charset=utf-8", "not found: try /metrics\n", {}};
  }
  if (config_.metrics_keys && !config_.metrics_keys->authenticate(request.authorization)) {
    HttpReply reply{401, "text/plain; charset=utf-8", "a bearer key is required\n", {}};
    reply.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"rewind-metrics\"");
    return reply;
  }
  if (request.method != "GET" && request.method != "HEAD") {
    return HttpReply{405, "text/plain; charset=utf-8", "GET /metrics\n", {}};
  }
  const ProcessSample process = process_sample();
  return HttpReply{200, "text/plain; version=0.0.4", render_metrics(samples(), &process), {}};
}

MatchListing Server::listing_of(const MatchRunner& match) {
  const MetricsSample sample = match.sample();
  MatchListing out;
  out.id = match.id();
  out.owner = match.owner();
  out.game = match.config().game;
  out.port = match.port();
  out.players = match.config().players;
  out.phase = sample.phase;
  out.players_connected = sample.players_connected;
  out.ticks_final = sample.stats.ticks_final;
  out.end_reason = sample.stats.end_reason;
  out.ended = match.ended();
  return out;
}

Result<MatchListing> Server::allocate_match(const MatchRequest& request, const std::string& owner) {
  auto runner = allocate(request, owner);
  if (!runner.ok()) return runner.status();
  return listing_of(**runner);
}

std::vector<MatchListing> Server::list_matches() const {
  std::vector<std::shared_ptr<MatchRunner>> matches;
  {
    std::lock_guard lock(matches_mutex_);
    matches = matches_;
  }
  std::vector<MatchListing> out;
  out.reserve(matches.size());
  for (const auto& match : matches) out.push_back(listing_of(*match));
  return out;
}

Status Server::stop_match(std::string_view id, const std::string& reason) {
  std::shared_ptr<MatchRunner> found;
  {
    std::lock_guard lock(matches_mutex_);
    for (const auto& match : matches_) {
      if (match->id() == id && !match->ended()) found = match;
    }
  }
  if (!found) return Status::Error(ErrorCode::kNotFound, "no running match with that id");
  found->stop(reason);
  return Status::Ok();
}

}  // namespace rwd::server
