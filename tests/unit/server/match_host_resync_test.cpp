// SPDX-License-Identifier: MIT
// The match host's desync path: one snapshot per resync episode, snapshots
// checked to load before they go out (and the fallback when they do not),
// snapshots a client refuses, desync reports whose dump is unreadable or
// cannot be written.
#include "match_host_harness.h"
#include "scratch_dir.h"

namespace rwd::server {
namespace {

using namespace host_test;  // NOLINT: test helpers
using test::ScratchDir;

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

TEST(MatchHost, DesyncReportsGoToTheFilesOfItsEnvironment) {
  // A disk that exists only in this test: the host must create and write
  // nothing but through it.
  std::map<std::string, std::string> files;
  std::vector<std::string> directories;
  MatchEnvironment env;
  env.unix_ms = [] { return int64_t{1'700'000'000'000}; };
  env.create_directories = [&](const std::string& path) {
    directories.push_back(path);
    return Status::Ok();
  };
  env.write_file = [&](const std::string& path, std::span<const uint8_t> bytes) {
    files[path] = std::string(bytes.begin(), bytes.end());
    return Status::Ok();
  };
  MatchConfig config = test_config();
  config.desync_dir = "/nonexistent/rewind-test-reports";
  HostHarness h(config, env);
  ASSERT_EQ(directories, std::vector<std::string>{config.desync_dir});
  FakeClient a = h.join(4001);
  FakeClient b = h.join(4002);
  h.play_on_time(a, b, 20);
  v1::Envelope report;
  v1::DesyncReport* r = report.mutable_desync_report();
  r->set_tick(3);
  r->set_report_id(5);
  r->set_chunk_index(0);
  r->set_chunk_count(1);
  r->set_total_size(4);
  r->set_chunk("dump");
  h.send(a, report);
  EXPECT_FALSE(std::filesystem::exists(config.desync_dir));
  const std::string base = config.desync_dir + "/desync_p" + std::to_string(a.player) + "_t3_r5";
  ASSERT_EQ(files.count(base + ".bin"), 1u);
  EXPECT_EQ(files[base + ".bin"], "dump");
  ASSERT_EQ(files.count(base + ".txt"), 1u);
  EXPECT_NE(files[base + ".txt"].find("desync at tick 3"), std::string::npos);
  EXPECT_EQ(h.host().stats().desync_report_write_failures, 0u);

  // The same disk refusing: counted, and the match goes on.
  env.write_file = [](const std::string&, std::span<const uint8_t>) {
    return Status::Error(ErrorCode::kIo, "disk full");
  };
  HostHarness failing(config, env);
  FakeClient c = failing.join(4003);
  FakeClient d = failing.join(4004);
  failing.play_on_time(c, d, 20);
  r->set_report_id(6);
  failing.send(c, report);
  EXPECT_EQ(failing.host().stats().desync_report_write_failures, 1u);
  EXPECT_EQ(failing.host().stats().resyncs_sent, 1u);
}

}  // namespace
}  // namespace rwd::server
