// SPDX-License-Identifier: MIT
// MatchHost driven without sockets: scripted clients build envelopes by
// hand, and the clock is whatever the test says.
#include "rewind/server/match_host.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "rewind/game/simulation.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/replay/engine_identity.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_verifier.h"
#include "rewind/sim/version.h"
#include "rewind/sim/world3d.h"

namespace rwd::server {
namespace {

using asio::ip::make_address;

struct Outbox {
  std::map<Endpoint, std::vector<v1::Envelope>> received;
  void deliver(const Endpoint& to, std::span<const uint8_t> bytes) {
    auto decoded = net::decode_envelope(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    received[to].push_back(*decoded);
  }
};

struct FakeClient {
  Endpoint endpoint;
  uint64_t connection_id = 0;
  uint32_t player = 0;
  uint32_t sequence = 1;
};

game::PlayerInput scripted(uint32_t player, Tick tick) {
  return {static_cast<int16_t>(((tick / 5 + player) % 3 - 1) * 900),
          static_cast<int16_t>(((tick / 7 + player) % 3 - 1) * 700), 0};
}

class HostHarness {
 public:
  explicit HostHarness(MatchConfig config) {
    now_ = net::SteadyClock::now();
    auto host = MatchHost::create(
        config, [this](const Endpoint& to, std::span<const uint8_t> b) { outbox_.deliver(to, b); },
        now_);
    EXPECT_TRUE(host.ok()) << host.status().message();
    host_ = std::move(*host);
  }

  std::vector<uint8_t> encode(v1::Envelope envelope) {
    envelope.set_protocol_version(net::kProtocolVersion);
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(net::encode_envelope(envelope, bytes).ok());
    return bytes;
  }
  void raw(const Endpoint& from, std::span<const uint8_t> bytes) {
    host_->on_datagram(bytes, from, now_);
  }
  void send(FakeClient& client, v1::Envelope envelope) {
    envelope.set_connection_id(client.connection_id);
    envelope.set_sequence(client.sequence++);
    raw(client.endpoint, encode(envelope));
  }
  FakeClient join(uint16_t port) {
    FakeClient client;
    client.endpoint = Endpoint(make_address("127.0.0.1"), port);
    v1::Envelope envelope;
    envelope.mutable_join_request()->set_game("crates");
    envelope.mutable_join_request()->set_nonce(port);
    raw(client.endpoint, encode(envelope));
    for (const v1::Envelope& answer : outbox_.received[client.endpoint]) {
      if (answer.has_join_accept()) {
        client.connection_id = answer.join_accept().connection_id();
        client.player = answer.join_accept().player();
      }
    }
    EXPECT_NE(client.connection_id, 0u);
    return client;
  }
  void send_input(FakeClient& client, Tick tick, game::PlayerInput input, uint32_t as_player) {
    v1::Envelope envelope;
    v1::InputFrame* frame = envelope.mutable_input_frame();
    frame->set_player(as_player);
    frame->set_first_tick(tick);
    v1::Input* in = frame->add_inputs();
    in->set_axis_x(input.axis_x);
    in->set_axis_y(input.axis_y);
    in->set_buttons(input.buttons);
    send(client, envelope);
  }
  void tick() {
    now_ += std::chrono::milliseconds(16);
    host_->on_tick(now_);
  }
  /// Both players send on time for `ticks` ticks, acknowledging nothing.
  void play_on_time(FakeClient& a, FakeClient& b, Tick ticks) {
    for (Tick i = 0; i < ticks; ++i) {
      const Tick t = host_->current_tick();
      send_input(a, t, scripted(a.player, t), a.player);
      send_input(b, t, scripted(b.player, t), b.player);
      tick();
    }
  }
  void request_resync(FakeClient& client, uint32_t refused_id = 0) {
    v1::Envelope request;
    request.mutable_resync_request()->set_desync_tick(0);
    request.mutable_resync_request()->set_refused_snapshot_id(refused_id);
    if (refused_id != 0) request.mutable_resync_request()->set_refused_reason("test refusal");
    send(client, request);
  }
  void acknowledge_finals(FakeClient& client, Tick through) {
    v1::Envelope ack;
    ack.mutable_input_frame()->set_player(client.player);
    ack.mutable_input_frame()->set_first_tick(host_->current_tick());
    ack.mutable_input_frame()->set_last_final_tick_seen(through);
    send(client, ack);
  }
  MatchHost& host() { return *host_; }
  Outbox& outbox() { return outbox_; }

