// SPDX-License-Identifier: MIT
// MatchHost driven without sockets: scripted clients build envelopes by
// hand, and the clock is whatever the test says.
#include "car_input_game.h"
#include "failing_game.h"
#include "match_host_harness.h"
#include "rewind/game/crates_game.h"
#include "rewind/game/game_registry.h"
#include "rewind/proto/message_inputs.h"
#include "scratch_dir.h"

namespace rwd::server {
namespace {

using namespace host_test;  // NOLINT: test helpers

TEST(MatchHost, FinalizesWithLateInputsAndRollsBack) {
  HostHarness h(test_config());
  auto finals = play(h, 60, nullptr);
  EXPECT_GE(finals.size(), 50u);
  const MatchStats stats = h.host().stats();
  EXPECT_GT(stats.rollbacks, 0u);
  EXPECT_GT(stats.late_inputs, 0u);
  EXPECT_EQ(stats.substituted_inputs, 0u);
  EXPECT_EQ(stats.rejected_packets, 0u);
}

// Each client gets one datagram a tick: the final ticks, its own input
// acknowledgement and the other players' new inputs (never its own),
// however many inputs arrived in between.
TEST(MatchHost, OneDatagramPerClientPerTickCarriesTheOthersInputs) {
  MatchConfig config = test_config();
  config.players = 4;
  HostHarness h(config);
  std::vector<FakeClient> clients;
  for (uint16_t port = 4101; port < 4105; ++port) clients.push_back(h.join(port));
  ASSERT_EQ(h.host().phase(), MatchHost::Phase::kRunning);
  for (Tick t = 0; t < 30; ++t) {
    for (FakeClient& c : clients) h.outbox().received[c.endpoint].clear();
    for (FakeClient& c : clients) {
      // Two packets each: the tick's input, then the same again (a resend).
      h.send_input(c, t, scripted(c.player, t), c.player);
      h.send_input(c, t, scripted(c.player, t), c.player);
    }
    for (FakeClient& c : clients) {
      EXPECT_TRUE(h.outbox().received[c.endpoint].empty()) << "nothing before the tick";
    }
    h.tick();
    for (FakeClient& c : clients) {
      const std::vector<v1::Envelope>& got = h.outbox().received[c.endpoint];
      ASSERT_EQ(got.size(), 1u) << "tick " << t << " player " << c.player;
      ASSERT_TRUE(got[0].has_final_ticks());
      uint64_t from = 0;
      std::vector<proto::RelayedRun> runs;
      ASSERT_TRUE(proto::relayed_runs(got[0].final_ticks(), runs).ok());
      for (const proto::RelayedRun& run : runs) {
        EXPECT_NE(run.player, c.player);
        EXPECT_EQ(run.first_tick, t);
        ASSERT_EQ(run.inputs.size(), 1u);
        EXPECT_EQ(run.inputs[0], scripted(run.player, t));
        from |= uint64_t{1} << run.player;
      }
      EXPECT_EQ(from, 0xFull & ~(uint64_t{1} << c.player)) << "tick " << t;
    }
  }
  EXPECT_EQ(h.host().stats().relayed_inputs, 4u * 30u);
}

// A spectator takes a read-only seat past the player slots: it is not a
// player (the match starts without it), it gets the tick's datagram, and
// inputs it sends are never taken.
TEST(MatchHost, ASpectatorWatchesButNeverPlays) {
  HostHarness h(test_config());
  FakeClient watcher;
  watcher.endpoint = Endpoint(make_address("127.0.0.1"), 4300);
  v1::Envelope join;
  join.mutable_join_request()->set_game("crates");
  join.mutable_join_request()->set_spectator(true);
  join.mutable_join_request()->set_nonce(7);
  h.admitted(watcher.endpoint, h.encode(join));
  const std::vector<v1::Envelope>& answers = h.outbox().received[watcher.endpoint];
  ASSERT_EQ(answers.size(), 1u);
  ASSERT_TRUE(answers[0].has_join_accept());
  EXPECT_TRUE(answers[0].join_accept().spectator());
  EXPECT_EQ(answers[0].join_accept().player(), 2u);  // after the two player slots
  watcher.connection_id = answers[0].join_accept().connection_id();
  watcher.player = 2;
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kLobby);
  FakeClient a = h.join(4301);
  FakeClient b = h.join(4302);
  ASSERT_EQ(h.host().phase(), MatchHost::Phase::kRunning);
  EXPECT_EQ(h.host().stats().players_joined, 2u);
  for (Tick t = 0; t < 20; ++t) {
    h.send_input(a, t, scripted(a.player, t), a.player);
    h.send_input(b, t, scripted(b.player, t), b.player);
    h.send_input(watcher, t, rwd::stick_input(1000, 1000, 1), watcher.player);  // never taken
    h.tick();
  }
  EXPECT_GT(h.host().stats().rejected_inputs, 0u);
  EXPECT_EQ(h.host().stats().substituted_inputs, 0u);
  size_t finals = 0;
  for (const v1::Envelope& e : h.outbox().received[watcher.endpoint]) finals += e.has_final_ticks();
  EXPECT_GE(finals, 15u);
}

TEST(MatchHost, MissingInputsAreSubstitutedAtTheDeadline) {
  HostHarness h(test_config());
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  for (Tick t = 0; t < 20; ++t) {
    h.send_input(a, t, scripted(a.player, t), a.player);  // b never sends
    h.tick();
  }
  const MatchStats stats = h.host().stats();
  EXPECT_GE(stats.ticks_final, 14);
  EXPECT_EQ(stats.substituted_inputs, static_cast<uint64_t>(stats.ticks_final));
  for (const v1::FinalTick& f : h.host().recent_finals()) EXPECT_EQ(f.substituted_mask(), 2u);
  // b's input for a final tick arrives now: rejected and counted.
  h.send_input(b, 0, rwd::stick_input(1000, 0), b.player);
  EXPECT_EQ(h.host().stats().rejected_inputs, 1u);
}

TEST(MatchHost, HostileDatagramsChangeNothingForThePlayers) {
  HostHarness clean(test_config());
  const auto expected = play(clean, 90, nullptr);

  HostHarness h(test_config());
  std::mt19937 rng(1234);
  const Endpoint attacker(make_address("127.0.0.1"), 6666);
  auto attack = [&](HostHarness& host, FakeClient& a, FakeClient& b, Tick t) {
    // Random bytes of every size, including oversize.
    std::vector<uint8_t> junk(rng() % 1500 + 1);
    for (uint8_t& byte : junk) byte = static_cast<uint8_t>(rng());
    host.raw(attacker, junk);
    // A valid input frame, truncated.
    v1::Envelope frame;
    frame.set_connection_id(a.connection_id);
    frame.set_sequence(999999);
    frame.mutable_input_frame()->set_player(a.player);
    frame.mutable_input_frame()->set_first_tick(t);
    frame.mutable_input_frame()->add_inputs()->set_data("\x05");
    std::vector<uint8_t> bytes = host.encode(frame);
    bytes.resize(bytes.size() - 3);
    host.raw(a.endpoint, bytes);
    // Wrong protocol version.
    v1::Envelope wrong = frame;
    wrong.set_protocol_version(7);
    std::string text;
    wrong.SerializeToString(&text);
    host.raw(a.endpoint,
             std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
    // Player a's connection id from another address (spoofed).
    v1::Envelope spoof;
    spoof.set_connection_id(a.connection_id);
    spoof.set_sequence(a.sequence + 5);
    spoof.mutable_input_frame()->set_player(a.player);
    spoof.mutable_input_frame()->set_first_tick(t + 1);
    *spoof.mutable_input_frame()->add_inputs() = proto::to_wire(rwd::stick_input(-1000, 0));
    host.raw(attacker, host.encode(spoof));
    // An unknown connection id.
    spoof.set_connection_id(a.connection_id ^ 0x5555);
    host.raw(a.endpoint, host.encode(spoof));
    // Player a claiming to be player b.
    host.send_input(a, t + 1, rwd::stick_input(-1000, -1000, 3), b.player);
    // Far in the future, and for a final tick.
    host.send_input(a, t + 100000, rwd::stick_input(1000, 0), a.player);
    if (t > 10) host.send_input(b, t - 9, rwd::stick_input(-999, 999, 1), b.player);
    // A server-to-client message from a client.
    v1::Envelope bogus;
    bogus.mutable_final_ticks()->set_server_tick(t);
    host.send(a, bogus);
  };
  const auto actual = play(h, 90, attack);

  ASSERT_EQ(actual.size(), expected.size());
  for (const auto& [tick, checksum] : expected) {
    ASSERT_EQ(actual.at(tick), checksum) << "final tick " << tick;
  }
  const MatchStats stats = h.host().stats();
  EXPECT_EQ(stats.substituted_inputs, 0u);
  EXPECT_GE(stats.rejected_packets, 90u * 6);
  EXPECT_GE(stats.rejected_inputs, 90u * 2);
}

TEST(MatchHost, RepeatedJoinIsIdempotentAndExtraPlayersAreRefused) {
  HostHarness h(test_config());
  FakeClient a = h.join(4001);
  FakeClient again = h.join(4001);
  EXPECT_EQ(again.connection_id, a.connection_id);
  h.join(4002);
  const Endpoint late(make_address("127.0.0.1"), 4003);
  v1::Envelope envelope;
  envelope.mutable_join_request()->set_game("crates");
  envelope.mutable_join_request()->set_nonce(9);
  h.admitted(late, h.encode(envelope));
  ASSERT_FALSE(h.outbox().received[late].empty());
  EXPECT_TRUE(h.outbox().received[late].back().has_join_reject());
}

TEST(MatchHost, CountsDownToTickZeroRepeatingMatchStart) {
  MatchConfig config = test_config();
  config.start_delay_s = 0.1;  // 6 ticks at 60 Hz
  HostHarness h(config);
  FakeClient a = h.join(4001);
  h.join(4002);
  EXPECT_EQ(h.host().server_tick(), -6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(h.host().current_tick(), 0);
    h.tick();
  }
  EXPECT_EQ(h.host().server_tick(), 0);
  std::vector<int32_t> announced;
  for (const v1::Envelope& e : h.outbox().received[a.endpoint]) {
    if (e.has_match_start()) announced.push_back(e.match_start().server_tick());
  }
  EXPECT_EQ(announced, (std::vector<int32_t>{-6, -5, -4, -3, -2, -1, 0}));
  h.tick();
  EXPECT_EQ(h.host().current_tick(), 1);
}

TEST(MatchHost, ClosingResendsMatchEndUntilEveryClientSaysGoodbye) {
  MatchConfig config = test_config();
  config.max_ticks = 10;
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  for (Tick t = 0; t < 12 && h.host().phase() == MatchHost::Phase::kRunning; ++t) {
    h.send_input(a, t, {}, a.player);
    h.send_input(b, t, {}, b.player);
    h.tick();
  }
  ASSERT_EQ(h.host().phase(), MatchHost::Phase::kClosing);
  EXPECT_EQ(h.host().last_final_tick(), 9);
  auto match_ends = [&](const FakeClient& c) {
    int n = 0;
    for (const v1::Envelope& e : h.outbox().received[c.endpoint]) n += e.has_match_end();
    return n;
  };
  const int ends_before = match_ends(a);
  h.tick();
  h.tick();
  EXPECT_EQ(match_ends(a), ends_before + 2) << "MatchEnd is repeated every closing tick";
  ASSERT_EQ(h.host().phase(), MatchHost::Phase::kClosing);
  // Both clients say goodbye: the match is over.
  for (FakeClient* c : {&a, &b}) {
    v1::Envelope bye;
    bye.mutable_disconnect()->set_reason("match over");
    h.send(*c, bye);
  }
  h.tick();
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kEnded);
}

// Rules that return an error end their match with the message; the host
// does not tick on past them.
TEST(MatchHost, AnErrorFromTheRulesEndsTheMatchWithItsMessage) {
  ASSERT_TRUE(game::register_game("fails-after-tick-5", [] {
                return std::make_unique<test::FailingGame>(test::FailingGame::Where::kAfterStep, 5);
              }).ok());
  MatchConfig config = test_config();
  config.game = "fails-after-tick-5";
  HostHarness h(config);
  (void)play(h, 20, nullptr);
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kClosing);
  const std::string reason = h.host().stats().end_reason;
  EXPECT_EQ(reason.rfind("the game's rules failed: game 'failing', tick 5: ", 0), 0u) << reason;
  EXPECT_NE(reason.find("the flag's body is gone"), std::string::npos) << reason;
  EXPECT_LE(h.host().last_final_tick(), 4);
}

