// SPDX-License-Identifier: MIT
// rewind-server's run loop (server_main.h): flags -> config -> run -> summary.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rewind/cli/flag_parser.h"
#include "rewind/cli/host_port.h"
#include "rewind/server/agones_lifecycle.h"
#include "rewind/server/api_keys.h"
#include "rewind/server/server.h"
#include "rewind/server/server_log.h"
#include "rewind/server/server_main.h"
#include "rewind/server/static_files.h"

namespace {

using rwd::server::LogLevel;
using rwd::server::write_log;

// One port a line, written to a temporary name and renamed, so a reader
// never sees half a number.
bool write_port_file(const std::string& path, const std::vector<uint16_t>& ports) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  bool written = file != nullptr;
  if (written) {
    for (const uint16_t port : ports) {
      written = std::fprintf(file, "%u\n", static_cast<unsigned>(port)) >= 0 && written;
    }
    written = std::fclose(file) == 0 && written;  // closed whatever happened
  }
  return written && std::rename(temporary.c_str(), path.c_str()) == 0;
}

// Where a hosted match reports: the port files and the summary line.
struct MatchOutputs {
  std::string port_file;
  std::string metrics_port_file;
  std::string control_port_file;
  std::string live_port_file;
  std::string websocket_port_file;
  bool summary_json = false;
};

// Binds, runs the match to its end and reports; the process exit status.
int host_match(const rwd::server::ServerConfig& config, const MatchOutputs& outputs) {
  auto server = rwd::server::Server::create(config);
  if (!server.ok()) {
    write_log(LogLevel::kError, server.status().message());
    return 1;
  }
  if (!outputs.port_file.empty() && !write_port_file(outputs.port_file, (*server)->ports())) {
    write_log(LogLevel::kError, "cannot write --port-file " + outputs.port_file);
    return 1;
  }
  if (!outputs.metrics_port_file.empty() &&
      !write_port_file(outputs.metrics_port_file, {(*server)->metrics_port()})) {
    write_log(LogLevel::kError, "cannot write --metrics-port-file " + outputs.metrics_port_file);
    return 1;
  }
  if (!outputs.control_port_file.empty() &&
      !write_port_file(outputs.control_port_file, {(*server)->control_port()})) {
    write_log(LogLevel::kError, "cannot write --control-port-file " + outputs.control_port_file);
    return 1;
  }
  if (!outputs.live_port_file.empty() &&
      !write_port_file(outputs.live_port_file, {(*server)->live_port()})) {
    write_log(LogLevel::kError, "cannot write --live-port-file " + outputs.live_port_file);
    return 1;
  }
  if (!outputs.websocket_port_file.empty() &&
      !write_port_file(outputs.websocket_port_file, {(*server)->websocket_port()})) {
    write_log(LogLevel::kError,
              "cannot write --websocket-port-file " + outputs.websocket_port_file);
    return 1;
  }
  (*server)->run();
  // One summary per match: the one line of a single match, or a line per
  // match (JSON with its "match" id) when the process hosted several.
  const std::vector<rwd::server::MetricsSample> samples = (*server)->samples();
  const bool many = samples.size() > 1 || config.control;
  bool lobby_timeout = false;
  for (const rwd::server::MetricsSample& sample : samples) {
    const rwd::server::MatchStats& stats = sample.stats;
    rwd::server::LogMatchScope scope(many ? std::string_view(sample.match) : std::string_view());
    write_log(LogLevel::kInfo, stats.to_text());
    if (const std::string problems = stats.problems(); !problems.empty()) {
      write_log(LogLevel::kWarning, problems);
    }
    if (outputs.summary_json) {
      std::string json = stats.to_json();
      if (many && json.size() > 1) json.insert(1, "\"match\":\"" + sample.match + "\",");
      std::printf("%s\n", json.c_str());
    }
    lobby_timeout = lobby_timeout || stats.end_reason.rfind("lobby timeout", 0) == 0;
  }
  std::fflush(stdout);
  // A lobby that never filled is a failed match for scripts.
  return lobby_timeout ? 2 : 0;
}

}  // namespace