 private:
  Outbox outbox_;
  TimePoint now_;
  std::unique_ptr<MatchHost> host_;
};

MatchConfig test_config() {
  MatchConfig config;
  config.players = 2;
  config.window_ticks = 4;
  config.keyframe_interval = 0;
  config.start_delay_s = 0;
  return config;
}

// Plays `ticks` ticks with both players sending on time (player 1's input
// two ticks late, to exercise rollback); `attack` runs before every tick.
std::map<Tick, uint64_t> play(
    HostHarness& h, Tick ticks,
    const std::function<void(HostHarness&, FakeClient&, FakeClient&, Tick)>& attack) {
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  EXPECT_EQ(h.host().phase(), MatchHost::Phase::kRunning);
  std::map<Tick, uint64_t> finals;
  for (Tick t = 0; t < ticks; ++t) {
    h.send_input(a, t, scripted(a.player, t), a.player);
    if (t >= 2) h.send_input(b, t - 2, scripted(b.player, t - 2), b.player);
    if (attack) attack(h, a, b, t);
    h.tick();
    for (const v1::FinalTick& f : h.host().recent_finals()) finals[f.tick()] = f.checksum();
  }
  return finals;
}

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
  h.send_input(b, 0, {1000, 0, 0}, b.player);
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
    frame.mutable_input_frame()->add_inputs()->set_axis_x(5);
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
    spoof.mutable_input_frame()->add_inputs()->set_axis_x(-1000);
    host.raw(attacker, host.encode(spoof));
    // An unknown connection id.
    spoof.set_connection_id(a.connection_id ^ 0x5555);
    host.raw(a.endpoint, host.encode(spoof));
    // Player a claiming to be player b.
    host.send_input(a, t + 1, {-1000, -1000, 3}, b.player);
    // Far in the future, and for a final tick.
    host.send_input(a, t + 100000, {1000, 0, 0}, a.player);
    if (t > 10) host.send_input(b, t - 9, {-999, 999, 1}, b.player);
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
  h.raw(late, h.encode(envelope));
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

TEST(MatchHost, ResyncRepeatsOneSnapshotUntilAcknowledged) {
  HostHarness h(test_config());
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  for (Tick t = 0; t < 20; ++t) {
    h.send_input(a, t, scripted(a.player, t), a.player);
    h.send_input(b, t, scripted(b.player, t), b.player);
    h.tick();
  }
  auto resyncs = [&]() {
    std::vector<std::pair<uint32_t, Tick>> out;  // (snapshot id, tick) of chunk 0s
    for (const v1::Envelope& e : h.outbox().received[a.endpoint]) {
      if (e.has_resync_chunk() && e.resync_chunk().chunk_index() == 0) {
        out.emplace_back(e.resync_chunk().snapshot_id(), e.resync_chunk().tick());
      }
    }
    return out;
  };
  v1::Envelope request;
  request.mutable_resync_request()->set_desync_tick(5);
  h.send(a, request);
  ASSERT_EQ(resyncs().size(), 1u);
  const auto [id, tick] = resyncs().front();
  // No acknowledgement for a while: the same snapshot comes again, and the
  // server's clock keeps flowing in FinalTicks without ticks.
  size_t finals_before = h.outbox().received[a.endpoint].size();
  for (int i = 0; i < 40; ++i) {
    h.send_input(b, 20 + i, {}, b.player);
    h.tick();
  }
  const auto repeated = resyncs();
  ASSERT_GE(repeated.size(), 2u);
  for (const auto& r : repeated) EXPECT_EQ(r, std::make_pair(id, tick));
  bool saw_empty_finals = false;
  for (size_t i = finals_before; i < h.outbox().received[a.endpoint].size(); ++i) {
    const v1::Envelope& e = h.outbox().received[a.endpoint][i];
    if (e.has_final_ticks()) saw_empty_finals = e.final_ticks().ticks_size() == 0;
  }
  EXPECT_TRUE(saw_empty_finals);
  // The client acknowledges tick - 1: the episode ends, final ticks resume.
  v1::Envelope ack;
  ack.mutable_input_frame()->set_player(a.player);
  ack.mutable_input_frame()->set_first_tick(60);
  ack.mutable_input_frame()->set_last_final_tick_seen(tick - 1);
  h.send(a, ack);
  h.tick();
  const v1::Envelope& last = h.outbox().received[a.endpoint].back();
  ASSERT_TRUE(last.has_final_ticks());
  ASSERT_GT(last.final_ticks().ticks_size(), 0);
  EXPECT_EQ(last.final_ticks().ticks(0).tick(), tick);
  EXPECT_EQ(h.host().stats().resyncs_sent, 1u);
}

// A whole snapshot as the client would assemble it from the chunks it got.
struct ReceivedSnapshot {
  uint32_t id = 0;
  Tick tick = kNoTick;
  uint64_t checksum = 0;
  std::vector<uint8_t> bytes;
};

std::vector<ReceivedSnapshot> received_snapshots(const std::vector<v1::Envelope>& inbox) {
  std::map<uint32_t, ReceivedSnapshot> by_id;
  std::map<uint32_t, std::map<uint32_t, std::string>> chunks;
  std::vector<uint32_t> order;
  for (const v1::Envelope& e : inbox) {
    if (!e.has_resync_chunk()) continue;
    const v1::ResyncChunk& c = e.resync_chunk();
    if (!by_id.count(c.snapshot_id())) order.push_back(c.snapshot_id());
    by_id[c.snapshot_id()] = {c.snapshot_id(), c.tick(), c.checksum(), {}};
    chunks[c.snapshot_id()][c.chunk_index()] = c.chunk();
  }
  std::vector<ReceivedSnapshot> out;
  for (uint32_t id : order) {
    ReceivedSnapshot snapshot = by_id[id];
    for (const auto& [index, part] : chunks[id]) {
      snapshot.bytes.insert(snapshot.bytes.end(), part.begin(), part.end());
    }
    out.push_back(std::move(snapshot));
  }
  return out;
}

// Loads a received snapshot the way a client does and returns the checksum
// of what it loaded.
uint64_t load_like_a_client(const MatchConfig& config, const ReceivedSnapshot& snapshot) {
  auto sim = game::Simulation::create(config.game, {config.players, config.seed});
  EXPECT_TRUE(sim.ok());
  const Status status = (*sim)->deserialize(snapshot.bytes);
  EXPECT_TRUE(status.ok()) << status.message();
  EXPECT_EQ((*sim)->tick(), snapshot.tick);
  return (*sim)->checksum();
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string hex(uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof(text), "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::path(testing::TempDir()) /
              (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(MatchHost, ResyncSnapshotThatDoesNotLoadIsNeverSent) {
  const MatchConfig config = test_config();
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 20);
  // Every snapshot is damaged after serialization (its magic overwritten):
  // the server's own load check must refuse each one.
  bool damage = true;
  h.host().set_resync_snapshot_hook([&damage](Tick, std::vector<uint8_t>& bytes) {
    if (damage) bytes[0] = 'X';
  });
  h.request_resync(a);
  EXPECT_TRUE(received_snapshots(h.outbox().received[a.endpoint]).empty());
  EXPECT_EQ(h.host().stats().resyncs_sent, 0u);
  EXPECT_GE(h.host().stats().resync_snapshot_failures, 1u);
  // The match goes on meanwhile.
  h.play_on_time(a, b, 20);
  EXPECT_GE(h.host().stats().ticks_final, 30);
  // The client keeps asking; once snapshots load again it gets one, and it
  // is one a client can load.
  const uint64_t failures = h.host().stats().resync_snapshot_failures;
  damage = false;
  h.request_resync(a);
  const auto snapshots = received_snapshots(h.outbox().received[a.endpoint]);
  ASSERT_EQ(snapshots.size(), 1u);
  EXPECT_EQ(h.host().stats().resync_snapshot_failures, failures);
  EXPECT_EQ(h.host().stats().resyncs_sent, 1u);
  EXPECT_EQ(load_like_a_client(config, snapshots[0]), snapshots[0].checksum);
  EXPECT_EQ(snapshots[0].tick, h.host().last_final_tick() + 1);
}

TEST(MatchHost, ResyncFallsBackToAnOlderFinalStateWhenTheNewestDoesNotLoad) {
  const MatchConfig config = test_config();
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 30);
  std::map<Tick, uint64_t> final_checksums;
  for (const v1::FinalTick& f : h.host().recent_finals()) final_checksums[f.tick()] = f.checksum();
  const Tick newest = h.host().last_final_tick() + 1;
  // Client a has seen the final ticks up to newest - 3: it can restart from
  // newest - 2 at the earliest.
  h.acknowledge_finals(a, newest - 3);
  // The newest state's bytes claim the next tick: they load, but do not
  // reproduce the checksum the server would announce with them.
  std::vector<Tick> checked;
  h.host().set_resync_snapshot_hook([&](Tick tick, std::vector<uint8_t>& bytes) {
    checked.push_back(tick);
    if (tick == newest) ++bytes[6];  // low byte of the encoded tick
  });
  h.request_resync(a);
  EXPECT_EQ(checked, (std::vector<Tick>{newest, newest - 2}));
  const auto snapshots = received_snapshots(h.outbox().received[a.endpoint]);
  ASSERT_EQ(snapshots.size(), 1u);
  EXPECT_EQ(snapshots[0].tick, newest - 2);
  EXPECT_EQ(snapshots[0].checksum, final_checksums.at(newest - 3))
      << "the state at the start of a tick is the state after the final tick before it";
  EXPECT_EQ(load_like_a_client(config, snapshots[0]), snapshots[0].checksum);
  EXPECT_EQ(h.host().stats().resync_snapshot_failures, 1u);
  EXPECT_EQ(h.host().stats().resyncs_sent, 1u);
  // Once the client has the snapshot it acknowledges the tick before it, and
  // the final ticks from the snapshot on come (again).
  h.acknowledge_finals(a, newest - 3);
  h.tick();
  std::vector<Tick> resent;
  const v1::Envelope& last = h.outbox().received[a.endpoint].back();
  ASSERT_TRUE(last.has_final_ticks());
  for (const v1::FinalTick& f : last.final_ticks().ticks()) resent.push_back(f.tick());
  EXPECT_NE(std::find(resent.begin(), resent.end(), newest - 2), resent.end());
}

TEST(MatchHost, RefusedSnapshotIsCountedAndReplacedByAnother) {
  const MatchConfig config = test_config();
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 20);
  h.request_resync(a);
  auto snapshots = received_snapshots(h.outbox().received[a.endpoint]);
  ASSERT_EQ(snapshots.size(), 1u);
  const uint32_t first_id = snapshots[0].id;
  // The client says it could not load that one; after the resend interval
  // it gets a new snapshot, not the same bytes again.
  h.request_resync(a, first_id);
  h.play_on_time(a, b, 20);
  h.request_resync(a, first_id);  // a late copy of the same refusal
  h.play_on_time(a, b, 20);
  snapshots = received_snapshots(h.outbox().received[a.endpoint]);
  ASSERT_EQ(snapshots.size(), 2u);
  EXPECT_NE(snapshots[1].id, first_id);
  EXPECT_GT(snapshots[1].tick, snapshots[0].tick);
  EXPECT_EQ(load_like_a_client(config, snapshots[1]), snapshots[1].checksum);
  const MatchStats stats = h.host().stats();
  EXPECT_EQ(stats.resyncs_refused, 1u);
  EXPECT_EQ(stats.resyncs_sent, 2u);
  EXPECT_NE(stats.problems().find("1 resync snapshots were refused"), std::string::npos)
      << stats.problems();
  EXPECT_NE(stats.to_json().find("\"resyncs_refused\":1"), std::string::npos);
}

// A desync report whose dump is garbage: still stored with the tick and
// both checksums, the raw bytes kept, counted, and the client resynced.
TEST(MatchHost, DesyncReportWithUnreadableDumpKeepsTickAndChecksums) {
  ScratchDir dir("desync_garbage");
  MatchConfig config = test_config();
  config.desync_dir = dir.path().string();
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 30);
  const Tick tick = h.host().last_final_tick() - 2;
  uint64_t server_checksum = 0;
  for (const v1::FinalTick& f : h.host().recent_finals()) {
    if (f.tick() == tick) server_checksum = f.checksum();
  }
  ASSERT_NE(server_checksum, 0u);
  // Every client has seen the tick: the server no longer holds it for
  // resending, but still knows its checksum.
  h.acknowledge_finals(a, tick + 1);
  h.acknowledge_finals(b, tick + 1);
  h.tick();
  ASSERT_GT(h.host().recent_finals().front().tick(), tick);

