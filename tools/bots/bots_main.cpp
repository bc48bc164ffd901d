// SPDX-License-Identifier: MIT
// rewind-bots' run loop (bots_main.h): N full SDK clients in one process, for
// load tests and the demo.
#include <algorithm>
#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <asio/steady_timer.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rewind/cli/flag_parser.h"
#include "rewind/cli/host_port.h"
#include "rewind/client/client_session.h"
#include "rewind/client/websocket_link.h"
#include "rewind/game/simulation.h"  // make_builtin_game
#include "rewind/net/connect_token.h"
#include "rewind/net/fault_injector.h"
#include "rewind/tools/bot_script.h"
#include "rewind/tools/bots_main.h"

namespace {

using rwd::client::ClientEvent;
using rwd::client::ClientEventType;
using rwd::client::ClientSession;

struct Bot {
  std::unique_ptr<ClientSession> session;
  // Over WebSocket (--websocket): the connection, and the simulated faults
  // on each direction (a UDP session has them inside).
  std::unique_ptr<rwd::client::WebSocketLink> link;
  std::optional<rwd::net::FaultyLink> faults_out;
  std::optional<rwd::net::FaultyLink> faults_in;
  bool ended = false;
  bool match_ended = false;
  bool failed = false;
  std::string failure;
};

// Names (e.g. "server" on a compose network) are resolved once, up front;
// the sessions take an address literal.
bool resolve(asio::io_context& io, const std::string& host, std::string* address,
             std::string* error) {
  asio::ip::udp::resolver resolver(io);
  std::error_code ec;
  const auto results = resolver.resolve(host, "", ec);
  if (ec || results.empty()) {
    *error = ec ? ec.message() : "no addresses";
    return false;
  }
  // Prefer IPv4, as loopback examples and most game hosts are.
  for (const auto& entry : results) {
    if (entry.endpoint().address().is_v4()) {
      *address = entry.endpoint().address().to_string();
      return true;
    }
  }
  *address = results.begin()->endpoint().address().to_string();
  return true;
}

// A session whose datagrams travel over WebSocket, through the same
// simulated faults a UDP session applies (each direction its own stream).
rwd::Result<std::unique_ptr<ClientSession>> over_websocket(asio::io_context& io,
                                                           const std::string& url,
                                                           rwd::client::ClientConfig config,
                                                           Bot& bot) {
  auto link = rwd::client::WebSocketLink::open(url);
  if (!link.ok()) return link.status();
  bot.link = std::move(*link);
  rwd::client::WebSocketLink* wire = bot.link.get();
  if (config.faults) {
    rwd::net::FaultConfig out = *config.faults, in = *config.faults;
    in.seed = out.seed ^ 0x9e3779b97f4a7c15ull;
    auto sending = rwd::net::FaultyLink::create(
        io, out, [wire](std::span<const uint8_t> bytes, const auto&) { wire->send(bytes); });
    if (!sending.ok()) return sending.status();
    auto receiving =
        rwd::net::FaultyLink::create(io, in, [&bot](std::span<const uint8_t> bytes, const auto&) {
          bot.session->receive(bytes, rwd::net::SteadyClock::now());
        });
    if (!receiving.ok()) return receiving.status();
    bot.faults_out.emplace(std::move(*sending));
    bot.faults_in.emplace(std::move(*receiving));
    config.faults.reset();
  }
  return ClientSession::create_detached(config, [&bot, wire](std::span<const uint8_t> datagram) {
    if (bot.faults_out) {
      bot.faults_out->send(datagram, {});
    } else {
      wire->send(datagram);
    }
  });
}

}  // namespace