TEST(MatchHost, AGamesOwnInputIsPlayedAndInputOutsideItsSpecIsRejected) {
  ASSERT_TRUE(
      game::register_game("cars", [] { return std::make_unique<test::CarInputGame>(); }).ok());
  MatchConfig config = test_config();
  config.game = "cars";
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  for (Tick t = 0; t < 20; ++t) {
    const auto brake = static_cast<uint8_t>(t % 2);
    h.send_input(a, t, PlayerInput::of(test::CarInput{-250, 40, brake}), a.player);
    // b's throttle at tick 6 is beyond the game's 100: refused on arrival,
    // and the tick is played with a substitute.
    const auto throttle = static_cast<uint8_t>(t == 6 ? 101 : 90);
    h.send_input(b, t, PlayerInput::of(test::CarInput{300, throttle, 0}), b.player);
    h.tick();
  }
  const MatchStats stats = h.host().stats();
  EXPECT_EQ(stats.rejected_inputs, 1u);
  EXPECT_GE(stats.ticks_final, 14);
  EXPECT_EQ(stats.substituted_inputs, 1u);
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kRunning);
}

TEST(MatchHost, ConfigErrorsAreReported) {
  MatchConfig config = test_config();
  config.game = "chess";
  auto host = MatchHost::create(
      config, [](const Endpoint&, std::span<const uint8_t>) {}, net::SteadyClock::now());
  ASSERT_FALSE(host.ok());
  EXPECT_NE(host.status().message().find("unknown game"), std::string::npos);
  config = test_config();
  config.window_ticks = 0;
  EXPECT_FALSE(
      MatchHost::create(
          config, [](const Endpoint&, std::span<const uint8_t>) {}, net::SteadyClock::now())
          .ok());
}