  const std::string garbage = "this is not a simulation";
  v1::Envelope report;
  v1::DesyncReport* r = report.mutable_desync_report();
  r->set_tick(tick);
  r->set_client_checksum(0x1234567890abcdefull);
  r->set_server_checksum(server_checksum);
  r->set_report_id(7);
  r->set_chunk_index(0);
  r->set_chunk_count(1);
  r->set_total_size(static_cast<uint32_t>(garbage.size()));
  r->set_chunk(garbage);
  h.send(a, report);

  const MatchStats stats = h.host().stats();
  EXPECT_EQ(stats.desync_reports, 1u);
  EXPECT_EQ(stats.desync_dumps_unreadable, 1u);
  EXPECT_EQ(stats.desync_report_write_failures, 0u);
  EXPECT_EQ(stats.resyncs_sent, 1u) << "an unreadable dump still gets its sender resynced";
  const std::string base =
      "desync_p" + std::to_string(a.player) + "_t" + std::to_string(tick) + "_r7";
  const std::string text = read_text(dir.path() / (base + ".txt"));
  const std::string first_line = text.substr(0, text.find('\n'));
  EXPECT_NE(first_line.find("desync at tick " + std::to_string(tick)), std::string::npos) << text;
  EXPECT_NE(first_line.find("client 0x1234567890abcdef"), std::string::npos) << text;
  EXPECT_NE(first_line.find("server " + hex(server_checksum)), std::string::npos) << text;
  EXPECT_NE(text.find("client dump unreadable"), std::string::npos) << text;
  EXPECT_EQ(read_text(dir.path() / (base + ".bin")), garbage);
  EXPECT_NE(stats.problems().find("unreadable client dump"), std::string::npos);
}

TEST(MatchHost, DesyncReportThatCannotBeWrittenIsCounted) {
  ScratchDir dir("desync_unwritable");
  MatchConfig config = test_config();
  config.desync_dir = dir.path().string();
  HostHarness h(config);
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 20);
  std::filesystem::remove_all(dir.path());  // the directory went away mid-match
  v1::Envelope report;
  v1::DesyncReport* r = report.mutable_desync_report();
  r->set_tick(3);
  r->set_report_id(1);
  r->set_chunk_index(0);
  r->set_chunk_count(1);
  r->set_total_size(3);
  r->set_chunk("abc");
  h.send(a, report);
  const MatchStats stats = h.host().stats();
  EXPECT_EQ(stats.desync_reports, 1u);
  EXPECT_EQ(stats.desync_report_write_failures, 1u);
  EXPECT_EQ(stats.resyncs_sent, 1u);
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
  const std::string path =
      (std::filesystem::path(::testing::TempDir()) / "match_host_replay.rwr").string();
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
  sim::World3D::encode_config(game::make_builtin_game("crates")->world_config(), config_bytes);
  EXPECT_EQ(header.world_config(), std::string(config_bytes.begin(), config_bytes.end()));
  EXPECT_TRUE(replay::check_versions(header).matches());

  const replay::VerifyReport report = replay::verify_replay(path);
  EXPECT_EQ(report.outcome(), replay::VerifyOutcome::kIncomplete);
  EXPECT_EQ(report.ticks_verified, static_cast<uint64_t>(finals));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rwd::server