namespace rwd::tools {

int bots_main(int argc, const char* const* argv) {
  int64_t bots = 4, seed = 1, corrupt_bot = -1, corrupt_at = -1, snapshot_ticks = 96,
          spectators = 0;
  std::string connect = "127.0.0.1:7777", game = "crates", script_name = "game";
  int64_t latency_ms = 0, jitter_ms = 0;
  double loss = 0, duplicate = 0, reorder = 0, duration_s = 600;
  bool summary_json = false;
  std::string token_file, websocket_url;
  std::vector<std::string> tokens;

  rwd::cli::FlagParser flags(
      "rewind-bots", "rewind-bots [flags]",
      "Runs N bot clients (each a full client SDK session: prediction, rollback, checksum\n"
      "checks, desync reports) against a rewind-server, with optional injected network faults.\n"
      "Exit status: 0 = every bot played the match to its end with no desync; 1 = a desync\n"
      "was detected; 2 = a bot could not join or lost the server.");
  flags.add_int("bots", &bots, 0, 1000, "number of bot clients (players)");
  flags.add_int("spectators", &spectators, 0, 64,
                "spectator clients besides the bots (read-only: they verify every final tick)");
  flags.add_string("connect", &connect, "server HOST:PORT (a name, an IPv4 literal or [IPv6])");
  flags.add_string("websocket", &websocket_url,
                   "connect over WebSocket instead, as browsers do: "
                   "ws://HOST:PORT/matches/<match id> (rewind-server --websocket)");
  flags.add_string("game", &game, "game the server hosts");
  flags.add_string("script", &script_name,
                   "input script: game (the game's own bots, Game::bot_input), random, circle "
                   "or idle");
  flags.add_int("seed", &seed, 0, INT64_MAX, "seed of the input scripts and fault streams");
  flags.add_int("latency-ms", &latency_ms, 0, 10000, "one-way delay added in each direction");
  flags.add_int("jitter-ms", &jitter_ms, 0, 10000, "uniform +- variation of the delay");
  flags.add_double("loss", &loss, 0, 1, "probability a datagram is dropped (each direction)");
  flags.add_double("duplicate", &duplicate, 0, 1, "probability a datagram is delivered twice");
  flags.add_double("reorder", &reorder, 0, 1, "probability a datagram is held back and overtaken");
  flags.add_double("duration", &duration_s, 0.1, 86400, "give up after this many seconds");
  flags.add_int("snapshot-ticks", &snapshot_ticks, 16, 1024, "rollback depth of each bot");
  flags.add_int("corrupt-bot", &corrupt_bot, -1, 999,
                "test: this bot corrupts its state (-1 = none)");
  flags.add_int("corrupt-at-tick", &corrupt_at, -1, INT32_MAX,
                "test: tick at which --corrupt-bot corrupts");
  flags.add_bool("summary-json", &summary_json, "print one JSON summary line on stdout at exit");
  flags.add_string("token-file", &token_file,
                   "connect tokens for a secure server, one hex line per bot (rewind-token mint)");
  flags.add_string_list("token", &tokens,
                        "a connect token (hex) for the next bot; repeat once per bot");

  if (rwd::Status status = flags.parse(argc, argv); !status.ok()) {
    std::fprintf(stderr, "rewind-bots: %s\n", status.message().c_str());
    return rwd::cli::kExitUsage;
  }
  if (flags.help_requested()) {
    std::fputs(flags.help_text().c_str(), stdout);
    return 0;
  }
  std::string host;
  uint16_t port = 0;
  if (!rwd::cli::split_host_port(connect, &host, &port) || port == 0) {
    std::fprintf(stderr, "rewind-bots: --connect: expected HOST:PORT, got '%s'\n", connect.c_str());
    return rwd::cli::kExitUsage;
  }
  rwd::tools::BotScript script;
  if (!rwd::tools::parse_bot_script(script_name, &script)) {
    std::fprintf(stderr, "rewind-bots: --script: expected game, random, circle or idle, got '%s'\n",
                 script_name.c_str());
    return rwd::cli::kExitUsage;
  }
  // The game's own bots play through its bot_input() hook; a game this
  // program does not know is refused here rather than by every session.
  std::shared_ptr<const rwd::game::Game> bot_game = rwd::game::make_builtin_game(game);
  if (bot_game == nullptr) {
    std::fprintf(stderr, "rewind-bots: --game: no game named '%s' in this program\n", game.c_str());
    return rwd::cli::kExitUsage;
  }
  if (rwd::Status fits = rwd::tools::check_bot_script(script, bot_game->input_spec()); !fits.ok()) {
    std::fprintf(stderr, "rewind-bots: --script %s: %s\n", script_name.c_str(),
                 fits.message().c_str());
    return rwd::cli::kExitUsage;
  }
  if ((corrupt_bot >= 0) != (corrupt_at >= 0)) {
    std::fprintf(stderr, "rewind-bots: --corrupt-bot and --corrupt-at-tick go together\n");
    return rwd::cli::kExitUsage;
  }

  if (!token_file.empty()) {
    std::ifstream in(token_file);
    if (!in) {
      std::fprintf(stderr, "rewind-bots: --token-file: cannot read %s\n", token_file.c_str());
      return rwd::cli::kExitUsage;
    }
    for (std::string line; std::getline(in, line);) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) tokens.push_back(line);
    }
  }
  std::vector<std::vector<uint8_t>> connect_tokens;
  for (size_t i = 0; i < tokens.size(); ++i) {
    auto bytes = rwd::net::from_hex(tokens[i]);
    if (bytes.ok() && !rwd::net::read_connect_token(*bytes).ok()) {
      bytes = rwd::net::read_connect_token(*bytes).status();
    }
    if (!bytes.ok()) {
      std::fprintf(stderr, "rewind-bots: connect token %zu: %s\n", i,
                   bytes.status().message().c_str());
      return rwd::cli::kExitUsage;
    }
    connect_tokens.push_back(std::move(*bytes));
  }
  if (bots + spectators == 0) {
    std::fprintf(stderr, "rewind-bots: --bots and --spectators are both 0: nobody to run\n");
    return rwd::cli::kExitUsage;
  }
  const int64_t clients = bots + spectators;
  if (!connect_tokens.empty() && connect_tokens.size() != static_cast<size_t>(clients)) {
    std::fprintf(stderr, "rewind-bots: %zu connect tokens for %lld clients (one each)\n",
                 connect_tokens.size(), static_cast<long long>(clients));
    return rwd::cli::kExitUsage;
  }

  asio::io_context io(1);
  std::string address, resolve_error;
  if (websocket_url.empty() && !resolve(io, host, &address, &resolve_error)) {
    std::fprintf(stderr, "rewind-bots: --connect: cannot resolve '%s': %s\n", host.c_str(),
                 resolve_error.c_str());
    return 2;
  }
  std::vector<Bot> fleet(static_cast<size_t>(clients));
  const auto start = rwd::net::SteadyClock::now();
  for (size_t i = 0; i < fleet.size(); ++i) {
    rwd::client::ClientConfig config;
    config.server_address = address;
    config.server_port = port;
    config.game = game;
    config.spectator = static_cast<int64_t>(i) >= bots;
    config.name = config.spectator ? "spectator-" + std::to_string(i - static_cast<size_t>(bots))
                                   : "bot-" + std::to_string(i);
    config.snapshot_ticks = static_cast<int32_t>(snapshot_ticks);
    if (!connect_tokens.empty()) config.connect_token = connect_tokens[i];
    if (latency_ms || jitter_ms || loss > 0 || duplicate > 0 || reorder > 0) {
      rwd::net::FaultConfig faults;
      faults.latency_ms = static_cast<uint32_t>(latency_ms);
      faults.jitter_ms = static_cast<uint32_t>(jitter_ms);
      faults.loss = loss;
      faults.duplicate = duplicate;
      faults.reorder = reorder;
      faults.seed = static_cast<uint64_t>(seed) * 1000003u + i;
      config.faults = faults;
    }
    if (static_cast<int64_t>(i) == corrupt_bot)
      config.debug_corrupt_at_tick = static_cast<int32_t>(corrupt_at);
    auto session = websocket_url.empty() ? ClientSession::create(io, config)
                                         : over_websocket(io, websocket_url, config, fleet[i]);
    if (!session.ok()) {
      std::fprintf(stderr, "rewind-bots: bot %zu: %s\n", i, session.status().message().c_str());
      return 2;
    }
    fleet[i].session = std::move(*session);
    const uint32_t bot_index = static_cast<uint32_t>(i);
    const uint64_t script_seed = static_cast<uint64_t>(seed);
    fleet[i].session->set_input_provider(
        [script, script_seed, bot_index, bot_game](rwd::Tick tick) {
          return rwd::tools::bot_input(script, *bot_game, script_seed, bot_index, tick);
        });
    fleet[i].session->connect(start);
  }

  uint64_t desync_events = 0, resync_events = 0, refused_events = 0;
  asio::steady_timer timer(io);
  std::function<void()> pump = [&]() {
    const auto now = rwd::net::SteadyClock::now();
    bool all_ended = true;
    for (size_t i = 0; i < fleet.size(); ++i) {
      Bot& bot = fleet[i];
      if (bot.ended) continue;
      if (bot.link) {
        bot.link->poll([&bot, now](std::span<const uint8_t> datagram) {
          if (bot.faults_in) {
            bot.faults_in->send(datagram, {});
          } else {
            bot.session->receive(datagram, now);
          }
        });
        if (bot.link->state() == rwd::client::WebSocketLink::State::kClosed &&
            !bot.session->simulation()) {
          bot.failed = true;
          bot.ended = true;
          bot.failure = bot.link->error();
          std::fprintf(stderr, "[rewind-bots] bot %zu: %s\n", i, bot.failure.c_str());
          continue;
        }
      }
      bot.session->update(now);
      ClientEvent event;
      while (bot.session->poll_event(event)) {
        switch (event.type) {
          case ClientEventType::kDesync:
            ++desync_events;
            std::fprintf(
                stderr,
                "[rewind-bots] bot %zu: DESYNC at tick %d (local %016llx, server %016llx)\n", i,
                event.tick, static_cast<unsigned long long>(event.local_checksum),
                static_cast<unsigned long long>(event.server_checksum));
            break;
          case ClientEventType::kResynced:
            ++resync_events;
            std::fprintf(stderr, "[rewind-bots] bot %zu: resynced at tick %d\n", i, event.tick);
            break;
          case ClientEventType::kResyncRefused:
            ++refused_events;
            std::fprintf(stderr,
                         "[rewind-bots] bot %zu: resync snapshot for tick %d did not load (%s); "
                         "asked for another\n",
                         i, event.tick, event.reason.c_str());
            break;
          case ClientEventType::kMatchEnded:
            bot.match_ended = true;
            bot.ended = true;
            break;
          case ClientEventType::kRejected:
          case ClientEventType::kDisconnected:
            bot.failed = true;
            bot.ended = true;
            bot.failure = event.reason;
            std::fprintf(stderr, "[rewind-bots] bot %zu: %s\n", i, event.reason.c_str());
            break;
          default:
            break;
        }
      }
      all_ended = all_ended && bot.ended;
    }
    if (all_ended || std::chrono::duration<double>(now - start).count() > duration_s) {
      io.stop();
      return;
    }
    timer.expires_after(std::chrono::milliseconds(2));
    timer.async_wait([&](const std::error_code& error) {
      if (!error) pump();
    });
  };
  pump();
  io.run();

  uint64_t rollbacks = 0, resimulated = 0, verified = 0, resynced = 0, joined_ok = 0, ended_ok = 0,
           failed = 0;
  int64_t min_final = INT64_MAX;
  double rtt_sum = 0;
  for (Bot& bot : fleet) {
    const rwd::client::ClientStats stats = bot.session->stats();
    rollbacks += stats.rollbacks;
    resimulated += stats.resimulated_ticks;
    verified += stats.final_ticks_verified;
    resynced += stats.final_ticks_resynced;
    rtt_sum += stats.rtt_ms;
    min_final = std::min<int64_t>(min_final, stats.last_final_tick + 1);
    joined_ok += bot.session->phase() != ClientSession::Phase::kJoining && !bot.failed;
    ended_ok += bot.match_ended;
    failed += bot.failed || !bot.ended;
  }
  const double elapsed =
      std::chrono::duration<double>(rwd::net::SteadyClock::now() - start).count();
  std::fprintf(
      stderr,
      "[rewind-bots] %lld bots, %lld spectators: %llu finished the match, %llu desyncs, %llu "
      "rollbacks\n",
      static_cast<long long>(bots), static_cast<long long>(spectators),
      static_cast<unsigned long long>(ended_ok), static_cast<unsigned long long>(desync_events),
      static_cast<unsigned long long>(rollbacks));
  if (summary_json) {
    std::printf(
        "{\"bots\":%lld,\"spectators\":%lld,\"joined\":%llu,\"finished\":%llu,\"failed\":%llu,"
        "\"desyncs\":%llu,"
        "\"resyncs\":%llu,\"resyncs_refused\":%llu,\"rollbacks\":%llu,\"resimulated_ticks\":%llu,"
        "\"ticks_final\":%lld,"
        "\"final_ticks_verified\":%llu,\"final_ticks_resynced\":%llu,\"rtt_ms_avg\":%.2f,"
        "\"duration_s\":%.2f}\n",
        static_cast<long long>(bots), static_cast<long long>(spectators),
        static_cast<unsigned long long>(joined_ok), static_cast<unsigned long long>(ended_ok),
        static_cast<unsigned long long>(failed), static_cast<unsigned long long>(desync_events),
        static_cast<unsigned long long>(resync_events),
        static_cast<unsigned long long>(refused_events), static_cast<unsigned long long>(rollbacks),
        static_cast<unsigned long long>(resimulated),
        static_cast<long long>(min_final == INT64_MAX ? 0 : min_final),
        static_cast<unsigned long long>(verified), static_cast<unsigned long long>(resynced),
        rtt_sum / static_cast<double>(fleet.size()), elapsed);
  }
  std::fflush(stdout);
  if (failed > 0) return 2;
  return desync_events > 0 ? 1 : 0;
}

}  // namespace rwd::tools
