// SPDX-License-Identifier: MIT
// Bundles made from replay files as the server writes them: every tick's
// inputs and checksum, a torn file's whole prefix, and a server's desync
// report attached by its file name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "replay_test_support.h"
#include "rewind/replay/replay_view.h"
#include "rewind/viewer/replay_player.h"

namespace rwd::replay {
namespace {

using testing_support::record_match;
using testing_support::Recording;
using testing_support::TempFile;

TEST(ReplayView, AReplayPlaysBackWithItsChecksums) {
  TempFile file("view_whole");
  Recording rec;
  rec.ticks = 180;
  const std::vector<uint64_t> recorded = record_match(file.path(), rec);
  auto reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  ReplayViewInfo info;
  auto bundle = view_bundle_from_replay(*reader, &info);
  ASSERT_TRUE(bundle.ok()) << bundle.status().message();
  EXPECT_EQ(info.file_state, ReadState::kComplete);
  EXPECT_TRUE(info.problem.empty());
  EXPECT_TRUE(bundle->identity_matches) << bundle->identity_note;
  EXPECT_EQ(bundle->game, "crates");
  EXPECT_EQ(bundle->setup.player_count, 4u);
  EXPECT_EQ(bundle->checksums, recorded);
  EXPECT_EQ(bundle->substituted_masks[49], 1u);  // player 0 dropped out then
  // The replay's keyframes (after ticks 59, 119, 179) come along to seek by.
  ASSERT_EQ(bundle->keyframes.size(), 3u);
  EXPECT_EQ(bundle->keyframes[0].position, 60);
  EXPECT_EQ(bundle->keyframes[2].position, 180);

  std::vector<uint8_t> bytes;
  ASSERT_TRUE(viewer::encode_view_bundle(*bundle, bytes).ok());
  auto decoded = viewer::decode_view_bundle(bytes);
  ASSERT_TRUE(decoded.ok());
  auto player = viewer::ReplayPlayer::create(std::move(*decoded));
  ASSERT_TRUE(player.ok());
  (*player)->seek(170);  // from the keyframe at 120
  EXPECT_EQ((*player)->checksum(), recorded[169]);
  EXPECT_EQ((*player)->check(120), viewer::TickCheck::kMatch);
  EXPECT_EQ((*player)->check(100), viewer::TickCheck::kUnchecked);  // jumped over
  (*player)->seek(0);
  while ((*player)->step()) {
  }
  EXPECT_FALSE((*player)->first_mismatch().has_value());
  EXPECT_EQ((*player)->checksum(), recorded.back());
}

TEST(ReplayView, ATornReplayGivesItsWholeTicks) {
  TempFile file("view_torn");
  Recording rec;
  rec.ticks = 120;
  rec.finish = false;
  rec.keyframe_interval = 0;  // tick records only: the cut falls among them
  const std::vector<uint64_t> recorded = record_match(file.path(), rec);
  testing_support::cut_inside_frame(file.path(), 0.6);
  auto reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  ReplayViewInfo info;
  auto bundle = view_bundle_from_replay(*reader, &info);
  ASSERT_TRUE(bundle.ok());
  EXPECT_EQ(info.file_state, ReadState::kTorn);
  EXPECT_FALSE(info.problem.empty());
  ASSERT_GT(bundle->tick_count(), 10u);
  ASSERT_LT(bundle->tick_count(), 120u);
  EXPECT_TRUE(std::equal(bundle->checksums.begin(), bundle->checksums.end(), recorded.begin()));
}

TEST(ReplayView, ADesyncReportIsAttachedByItsFileName) {
  TempFile file("view_desync");
  Recording rec;
  rec.players = 2;
  rec.ticks = 90;
  record_match(file.path(), rec);
  auto reader = ReplayReader::open(file.path());
  auto bundle = view_bundle_from_replay(*reader, nullptr);
  ASSERT_TRUE(bundle.ok());

  // The client's state after tick 40, nudged, stored as the server does.
  auto client = game::Simulation::create("crates", bundle->setup);
  for (Tick t = 0; t <= 40; ++t) {
    ASSERT_TRUE((*client)
                    ->step(std::span<const rwd::PlayerInput>(bundle->inputs)
                               .subspan(static_cast<size_t>(t) * 2, 2))
                    .ok());
  }
  ASSERT_TRUE((*client)->lane().perturb_for_drill());
  std::vector<uint8_t> state;
  (*client)->serialize(state);
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("view_desync_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string bin = (dir / "desync_p1_t40_r3.bin").string();
  std::ofstream(bin, std::ios::binary)
      .write(reinterpret_cast<const char*>(state.data()),
             static_cast<std::streamsize>(state.size()));
  std::ofstream(dir / "desync_p1_t40_r3.txt")
      << "player 1 desync at tick 40: client 0x1 server 0x2\n"
      << "3 differing fields\n";

  viewer::ViewBundle with = *bundle;
  ASSERT_TRUE(attach_desync_report(with, bin).ok());
  ASSERT_TRUE(with.desync.has_value());
  EXPECT_EQ(with.desync->tick, 40);
  EXPECT_EQ(with.desync->player, 1u);
  EXPECT_EQ(with.desync->headline, "player 1 desync at tick 40: client 0x1 server 0x2");
  auto player = viewer::ReplayPlayer::create(with);
  auto view = (*player)->open_desync();
  ASSERT_TRUE(view.ok()) << view.status().message();
  EXPECT_EQ(view->bodies.size(), 1u);

  // Names of another form, ticks past the replay, missing files: refused,
  // the bundle unchanged.
  viewer::ViewBundle untouched = *bundle;
  EXPECT_FALSE(attach_desync_report(untouched, (dir / "state.bin").string()).ok());
  EXPECT_FALSE(attach_desync_report(untouched, (dir / "desync_p1_t89_r0.bin").string()).ok());
  const Status missing = attach_desync_report(untouched, (dir / "desync_p1_t20_r0.bin").string());
  EXPECT_EQ(missing.code(), ErrorCode::kIo);
  EXPECT_FALSE(untouched.desync.has_value());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rwd::replay
