// SPDX-License-Identifier: MIT
// The replay writer: round trips, refused appends, flushing, write errors.
#include "replay_io_support.h"

namespace rwd::replay {
namespace {

using namespace io_test;  // NOLINT: test helpers

TEST(ReplayIo, WriterReaderRoundTrip) {
  TempFile file("round_trip");
  write_small_replay(file.path(), 6);

  Result<ReplayReader> reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  EXPECT_EQ(reader->header().game(), "crates");
  EXPECT_EQ(reader->header().player_count(), 3u);
  EXPECT_EQ(reader->header().seed(), 42u);
  EXPECT_EQ(reader->header().format_version(), kFormatVersion);

  std::vector<v1::ReplayRecord> records;
  ASSERT_EQ(drain(*reader, &records), "");
  ASSERT_EQ(records.size(), 6u + 2u + 1u);
  Tick expected_tick = 0;
  int keyframes = 0;
  for (const v1::ReplayRecord& r : records) {
    if (r.has_tick()) {
      EXPECT_EQ(r.tick().tick(), expected_tick);
      EXPECT_EQ(r.tick().checksum(), checksum_for(expected_tick));
      EXPECT_EQ(r.tick().substituted_mask(), expected_tick == 2 ? 0b101u : 0u);
      const std::vector<rwd::PlayerInput> want = inputs_for(expected_tick, 3);
      ASSERT_EQ(r.tick().inputs_size(), 3);
      for (int p = 0; p < 3; ++p) {
        EXPECT_EQ(*proto::from_wire(r.tick().inputs(p)), want[static_cast<size_t>(p)]);
      }
      ++expected_tick;
    } else if (r.has_keyframe()) {
      EXPECT_EQ(r.keyframe().tick(), expected_tick - 1);
      EXPECT_EQ(r.keyframe().state(), std::string(17, static_cast<char>(expected_tick - 1)));
      ++keyframes;
    } else {
      ASSERT_TRUE(r.has_end());
      EXPECT_EQ(r.end().last_final_tick(), 5);
      EXPECT_EQ(r.end().reason(), "match over");
    }
  }
  EXPECT_EQ(keyframes, 2);
  EXPECT_TRUE(reader->ended());
  EXPECT_EQ(reader->last_tick(), 5);
  EXPECT_EQ(reader->offset(), file_size(file.path()));
  // Reading past the end stays at the end.
  Result<std::optional<v1::ReplayRecord>> again = reader->next();
  ASSERT_TRUE(again.ok());
  EXPECT_FALSE(again->has_value());
}

TEST(ReplayIo, WriterRefusesOutOfOrderAndMalformedAppends) {
  TempFile file("order");
  Result<ReplayWriter> w = ReplayWriter::open(file.path(), test_header());
  ASSERT_TRUE(w.ok());
  const auto in = inputs_for(0, 3);

  Status s = w->append_tick(1, in, 0, 1);
  EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(s.message().find("expected tick 0"), std::string::npos) << s.message();
  ASSERT_TRUE(w->append_tick(0, in, 0, 1).ok());
  EXPECT_EQ(w->append_tick(0, in, 0, 1).code(), ErrorCode::kInvalidArgument);  // repeat
  s = w->append_tick(2, in, 0, 1);                                             // gap
  EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(s.message().find("after tick 0"), std::string::npos) << s.message();
  EXPECT_EQ(w->append_tick(-1, in, 0, 1).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(w->append_tick(1, inputs_for(1, 2), 0, 1).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(w->append_tick(1, in, 0b1000, 1).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(w->append_keyframe(1, std::vector<uint8_t>{1}).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(w->finish(3, "x").code(), ErrorCode::kInvalidArgument);
  // Refusals changed nothing: tick 1 is still the next one.
  EXPECT_EQ(w->last_tick(), 0);
  ASSERT_TRUE(w->append_tick(1, in, 0b100, 2).ok());
  ASSERT_TRUE(w->append_keyframe(1, std::vector<uint8_t>{1}).ok());
  EXPECT_EQ(w->append_keyframe(1, std::vector<uint8_t>{1}).code(), ErrorCode::kInvalidArgument);
  ASSERT_TRUE(w->finish(1, "done").ok());
  EXPECT_TRUE(w->finished());
  EXPECT_FALSE(w->append_tick(2, in, 0, 3).ok());
  EXPECT_FALSE(w->finish(1, "again").ok());

  Result<ReplayReader> reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(drain(*reader), "");
  EXPECT_EQ(reader->last_tick(), 1);
  EXPECT_TRUE(reader->ended());
}

TEST(ReplayIo, WriterRefusesExistingFileAndBadHeader) {
  TempFile file("exists");
  write_all(file.path(), {1, 2, 3});
  Result<ReplayWriter> w = ReplayWriter::open(file.path(), test_header());
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.status().message().find("already exists"), std::string::npos);
  EXPECT_EQ(read_all(file.path()).size(), 3u);  // untouched

  ReplayWriterOptions overwrite;
  overwrite.overwrite = true;
  EXPECT_TRUE(ReplayWriter::open(file.path(), test_header(), overwrite).ok());

  write_all(file.path(), {});  // empty files are fair game
  EXPECT_TRUE(ReplayWriter::open(file.path(), test_header()).ok());

  EXPECT_FALSE(ReplayWriter::open(file.path(), test_header(0), overwrite).ok());
  EXPECT_FALSE(ReplayWriter::open(file.path(), test_header(33), overwrite).ok());
  v1::ReplayHeader no_game = test_header();
  no_game.clear_game();
  EXPECT_FALSE(ReplayWriter::open(file.path(), no_game, overwrite).ok());

  // The writer fills in the current format, keeps an older readable one
  // (copies of old files) and cannot write a newer one.
  v1::ReplayHeader old_format = test_header();
  old_format.set_format_version(1);
  old_format.clear_engine();
  old_format.clear_sim_revision();
  old_format.clear_world_config();
  ASSERT_TRUE(ReplayWriter::open(file.path(), old_format, overwrite).ok());
  {
    Result<ReplayReader> reader = ReplayReader::open(file.path());
    ASSERT_TRUE(reader.ok()) << reader.status().message();
    EXPECT_EQ(reader->header().format_version(), 1u);
  }
  v1::ReplayHeader newer = test_header();
  newer.set_format_version(kFormatVersion + 1);
  Result<ReplayWriter> refused = ReplayWriter::open(file.path(), newer, overwrite);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  v1::ReplayHeader anonymous = test_header();
  anonymous.clear_sim_revision();
  EXPECT_FALSE(ReplayWriter::open(file.path(), anonymous, overwrite).ok());

  Result<ReplayWriter> dir = ReplayWriter::open(testing::TempDir(), test_header(), overwrite);
  ASSERT_FALSE(dir.ok());
  EXPECT_EQ(dir.status().code(), ErrorCode::kIo);
}

TEST(ReplayIo, WriterFlushesOncePerIntervalAndOnKeyframes) {
  TempFile file("flush");
  TimePoint now{};
  ReplayWriterOptions options;
  options.clock = [&now] { return now; };
  Result<ReplayWriter> w = ReplayWriter::open(file.path(), test_header(), options);
  ASSERT_TRUE(w.ok());
  const uint64_t after_header = file_size(file.path());
  EXPECT_GT(after_header, kMagic.size());  // the header is on disk at once
  EXPECT_EQ(w->bytes_buffered(), 0u);

  for (Tick t = 0; t < 30; ++t) {
    now += milliseconds(16);
    ASSERT_TRUE(w->append_tick(t, inputs_for(t, 3), 0, checksum_for(t)).ok());
  }
  EXPECT_EQ(file_size(file.path()), after_header);  // 480 ms: still buffered
  EXPECT_GT(w->bytes_buffered(), 0u);
  now += milliseconds(400);
  ASSERT_TRUE(w->flush_if_due().ok());
  EXPECT_EQ(file_size(file.path()), after_header);  // 880 ms
  now += milliseconds(120);
  ASSERT_TRUE(w->flush_if_due().ok());  // 1000 ms: due
  EXPECT_EQ(w->bytes_buffered(), 0u);
  const uint64_t after_flush = file_size(file.path());
  EXPECT_GT(after_flush, after_header);
  EXPECT_EQ(after_flush, w->bytes_flushed());

  now += milliseconds(16);
  ASSERT_TRUE(w->append_tick(30, inputs_for(30, 3), 0, checksum_for(30)).ok());
  EXPECT_EQ(file_size(file.path()), after_flush);
  ASSERT_TRUE(w->append_keyframe(30, std::vector<uint8_t>(100, 7)).ok());
  EXPECT_GT(file_size(file.path()), after_flush + 100);  // keyframes flush
  EXPECT_EQ(w->bytes_buffered(), 0u);

  // Ticks appended after the interval go out with the append itself.
  now += milliseconds(1000);
  ASSERT_TRUE(w->append_tick(31, inputs_for(31, 3), 0, checksum_for(31)).ok());
  EXPECT_EQ(w->bytes_buffered(), 0u);
}

TEST(ReplayIo, UnfinishedWriterLeavesReadablePrefix) {
  TempFile file("unfinished");
  {
    Result<ReplayWriter> w = ReplayWriter::open(file.path(), test_header());
    ASSERT_TRUE(w.ok());
    for (Tick t = 0; t < 10; ++t) ASSERT_TRUE(w->append_tick(t, inputs_for(t, 3), 0, 7).ok());
    ReplayWriter moved = std::move(*w);  // moves keep one owner of the file
    ASSERT_TRUE(moved.append_tick(10, inputs_for(10, 3), 0, 7).ok());
  }
  Result<ReplayReader> reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(drain(*reader), "");
  EXPECT_EQ(reader->last_tick(), 10);
  EXPECT_FALSE(reader->ended());
}

TEST(ReplayIo, WriteErrorsBecomeStatus) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  ReplayWriterOptions options;
  options.overwrite = true;
  Result<ReplayWriter> w = ReplayWriter::open("/dev/full", test_header(), options);
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.status().code(), ErrorCode::kIo);
  EXPECT_NE(w.status().message().find("No space left"), std::string::npos) << w.status().message();
}

}  // namespace
}  // namespace rwd::replay
