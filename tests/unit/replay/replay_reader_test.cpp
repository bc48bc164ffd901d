// SPDX-License-Identifier: MIT
// The replay reader against every kind of broken file: truncations, bit
// flips, damaged lengths, hostile sizes, records out of order, noise.
#include "replay_io_support.h"

namespace rwd::replay {
namespace {

using namespace io_test;  // NOLINT: test helpers

TEST(ReplayIo, TruncationAtEveryByteIsCleanPrefixOrPreciseError) {
  TempFile file("truncate");
  const std::vector<uint64_t> starts = write_small_replay(file.path());
  const std::vector<uint8_t> bytes = read_all(file.path());
  // Records: 0 header, 1 t0, 2 t1, 3 kf1, 4 t2, 5 t3, 6 kf3, 7 t4, 8 end.
  const std::vector<Tick> last_tick_before = {kNoTick, kNoTick, 0, 1, 1, 2, 3, 3, 4};
  ASSERT_EQ(starts.size(), last_tick_before.size() + 1);

  for (size_t len = 0; len <= bytes.size(); ++len) {
    SCOPED_TRACE("length " + std::to_string(len));
    Result<ReplayReader> reader =
        ReplayReader::from_bytes(std::span<const uint8_t>(bytes.data(), len));
    if (len < kMagic.size()) {
      ASSERT_FALSE(reader.ok());
      EXPECT_NE(reader.status().message().find("bad magic"), std::string::npos);
      continue;
    }
    if (len < starts[1]) {
      ASSERT_FALSE(reader.ok());
      const std::string& msg = reader.status().message();
      if (len == kMagic.size()) {
        EXPECT_NE(msg.find("header missing at byte 8"), std::string::npos) << msg;
      } else {
        EXPECT_NE(msg.find("truncated frame at byte 8 (record 0, before the first tick)"),
                  std::string::npos)
            << msg;
      }
      continue;
    }
    ASSERT_TRUE(reader.ok()) << reader.status().message();
    const std::string err = drain(*reader);
    // The frame the cut falls into, or the boundary it falls on.
    size_t k = 1;
    while (starts[k + 1] <= len && k + 1 < starts.size() - 1) ++k;
    if (starts[k + 1] <= len) k = starts.size() - 1;
    const bool on_boundary = std::find(starts.begin(), starts.end(), len) != starts.end();
    if (on_boundary) {
      EXPECT_EQ(err, "");
      EXPECT_EQ(reader->offset(), len);
      EXPECT_EQ(reader->ended(), len == bytes.size());
      EXPECT_EQ(reader->state(),
                len == bytes.size() ? ReadState::kComplete : ReadState::kIncomplete);
    } else {
      const uint64_t at = starts[k];
      const uint64_t frame_bytes = starts[k + 1] - at;
      const uint64_t have = len - at;
      const std::string where =
          "truncated frame at byte " + std::to_string(at) + " (record " + std::to_string(k) + ", " +
          describe_last_tick(last_tick_before[k]) + "): need " +
          std::to_string(have < kFrameHeaderBytes ? kFrameHeaderBytes : frame_bytes) +
          " bytes, have " + std::to_string(have);
      EXPECT_EQ(err, where);
      EXPECT_EQ(reader->offset(), at);  // the valid prefix ends where the frame starts
      EXPECT_EQ(reader->error().code(), ErrorCode::kCorrupt);
      // A cut inside a frame is a write that did not finish, not damage.
      EXPECT_EQ(reader->state(), ReadState::kTorn);
      // The error sticks.
      EXPECT_FALSE(reader->next().ok());
    }
  }
}

TEST(ReplayIo, BitFlipInAnyPayloadIsAHashMismatchNamingTheRecord) {
  TempFile file("flip");
  const std::vector<uint64_t> starts = write_small_replay(file.path());
  const std::vector<uint8_t> bytes = read_all(file.path());
  for (size_t k = 0; k + 1 < starts.size(); ++k) {
    for (uint64_t pos = starts[k] + kFrameHeaderBytes; pos < starts[k + 1]; ++pos) {
      std::vector<uint8_t> copy = bytes;
      copy[pos] ^= static_cast<uint8_t>(1u << (pos % 8));
      const std::string prefix = "hash mismatch at byte " + std::to_string(starts[k]) +
                                 " (record " + std::to_string(k) + ", ";
      Result<ReplayReader> reader = ReplayReader::from_bytes(copy);
      if (k == 0) {
        ASSERT_FALSE(reader.ok());
        EXPECT_EQ(reader.status().message().rfind(prefix, 0), 0u) << reader.status().message();
        continue;
      }
      ASSERT_TRUE(reader.ok());
      const std::string err = drain(*reader);
      EXPECT_EQ(err.rfind(prefix, 0), 0u) << "flip at " << pos << ": " << err;
      EXPECT_EQ(reader->offset(), starts[k]);
      EXPECT_EQ(reader->state(), ReadState::kCorrupt);
    }
  }
  // A flipped bit in the stored hash is caught the same way.
  std::vector<uint8_t> copy = bytes;
  copy[starts[2] + 4] ^= 0x10;
  Result<ReplayReader> reader = ReplayReader::from_bytes(copy);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(
      drain(*reader).rfind(
          "hash mismatch at byte " + std::to_string(starts[2]) + " (record 2, after tick 0)", 0),
      0u);
}

TEST(ReplayIo, DamagedLengthFieldIsCorruptNeverTorn) {
  TempFile file("length_flip");
  const std::vector<uint64_t> starts = write_small_replay(file.path());
  const std::vector<uint8_t> bytes = read_all(file.path());
  size_t past_end = 0;
  for (size_t k = 0; k + 1 < starts.size(); ++k) {
    for (int bit = 0; bit < 32; ++bit) {
      SCOPED_TRACE("record " + std::to_string(k) + " length bit " + std::to_string(bit));
      std::vector<uint8_t> copy = bytes;
      copy[starts[k] + static_cast<size_t>(bit / 8)] ^= static_cast<uint8_t>(1u << (bit % 8));
      const uint32_t claimed = uint32_t{copy[starts[k]]} | uint32_t{copy[starts[k] + 1]} << 8 |
                               uint32_t{copy[starts[k] + 2]} << 16 |
                               uint32_t{copy[starts[k] + 3]} << 24;
      if (claimed <= kMaxRecordBytes && starts[k] + kFrameHeaderBytes + claimed > bytes.size()) {
        ++past_end;  // looks like a frame cut short by the end of the file
      }
      Result<ReplayReader> reader = ReplayReader::from_bytes(copy);
      if (k == 0) {
        ASSERT_FALSE(reader.ok());
        EXPECT_EQ(reader.status().message().find("truncated"), std::string::npos)
            << reader.status().message();
        continue;
      }
      ASSERT_TRUE(reader.ok());
      const std::string err = drain(*reader);
      EXPECT_FALSE(err.empty());
      EXPECT_EQ(reader->state(), ReadState::kCorrupt) << err;
      EXPECT_EQ(reader->offset(), starts[k]);
    }
  }
  // The hash-prefix check is what tells these apart from a torn tail.
  EXPECT_GT(past_end, 20u);

  // The message says what happened.
  std::vector<uint8_t> copy = bytes;
  const size_t last = starts.size() - 2;  // the end record
  copy[starts[last]] ^= 0x40;             // claims 64 more bytes than the file holds
  Result<ReplayReader> reader = ReplayReader::from_bytes(copy);
  ASSERT_TRUE(reader.ok());
  EXPECT_NE(drain(*reader).find("damaged length at byte " + std::to_string(starts[last])),
            std::string::npos);
}

TEST(ReplayIo, PrefixWithHashFindsTheShortestMatchingPrefix) {
  const std::vector<uint8_t> bytes = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  for (size_t n = 0; n <= bytes.size(); ++n) {
    EXPECT_EQ(prefix_with_hash(bytes, payload_hash({bytes.data(), n})), n);
  }
  EXPECT_EQ(prefix_with_hash(bytes, payload_hash(std::vector<uint8_t>{9, 9})), std::nullopt);
  // Long enough for the streaming hash's internal blocks.
  std::vector<uint8_t> long_bytes(5000);
  for (size_t i = 0; i < long_bytes.size(); ++i) long_bytes[i] = static_cast<uint8_t>(i * 7);
  for (size_t n : {size_t{239}, size_t{241}, size_t{1024}, size_t{4097}}) {
    EXPECT_EQ(prefix_with_hash(long_bytes, payload_hash({long_bytes.data(), n})), n);
  }
}

TEST(ReplayIo, HugeLengthIsRefusedBeforeAllocating) {
  TempFile file("huge");
  const std::vector<uint64_t> starts = write_small_replay(file.path());
  std::vector<uint8_t> bytes = read_all(file.path());
  const uint32_t huge = 4000000000u;
  for (int i = 0; i < 4; ++i) bytes[starts[2] + i] = static_cast<uint8_t>(huge >> (8 * i));
  Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(drain(*reader), "length 4000000000 exceeds limit 8388608 at byte " +
                                std::to_string(starts[2]) + " (record 2, after tick 0)");

  for (int i = 0; i < 4; ++i) {
    bytes[starts[2] + i] = static_cast<uint8_t>((kMaxRecordBytes + 1) >> (8 * i));
  }
  Result<ReplayReader> just_over = ReplayReader::from_bytes(bytes);
  ASSERT_TRUE(just_over.ok());
  EXPECT_NE(drain(*just_over).find("exceeds limit"), std::string::npos);
}

TEST(ReplayIo, ReaderRefusesFilesTheWriterWouldNotWrite) {
  const v1::ReplayHeader h = test_header();
  EXPECT_EQ(FileBuilder{}.open_error(),
            "header missing at byte 8 (record 0): the first record "
            "must be the replay header");
  EXPECT_NE(FileBuilder{}.tick(0).open_error().find("header missing"), std::string::npos);

  FileBuilder bad_magic;
  bad_magic.header(h);
  bad_magic.bytes[7] = '2';
  EXPECT_EQ(bad_magic.open_error(),
            "bad magic at byte 0: not a replay file (expected \"RWRPLY01\")");

  // A newer format opens (its header can be shown) but its records are
  // not read.
  v1::ReplayRecord future_record;
  *future_record.mutable_header() = h;
  future_record.mutable_header()->set_format_version(kFormatVersion + 1);
  const FileBuilder future = FileBuilder{}.add(future_record).tick(0);
  EXPECT_EQ(future.open_error(), "");
  EXPECT_EQ(future.read_error(),
            "records of replay format version 4 are not read by this build "
            "(it reads formats 1 to 3)");
  {
    Result<ReplayReader> reader = ReplayReader::from_bytes(future.bytes);
    ASSERT_TRUE(reader.ok());
    EXPECT_EQ(reader->header().format_version(), kFormatVersion + 1);
    EXPECT_EQ(reader->state(), ReadState::kReading);
    EXPECT_FALSE(reader->next().ok());
    EXPECT_EQ(reader->state(), ReadState::kUnsupported);
    EXPECT_EQ(reader->error().code(), ErrorCode::kUnsupported);
  }
  // ... unless its common fields are broken too.
  future_record.mutable_header()->set_player_count(0);
  EXPECT_NE(FileBuilder{}.add(future_record).open_error().find("player_count 0"),
            std::string::npos);

  v1::ReplayRecord no_version;
  *no_version.mutable_header() = h;
  no_version.mutable_header()->set_format_version(0);
  EXPECT_EQ(FileBuilder{}.add(no_version).open_error(),
            "bad header at byte 8 (record 0): replay header names no format version");

  // Format 2 must say who recorded it; format 1 never did.
  v1::ReplayRecord anonymous;
  *anonymous.mutable_header() = h;
  anonymous.mutable_header()->clear_engine();
  anonymous.mutable_header()->set_format_version(2);
  EXPECT_NE(FileBuilder{}.add(anonymous).open_error().find(
                "lacks the engine name, sim revision or world config"),
            std::string::npos);
  anonymous.mutable_header()->set_format_version(1);
  anonymous.mutable_header()->clear_sim_revision();
  anonymous.mutable_header()->clear_world_config();
  EXPECT_EQ(FileBuilder{}.add(anonymous).tick(0).read_error(), "");

  const size_t gap_at = FileBuilder{}.header(h).tick(0).tick(1).bytes.size();
  EXPECT_EQ(
      FileBuilder{}.header(h).tick(0).tick(1).tick(3).read_error(),
      "tick 3 follows tick 1 at byte " + std::to_string(gap_at) + " (record 3, after tick 1)");
  EXPECT_NE(FileBuilder{}.header(h).tick(5).read_error().find("first tick is 5, expected 0"),
            std::string::npos);
  EXPECT_NE(FileBuilder{}.header(h).tick(0, 2).read_error().find("2 inputs for 3 players"),
            std::string::npos);
  EXPECT_NE(FileBuilder{}.header(h).tick(0).header(h).read_error().find("second header"),
            std::string::npos);

  v1::ReplayRecord empty;  // a zero-length payload parses but names no record
  EXPECT_NE(FileBuilder{}.header(h).add(empty).read_error().find("record of unknown type"),
            std::string::npos);

  FileBuilder garbage;
  garbage.header(h);
  const std::vector<uint8_t> junk = {0xff, 0xff, 0xff, 0xff, 0x0f};
  const uint64_t hash = payload_hash(junk);
  const uint8_t head[12] = {5,
                            0,
                            0,
                            0,
                            uint8_t(hash),
                            uint8_t(hash >> 8),
                            uint8_t(hash >> 16),
                            uint8_t(hash >> 24),
                            uint8_t(hash >> 32),
                            uint8_t(hash >> 40),
                            uint8_t(hash >> 48),
                            uint8_t(hash >> 56)};
  garbage.bytes.insert(garbage.bytes.end(), head, head + 12);
  garbage.bytes.insert(garbage.bytes.end(), junk.begin(), junk.end());
  EXPECT_NE(garbage.read_error().find("unparsable record at byte"), std::string::npos);

  v1::ReplayRecord wide;
  wide.mutable_tick()->set_tick(0);
  for (int p = 0; p < 3; ++p) wide.mutable_tick()->add_inputs()->set_axis_x(40000);
  EXPECT_NE(FileBuilder{}.header(h).add(wide).read_error().find("does not fit 16 bits"),
            std::string::npos);

  v1::ReplayRecord big = wide;
  for (auto& in : *big.mutable_tick()->mutable_inputs()) {
    in.set_axis_x(0);
    in.set_data(std::string(rwd::kInputCapacity + 1, '\x01'));
  }
  EXPECT_NE(FileBuilder{}.header(h).add(big).read_error().find("more than 32"), std::string::npos);

  v1::ReplayRecord mask = wide;
  for (auto& in : *mask.mutable_tick()->mutable_inputs()) in.set_axis_x(0);
  mask.mutable_tick()->set_substituted_mask(1u << 3);
  EXPECT_NE(FileBuilder{}.header(h).add(mask).read_error().find("beyond player 2"),
            std::string::npos);

  v1::ReplayRecord keyframe;
  keyframe.mutable_keyframe()->set_tick(4);
  EXPECT_NE(FileBuilder{}.header(h).tick(0).add(keyframe).read_error().find("keyframe for tick 4"),
            std::string::npos);

  v1::ReplayRecord end;
  end.mutable_end()->set_last_final_tick(0);
  EXPECT_EQ(FileBuilder{}.header(h).tick(0).add(end).read_error(), "");
  EXPECT_NE(FileBuilder{}.header(h).tick(0).add(end).tick(1).read_error().find(
                "data after the end record"),
            std::string::npos);
  end.mutable_end()->set_last_final_tick(7);
  EXPECT_NE(FileBuilder{}.header(h).tick(0).add(end).read_error().find("last final tick 7"),
            std::string::npos);

  Result<ReplayReader> missing = ReplayReader::open("/nonexistent/dir/replay.rwr");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), ErrorCode::kIo);
}

