// SPDX-License-Identifier: MIT
// One server process hosting several matches on real loopback sockets and
// a pool of threads: matches allocated through the control API side by
// side, a match whose game logic throws ending alone, and new matches
// refused while the process is overloaded.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "http_test_client.h"
#include "rewind/client/client_session.h"
#include "rewind/game/crates_game.h"
#include "rewind/game/game_registry.h"
#include "rewind/server/server.h"
#include "scratch_dir.h"

namespace rwd::server {
namespace {

constexpr Tick kFaultTick = 30;

// Set on the thread that runs the test's clients: their rules stay clean,
// while the server's threads meet the fault.
thread_local bool t_client_thread = false;

// Crates whose rules throw after stepping kFaultTick on the server,
// standing in for a game with a bug.
class FaultyCrates final : public game::Game {
 public:
  std::string_view name() const override { return "faulty-crates"; }
  uint32_t rules_version() const override { return crates_.rules_version(); }
  std::unique_ptr<game::Lane> make_lane() const override { return crates_.make_lane(); }
  bool accepts_lane(const game::Lane& lane) const override { return crates_.accepts_lane(lane); }
  void encode_world_config(std::vector<uint8_t>& out) const override {
    crates_.encode_world_config(out);
  }
  Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
      std::span<const uint8_t> bytes) const override {
    return crates_.describe_world_config(bytes);
  }
  size_t state_size() const override { return crates_.state_size(); }
  Status build(const game::MatchSetup& setup, game::Lane& lane,
               std::span<std::byte> state) const override {
    return crates_.build(setup, lane, state);
  }
  Status apply_inputs(Tick tick, std::span<const rwd::PlayerInput> inputs, game::Lane& lane,
                      std::span<std::byte> state) const override {
    return crates_.apply_inputs(tick, inputs, lane, state);
  }
  Status after_step(Tick tick, game::Lane& lane, std::span<std::byte> state) const override {
    if (!t_client_thread && tick == kFaultTick) {
      throw std::runtime_error("score table out of range");
    }
    return crates_.after_step(tick, lane, state);
  }
  void hash_state(std::span<const std::byte> state, rwd::StateHasher& hasher) const override {
    crates_.hash_state(state, hasher);
  }
  Status validate_state(const game::MatchSetup& setup,
                        std::span<const std::byte> state) const override {
    return crates_.validate_state(setup, state);
  }