TEST(MatchHost, ReplayHeaderNamesThisBuildAndAStoppedMatchVerifiesAsIncomplete) {
  const test::ScratchDir dir("match_host_replay");
  const std::string path = (dir.path() / "match.rwr").string();
  MatchConfig config = test_config();
  config.replay_path = path;
  Tick finals = 0;
  {
    HostHarness h(config);
    play(h, 40, nullptr);
    finals = h.host().stats().ticks_final;
    ASSERT_GT(finals, 20);
  }  // the host goes away without ending the match, as a killed server would

  Result<replay::ReplayReader> reader = replay::ReplayReader::open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  const v1::ReplayHeader& header = reader->header();
  EXPECT_EQ(header.format_version(), replay::kFormatVersion);
  EXPECT_EQ(header.engine(), sim::kEngineName);
  EXPECT_EQ(header.sim_revision(), sim::kSimRevision);
  EXPECT_EQ(header.rules_version(), game::make_builtin_game("crates")->rules_version());
  std::vector<uint8_t> config_bytes;
  sim::World3D::encode_config(game::CratesGame().world_config(), config_bytes);
  EXPECT_EQ(header.world_config(), std::string(config_bytes.begin(), config_bytes.end()));
  EXPECT_TRUE(replay::check_versions(header).matches());

  const replay::VerifyReport report = replay::verify_replay(path);
  EXPECT_EQ(report.outcome(), replay::VerifyOutcome::kIncomplete);
  EXPECT_EQ(report.ticks_verified, static_cast<uint64_t>(finals));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rwd::server