TEST(ReplayIo, RandomBytesNeverCrash) {
  TempFile file("random");
  write_small_replay(file.path());
  const std::vector<uint8_t> valid = read_all(file.path());
  std::mt19937_64 rng(1234);
  int opened = 0;
  for (int round = 0; round < 3000; ++round) {
    std::vector<uint8_t> bytes;
    const int mode = round % 3;
    if (mode == 0) {  // pure noise
      bytes.resize(rng() % 200);
    } else if (mode == 1) {  // magic + noise
      bytes.assign(kMagic.begin(), kMagic.end());
      bytes.resize(kMagic.size() + rng() % 200);
    } else {  // a valid file with a few random bytes overwritten
      bytes = valid;
    }
    const size_t from = mode == 1 ? kMagic.size() : 0;
    if (mode == 2) {
      for (int i = 0; i < 3; ++i) bytes[rng() % bytes.size()] = static_cast<uint8_t>(rng());
    } else {
      for (size_t i = from; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(rng());
    }
    Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
    if (!reader.ok()) {
      EXPECT_FALSE(reader.status().message().empty());
      continue;
    }
    ++opened;
    const std::string err = drain(*reader);
    EXPECT_LE(reader->offset(), bytes.size());
    if (!err.empty()) {
      EXPECT_EQ(reader->error().code(), ErrorCode::kCorrupt);
    }
  }
  EXPECT_GT(opened, 0);  // the mutated-valid-file rounds do reach the record loop
}

}  // namespace
}  // namespace rwd::replay