 private:
  game::CratesGame crates_;
};

void register_faulty_game() {
  static const bool registered = [] {
    const Status status =
        game::register_game("faulty-crates", [] { return std::make_unique<FaultyCrates>(); });
    EXPECT_TRUE(status.ok()) << status.message();
    return true;
  }();
  (void)registered;
}

ServerConfig control_config() {
  ServerConfig config;
  config.bind_address = "127.0.0.1";
  config.port = 0;
  config.matches = 0;
  config.control = true;
  config.control_bind = ServerConfig::HttpBind{"127.0.0.1", 0};
  config.control_keys = *ApiKeys::parse(std::string("backend ") + std::string(44, 'k') + "\n");
  config.threads = 2;
  config.metrics = ServerConfig::MetricsBind{"127.0.0.1", 0};
  config.match.players = 1;
  config.match.max_spectators = 0;
  config.match.join_timeout_s = 20;
  return config;
}

struct Player {
  std::unique_ptr<client::ClientSession> session;
  bool ended = false;
  std::string end_reason;
  uint32_t finals = 0;
};

// Plays every player until each has ended or the deadline passes.
void play(asio::io_context& io, std::vector<Player>& players, std::chrono::seconds deadline) {
  t_client_thread = true;
  const auto start = net::SteadyClock::now();
  for (Player& p : players) p.session->connect(start);
  while (net::SteadyClock::now() - start < deadline) {
    io.poll();
    bool all_ended = true;
    for (Player& p : players) {
      p.session->update(net::SteadyClock::now());
      client::ClientEvent event;
      while (p.session->poll_event(event)) {
        if (event.type == client::ClientEventType::kFinalTick) ++p.finals;
        if (event.type == client::ClientEventType::kMatchEnded ||
            event.type == client::ClientEventType::kDisconnected) {
          p.ended = true;
          p.end_reason = event.reason;
        }
      }
      all_ended = all_ended && p.ended;
    }
    if (all_ended) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

Player make_player(asio::io_context& io, uint16_t port, const std::string& game) {
  client::ClientConfig config;
  config.server_port = port;
  config.game = game;
  config.server_timeout_s = 3;
  auto session = client::ClientSession::create(io, config);
  EXPECT_TRUE(session.ok()) << session.status().message();
  Player player;
  player.session = std::move(*session);
  return player;
}

TEST(ServerMatches, AFailingGameEndsItsMatchOnlyAndTheProcessHostsOn) {
  register_faulty_game();
  auto server = Server::create(control_config());
  ASSERT_TRUE(server.ok()) << server.status().message();
  std::thread runner([&] { (*server)->run(); });

  MatchRequest faulty;
  faulty.match = control_config().match;
  faulty.match.game = "faulty-crates";
  faulty.match.match_id = "buggy";
  MatchRequest healthy = faulty;
  healthy.match.game = "crates";
  healthy.match.match_id = "healthy";
  healthy.match.max_ticks = 180;
  auto bad = (*server)->allocate(faulty);
  auto good = (*server)->allocate(healthy);
  ASSERT_TRUE(bad.ok()) << bad.status().message();
  ASSERT_TRUE(good.ok()) << good.status().message();
  EXPECT_NE((*bad)->port(), (*good)->port());
  // The same id cannot be taken twice while its match runs.
  EXPECT_FALSE((*server)->allocate(healthy).ok());

  asio::io_context io;
  std::vector<Player> players;
  players.push_back(make_player(io, (*bad)->port(), "faulty-crates"));
  players.push_back(make_player(io, (*good)->port(), "crates"));
  play(io, players, std::chrono::seconds(20));

  EXPECT_TRUE((*bad)->ended());
  const MetricsSample failed = (*bad)->sample();
  EXPECT_EQ(failed.phase, MatchHost::Phase::kEnded);
  EXPECT_NE(failed.stats.end_reason.find("game logic failed"), std::string::npos)
      << failed.stats.end_reason;
  EXPECT_NE(failed.stats.end_reason.find("score table out of range"), std::string::npos);
  EXPECT_LE(failed.stats.ticks_final, kFaultTick + 1);

  // The other match played to its end, every final tick verified, or
  // passed over by a resync when this loaded machine let the client fall
  // behind.
  ASSERT_TRUE(players[1].ended);
  EXPECT_EQ(players[1].finals + players[1].session->stats().final_ticks_resynced, 180u);
  const MetricsSample played = (*good)->sample();
  EXPECT_EQ(played.stats.ticks_final, 180);
  EXPECT_EQ(played.stats.end_reason, "tick budget reached");

  // The process still takes new matches. On a machine so loaded that the
  // matches' ticks slipped, it may refuse one as overloaded instead: that
  // answer comes from a live process too, and is all a starved host can
  // honestly give.
  MatchRequest later = healthy;
  later.match.match_id = "after-the-fault";
  auto again = (*server)->allocate(later);
  if (!again.ok()) {
    EXPECT_EQ(again.status().code(), ErrorCode::kCapacity);
    EXPECT_EQ(again.status().message().rfind("overloaded: ", 0), 0u) << again.status().message();
    (*server)->shutdown("test over");
    runner.join();
    return;
  }
  EXPECT_FALSE((*again)->ended());
  EXPECT_EQ((*server)->samples().size(), 3u);

  (*server)->shutdown("test over");
  runner.join();
  EXPECT_TRUE((*again)->ended());
  EXPECT_EQ((*again)->sample().stats.end_reason, "test over");
}

TEST(ServerMatches, LaunchMatchesTakeConsecutiveIdsAndPaths) {
  ServerConfig config = control_config();
  config.control = false;
  config.metrics.reset();
  config.matches = 3;
  const test::ScratchDir scratch("server_matches");
  const std::filesystem::path& dir = scratch.path();
  config.match.replay_path = (dir / "game.rwr").string();
  config.match.join_timeout_s = 0.2;
  auto server = Server::create(config);
  ASSERT_TRUE(server.ok()) << server.status().message();
  EXPECT_EQ((*server)->ports().size(), 3u);
  (*server)->run();  // nobody joins: every lobby times out and the process ends
  const std::vector<MetricsSample> samples = (*server)->samples();
  ASSERT_EQ(samples.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(samples[i].match, "match-" + std::to_string(i + 1));
    EXPECT_EQ(samples[i].phase, MatchHost::Phase::kEnded);
    EXPECT_EQ(samples[i].stats.end_reason.rfind("lobby timeout", 0), 0u);
    // Every tick the loop ran had its start measured against its time.
    EXPECT_GT(samples[i].tick_time.count(), 0u);
    EXPECT_EQ(samples[i].tick_lateness.count(), samples[i].tick_time.count());
    EXPECT_TRUE(std::filesystem::exists(dir / ("game-match-" + std::to_string(i + 1) + ".rwr")));
  }
}

TEST(ServerMatches, BadProcessConfigsAreRefused) {
  ServerConfig config = control_config();
  config.control_keys.reset();
  auto keyless = Server::create(config);
  ASSERT_FALSE(keyless.ok());  // control without bearer keys
  EXPECT_NE(keyless.status().message().find("--control-keys"), std::string::npos);
  config = control_config();
  config.metrics = ServerConfig::MetricsBind{"0.0.0.0", 0};
  auto exposed = Server::create(config);
  ASSERT_FALSE(exposed.ok());  // metrics on every address without keys
  EXPECT_NE(exposed.status().message().find("--metrics-keys"), std::string::npos);
  config.metrics_keys = config.control_keys;
  EXPECT_TRUE(Server::create(config).ok());
  config = control_config();
  config.control_policy.lobbies_per_caller = 0;
  EXPECT_FALSE(Server::create(config).ok());
  config = control_config();
  config.control = false;
  EXPECT_FALSE(Server::create(config).ok());  // no matches and no control
  config = control_config();
  config.matches = 20;
  config.max_matches = 4;
  EXPECT_FALSE(Server::create(config).ok());
  config = control_config();
  config.match.match_id = "no spaces";
  EXPECT_FALSE(Server::create(config).ok());
  config.match.match_id = "..";
  EXPECT_FALSE(Server::create(config).ok());
  for (const double budget : {0.0, -0.5, 1.01}) {
    config = control_config();
    config.tick_budget = budget;
    auto refused = Server::create(config);
    ASSERT_FALSE(refused.ok()) << budget;
    EXPECT_NE(refused.status().message().find("tick budget"), std::string::npos);
  }
}

TEST(ServerMatches, AnIdIsNotReusedWhileItsReplayExists) {
  ServerConfig config = control_config();
  const test::ScratchDir scratch("server_replay_ids");
  const std::filesystem::path& dir = scratch.path();
  config.match.replay_path = (dir / "{match}.rwr").string();
  auto server = Server::create(config);
  ASSERT_TRUE(server.ok()) << server.status().message();
  MatchRequest request;
  request.match = config.match;
  request.match.match_id = "kept";
  {
    std::FILE* file = std::fopen((dir / "kept.rwr").c_str(), "w");
    std::fclose(file);
  }
  auto refused = (*server)->allocate(request);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("has a replay"), std::string::npos);
  EXPECT_EQ(std::filesystem::file_size(dir / "kept.rwr"), 0u);  // untouched
  std::filesystem::remove(dir / "kept.rwr");
  EXPECT_TRUE((*server)->allocate(request).ok());
}

// The real endpoints: control calls need a key, and a control port full of
// held sockets does not stop a scrape on the metrics port.
TEST(ServerMatches, ControlAndMetricsAreSeparateEndpoints) {
  auto server = Server::create(control_config());
  ASSERT_TRUE(server.ok()) << server.status().message();
  ASSERT_NE((*server)->control_port(), 0);
  ASSERT_NE((*server)->metrics_port(), (*server)->control_port());
  std::thread runner([&] { (*server)->run(); });
  testing_http::Client control((*server)->control_port());
  testing_http::Client metrics((*server)->metrics_port());
  const std::string key = "Authorization: Bearer " + std::string(44, 'k') + "\r\n";
  EXPECT_EQ(testing_http::status_of(control.exchange("POST /matches?id=a HTTP/1.1\r\n\r\n")), 401);
  const std::string made =
      control.exchange("POST /matches?id=a&join_timeout=5 HTTP/1.1\r\n" + key + "\r\n");
  EXPECT_EQ(testing_http::status_of(made), 201) << made;
  EXPECT_EQ(testing_http::status_of(control.exchange("GET /metrics HTTP/1.1\r\n\r\n")), 404);
  std::vector<std::unique_ptr<asio::ip::tcp::socket>> held;
  for (int i = 0; i < 32; ++i) held.push_back(control.connect());
  for (int i = 0; i < 5; ++i) {
    const std::string scrape = metrics.exchange("GET /metrics HTTP/1.1\r\n\r\n");
    EXPECT_EQ(testing_http::status_of(scrape), 200);
    EXPECT_NE(scrape.find("match=\"a\""), std::string::npos);
  }
  (*server)->shutdown("test over");
  runner.join();
}

TEST(ServerMatches, AnOverloadedServerRefusesNewMatches) {
  using namespace std::chrono_literals;
  // A load record whose last seconds kept both match threads busy: made
  // up relative to now, so no real tick (nor the machine's speed) matters.
  const net::TimePoint now = net::SteadyClock::now();
  ServerConfig config = control_config();
  config.load = std::make_shared<LoadMonitor>(0.5, now - 60s);
  for (int s = 1; s <= 10; ++s) config.load->record_tick(now - s * 1s, 2s, false, 0);
  auto server = Server::create(config);
  ASSERT_TRUE(server.ok()) << server.status().message();
  MatchRequest request;
  request.match = config.match;
  request.match.match_id = "one-more";
  auto refused = (*server)->allocate(request);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kCapacity);
  EXPECT_EQ(refused.status().message().rfind("overloaded: ", 0), 0u) << refused.status().message();
  EXPECT_NE(refused.status().message().find("budget 50%"), std::string::npos)
      << refused.status().message();
  EXPECT_TRUE((*server)->samples().empty());
  const ProcessSample process = (*server)->process_sample();
  EXPECT_TRUE(process.overloaded);
  EXPECT_EQ(process.matches_refused, 1u);
  EXPECT_DOUBLE_EQ(process.tick_budget, 0.5);
  EXPECT_GT(process.tick_load, 0.5);
  // Busy but punctual: the process is still healthy.
  EXPECT_TRUE((*server)->healthy());
}

}  // namespace
}  // namespace rwd::server