namespace rwd::server {

int server_main(int argc, const char* const* argv) {
  using rwd::cli::FlagParser;
  rwd::server::ServerConfig config;
  std::string game = config.match.game;
  std::string bind = config.bind_address;
  int64_t port = config.port, players = config.match.players, tick_rate = config.match.tick_rate_hz,
          window = config.match.window_ticks, ticks = config.match.max_ticks,
          seed = static_cast<int64_t>(config.match.seed), keyframe = config.match.keyframe_interval;
  double join_timeout = config.match.join_timeout_s, peer_timeout = config.match.peer_timeout_s;
  std::string replay, desync_dir, key_file, match_id = config.match.match_id;
  bool summary_json = false, log_json = false;
  std::string port_file, metrics_bind, metrics_port_file;

  int64_t matches = config.matches, max_matches = config.max_matches, threads = config.threads;
  bool control = false;
  FlagParser flags("rewind-server", "rewind-server [flags]",
                   "Hosts authoritative rollback matches over UDP: ticks the deterministic "
                   "simulation, finalizes ticks,\nbroadcasts their inputs and checksums, records "
                   "a replay. One match by default; several\n(--matches, or allocated through "
                   "the control API) each tick on their own port and strand. Logs go to stderr.");
  flags.add_string("game", &game, "built-in game to host");
  flags.add_string("bind", &bind, "address to bind (IPv4 or IPv6 literal)");
  flags.add_int("port", &port, 0, 65535,
                "UDP port (0 = any free port); with --matches N, match i binds port + i - 1");
  flags.add_int("matches", &matches, 0, 256,
                "matches started at launch, named <match-id>-1.. when more than one (0 needs "
                "--control)");
  flags.add_int("max-matches", &max_matches, 1, 256,
                "most matches alive at once, launch and control together");
  flags.add_int("threads", &threads, 0, 64,
                "threads running the matches (0 = one per core, at most one per match)");
  double tick_budget = config.tick_budget;
  flags.add_double("tick-budget", &tick_budget, 0.01, 1,
                   "share of the match threads' time spent ticking (last 5 s) beyond which the "
                   "control API refuses new matches as overloaded; slipping ticks refuse them too");
  flags.add_bool("control", &control,
                 "serve the control API on --control-bind (GET/POST /matches, GET/DELETE "
                 "/matches/<id>), every call with a bearer key of --control-keys; the process "
                 "then runs until signalled");
  std::string control_bind =
      config.control_bind.address + ":" + std::to_string(config.control_bind.port);
  std::string control_keys, control_port_file, metrics_keys;
  flags.add_string("control-bind", &control_bind,
                   "with --control: HOST:PORT of the control API (port 0 = any free port)");
  flags.add_string("control-keys", &control_keys,
                   "with --control (required): bearer keys of the control API's callers, one "
                   "'NAME KEY [admin]' a line (rewind-token api-key)");
  flags.add_string("control-port-file", &control_port_file,
                   "write the bound control TCP port to this file once listening");
  int64_t lobbies_per_caller = config.control_policy.lobbies_per_caller;
  flags.add_int("control-lobbies-per-caller", &lobbies_per_caller, 1, 256,
                "with --control: matches one caller may have waiting for players at once");
  double max_lobby_seconds = config.control_policy.max_lobby_seconds;
  flags.add_double("control-max-lobby", &max_lobby_seconds, 1, 86400,
                   "with --control: the longest join_timeout a control call may ask for, seconds");
  flags.add_int("players", &players, 1, 32, "player slots; the match starts when all are joined");
  int64_t start_players = config.match.start_players;
  flags.add_int("start-players", &start_players, 0, 32,
                "start once N players joined (0 = every slot); the open slots are taken by late "
                "joiners mid-match, who catch up from a snapshot");
  int64_t spectators = config.match.max_spectators;
  flags.add_int("spectators", &spectators, 0, 63,
                "read-only seats (players + spectators <= 64); a secure server's token slots "
                "from --players on are spectator seats");
  flags.add_int("tick-rate", &tick_rate, 1, 1000, "ticks per second");
  flags.add_int("window", &window, 1, 120, "ticks before a missing input is substituted");
  flags.add_int("ticks", &ticks, 0, int64_t{1} << 31,
                "exit after N final ticks (0 = run until signalled)");
  flags.add_int("seed", &seed, 0, INT64_MAX, "game RNG seed");
  flags.add_string("replay", &replay,
                   "write the replay file here (empty = none); with several matches '{match}' "
                   "in it becomes the match id (else the id goes before the extension)");
  flags.add_int("keyframe-interval", &keyframe, 0, 1 << 20,
                "ticks between replay keyframes (0 = none)");
  flags.add_string("desync-dir", &desync_dir,
                   "store desync reports in this directory (empty = count only)");
  flags.add_string("key-file", &key_file,
                   "server key shared with the token backend (rewind-token keygen): secure "
                   "connections only; without it the server is TOKENLESS, which it refuses on "
                   "a non-loopback --bind (local tests only)");
  bool insecure_tokenless_public = false;
  flags.add_bool("insecure-tokenless-on-public-address", &insecure_tokenless_public,
                 "allow TOKENLESS mode (no --key-file) on a non-loopback --bind, on a network "
                 "you trust: anyone who reaches the port takes a free seat");
  flags.add_string("match-id", &match_id, "match id bound into connect tokens");
  flags.add_double("join-timeout", &join_timeout, 0.1, 86400, "seconds to wait for all players");
  flags.add_double("peer-timeout", &peer_timeout, 0.1, 3600,
                   "seconds of silence before a player is dropped");
  flags.add_string("port-file", &port_file,
                   "write the launch matches' bound UDP ports to this file, one a line, once "
                   "listening");
  flags.add_bool("summary-json", &summary_json, "print one JSON summary line on stdout at exit");
  flags.add_string("metrics-bind", &metrics_bind,
                   "serve Prometheus metrics over HTTP on HOST:PORT at /metrics (port 0 = any "
                   "free port; empty = off)");
  flags.add_string("metrics-port-file", &metrics_port_file,
                   "write the bound metrics TCP port to this file once listening");
  rwd::server::HttpTls tls;
  flags.add_string("http-tls-cert", &tls.certificate_file,
                   "serve the metrics and control endpoints over HTTPS with this PEM certificate "
                   "chain (with --http-tls-key)");
  flags.add_string("http-tls-key", &tls.private_key_file, "the PEM private key of --http-tls-cert");
  flags.add_string("http-tls-client-ca", &tls.client_ca_file,
                   "mutual TLS: clients of both endpoints must present a certificate this PEM CA "
                   "signed");
  flags.add_string("metrics-keys", &metrics_keys,
                   "scrapes must carry a bearer key of this file ('NAME KEY' a line); required "
                   "to serve metrics on an address other than loopback");
  std::string live_bind, live_port_file;
  std::string live_viewer_dir = rwd::server::default_viewer_dir();
  int64_t live_delay = config.match.live_delay_ticks,
          live_keyframe = config.match.live_keyframe_ticks;
  flags.add_string("live-bind", &live_bind,
                   "let browsers spectate every match on HOST:PORT over HTTP (port 0 = any free "
                   "port; empty = off): open http://HOST:PORT/ for the list of matches, each "
                   "shown in the viewer");
  std::string websocket_bind, websocket_port_file;
  flags.add_string("websocket", &websocket_bind,
                   "HOST:PORT where browsers join any match of this process over WebSocket "
                   "(ws://HOST:PORT/matches/<match id>; wss:// with --http-tls-cert), beside UDP; "
                   "port 0 = any free port");
  flags.add_string("websocket-port-file", &websocket_port_file,
                   "write the bound WebSocket TCP port to this file once listening");
  flags.add_string("live-port-file", &live_port_file,
                   "write the bound live TCP port to this file once listening");
  flags.add_string("live-viewer-dir", &live_viewer_dir,
                   "the built viewer the live endpoint serves (default: this build's viewer_web "
                   "when built; empty = data routes only)");
  flags.add_int("live-delay-ticks", &live_delay, 0, 36000,
                "spectators see each tick this many ticks after it became final");
  flags.add_int("live-keyframe-ticks", &live_keyframe, 1, 3600,
                "ticks between the states a joining spectator starts from");
  flags.add_double("live-linger", &config.live_linger_s, 0, 60,
                   "seconds the live endpoint may stay up after the last match ended, for "
                   "spectators to see the end (it closes once none has polled for 2 s)");
  bool agones = false;
  rwd::server::AgonesLifecycleOptions agones_options;
  flags.add_bool("agones", &agones,
                 "run as an Agones GameServer: Ready, wait for an allocation, take its "
                 "rewind.dev/* match settings, host, Shutdown (sidecar REST port from "
                 "AGONES_SDK_HTTP_PORT, default 9358)");
  flags.add_double("agones-allocation-timeout", &agones_options.allocation_timeout_s, 1, 604800,
                   "with --agones: seconds from Ready to an allocation before giving up "
                   "(Shutdown, exit 1)");
  flags.add_double("agones-health-period", &agones_options.health_period_s, 0.1, 60,
                   "with --agones: seconds between health pings (keep it below the Fleet's "
                   "health.periodSeconds)");
  flags.add_double("agones-sidecar-timeout", &agones_options.sidecar_timeout_s, 0.1, 3600,
                   "with --agones: seconds to wait for the SDK sidecar's first answer");
  flags.add_bool("log-json", &log_json,
                 "log lines on stderr as JSON objects {\"ts\",\"level\",\"msg\"}, one a line");

  // A usage error answers the person at the terminal, before --log-json is
  // known, so it stays plain text whatever the flags say.
  if (rwd::Status status = flags.parse(argc, argv); !status.ok()) {
    std::fprintf(stderr, "rewind-server: %s\n", status.message().c_str());
    return rwd::cli::kExitUsage;
  }
  if (flags.help_requested()) {
    std::fputs(flags.help_text().c_str(), stdout);
    return 0;
  }
  if (log_json) rwd::server::set_log_format(rwd::server::LogFormat::kJson);
  config.matches = static_cast<uint32_t>(matches);
  config.max_matches = static_cast<uint32_t>(max_matches);
  config.threads = static_cast<uint32_t>(threads);
  config.tick_budget = tick_budget;
  config.control = control;
  config.match.game = game;
  config.bind_address = bind;
  config.port = static_cast<uint16_t>(port);
  config.match.players = static_cast<uint32_t>(players);
  config.match.max_spectators = static_cast<uint32_t>(spectators);
  config.match.start_players = static_cast<uint32_t>(start_players);
  config.match.tick_rate_hz = static_cast<uint32_t>(tick_rate);
  config.match.window_ticks = static_cast<int32_t>(window);
  config.match.max_ticks = ticks;
  config.match.seed = static_cast<uint64_t>(seed);
  config.match.replay_path = replay;
  config.match.keyframe_interval = static_cast<int32_t>(keyframe);
  config.match.desync_dir = desync_dir;
  if (!key_file.empty()) {
    std::FILE* file = std::fopen(key_file.c_str(), "r");
    char text[130] = {};
    const size_t read = file != nullptr ? std::fread(text, 1, sizeof text - 1, file) : 0;
    if (file != nullptr) std::fclose(file);
    auto key = rwd::net::key_from_hex(std::string_view(text, read));
    if (file == nullptr || !key.ok()) {
      write_log(LogLevel::kError,
                "--key-file " + key_file + ": " +
                    (file == nullptr ? "cannot read it" : key.status().message()) +
                    " (a server key is 64 hex digits: rewind-token keygen --out FILE makes one)");
      return rwd::cli::kExitUsage;
    }
    config.server_key = *key;
  }
  // An HTTP endpoint's HOST:PORT flag, and its port file that needs it.
  const auto http_bind = [](const char* flag, const std::string& text,
                            const std::string& its_port_file, const char* port_file_flag,
                            std::optional<rwd::server::ServerConfig::HttpBind>* out) {
    if (text.empty()) {
      if (its_port_file.empty()) return true;
      write_log(LogLevel::kError, std::string("--") + port_file_flag + " needs --" + flag);
      return false;
    }
    rwd::server::ServerConfig::HttpBind endpoint;
    if (!rwd::cli::split_host_port(text, &endpoint.address, &endpoint.port)) {
      write_log(LogLevel::kError,
                std::string("--") + flag + ": expected HOST:PORT, got '" + text + "'");
      return false;
    }
    *out = endpoint;
    return true;
  };
  if (!http_bind("metrics-bind", metrics_bind, metrics_port_file, "metrics-port-file",
                 &config.metrics) ||
      !http_bind("live-bind", live_bind, live_port_file, "live-port-file", &config.live) ||
      !http_bind("websocket", websocket_bind, websocket_port_file, "websocket-port-file",
                 &config.websocket)) {
    return rwd::cli::kExitUsage;
  }
  if (config.live) config.live_viewer_dir = live_viewer_dir;
  config.match.live_delay_ticks = static_cast<uint32_t>(live_delay);
  config.match.live_keyframe_ticks = static_cast<uint32_t>(live_keyframe);
  if (!tls.certificate_file.empty() || !tls.private_key_file.empty() ||
      !tls.client_ca_file.empty()) {
    if (tls.certificate_file.empty() || tls.private_key_file.empty()) {
      write_log(LogLevel::kError, "--http-tls-cert and --http-tls-key go together");
      return rwd::cli::kExitUsage;
    }
    config.http_tls = tls;
  }
  if (!metrics_keys.empty()) {
    auto keys = rwd::server::ApiKeys::load(metrics_keys);
    if (!keys.ok()) {
      write_log(LogLevel::kError, "--metrics-keys " + keys.status().message());
      return rwd::cli::kExitUsage;
    }
    config.metrics_keys = std::move(*keys);
  }
  if (control) {
    if (!rwd::cli::split_host_port(control_bind, &config.control_bind.address,
                                   &config.control_bind.port)) {
      write_log(LogLevel::kError, "--control-bind: expected HOST:PORT, got '" + control_bind + "'");
      return rwd::cli::kExitUsage;
    }
    if (!control_keys.empty()) {
      auto keys = rwd::server::ApiKeys::load(control_keys);
      if (!keys.ok()) {
        write_log(LogLevel::kError, "--control-keys " + keys.status().message());
        return rwd::cli::kExitUsage;
      }
      config.control_keys = std::move(*keys);
    }
    config.control_policy.lobbies_per_caller = static_cast<uint32_t>(lobbies_per_caller);
    config.control_policy.max_lobby_seconds = max_lobby_seconds;
  } else if (!control_keys.empty() || !control_port_file.empty()) {
    write_log(LogLevel::kError, "--control-keys and --control-port-file need --control");
    return rwd::cli::kExitUsage;
  }
  config.match.match_id = match_id;
  config.match.join_timeout_s = join_timeout;
  config.match.peer_timeout_s = peer_timeout;

  config.insecure_tokenless_public = insecure_tokenless_public;

  const MatchOutputs outputs{port_file,      metrics_port_file,   control_port_file,
                             live_port_file, websocket_port_file, summary_json};
  if (!agones) return host_match(config, outputs);
  if (config.matches != 1 || config.control) {
    // An Agones GameServer is one allocation, so one match.
    write_log(LogLevel::kError, "--agones hosts one match: no --matches or --control with it");
    return rwd::cli::kExitUsage;
  }
  auto sdk_port = rwd::server::agones_port_from_env(std::getenv("AGONES_SDK_HTTP_PORT"));
  if (!sdk_port.ok()) {
    write_log(LogLevel::kError, "--agones: " + sdk_port.status().message());
    return rwd::cli::kExitUsage;
  }
  // Checked before the GameServer is Ready: Server::create would refuse it
  // only once allocated.
  if (rwd::Status status = rwd::server::check_tokenless_exposure(config); !status.ok()) {
    write_log(LogLevel::kError, status.message());
    return 1;
  }
  rwd::server::AgonesSdk::Options sdk_options;
  sdk_options.port = *sdk_port;
  const rwd::server::AgonesSdk sdk(sdk_options);
  return rwd::server::run_agones_match(config, sdk, agones_options,
                                       [&outputs](const rwd::server::ServerConfig& allocated) {
                                         return host_match(allocated, outputs);
                                       });
}

}  // namespace rwd::server
