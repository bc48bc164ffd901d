// SPDX-License-Identifier: MIT
// The replay file format without the simulation: writer, reader, summary and
// rewrite against every kind of broken file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "rewind/proto/input_wire.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_summary.h"
#include "rewind/replay/replay_writer.h"

namespace rwd::replay {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using TimePoint = std::chrono::steady_clock::time_point;

v1::ReplayHeader test_header(uint32_t players = 3) {
  v1::ReplayHeader h;
  h.set_game("crates");
  h.set_player_count(players);
  h.set_seed(42);
  h.set_tick_rate_hz(60);
  h.set_window_ticks(8);
  h.set_server_version("test");
  h.set_keyframe_interval(4);
  // The identity make_replay_header() records. This test links no engine,
  // so opaque bytes stand in for an encoded world config.
  h.set_engine("rewind-sim");
  h.set_sim_revision(2);
  h.set_rules_version(2);
  h.set_world_config(std::string(61, '\x01'));
  return h;
}

std::vector<game::PlayerInput> inputs_for(Tick tick, uint32_t players) {
  std::vector<game::PlayerInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    inputs[p].axis_x = static_cast<int16_t>(tick * 10 - static_cast<int>(p));
    inputs[p].axis_y = static_cast<int16_t>(-tick);
    inputs[p].buttons = static_cast<uint32_t>(tick) ^ p;
  }
  return inputs;
}

uint64_t checksum_for(Tick tick) {
  return 0x9E3779B97F4A7C15ull * static_cast<uint64_t>(tick + 1);
}

// A fresh path under the test temp dir, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((fs::path(testing::TempDir()) / (name + "_" + std::to_string(::getpid()) + ".rwr"))
                  .string()) {
    fs::remove(path_);
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::vector<uint8_t> read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_all(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

uint64_t file_size(const std::string& path) {
  return fs::file_size(path);
}

// Writes header, ticks 0..ticks-1 with keyframes after ticks 1 and 3, and an
// end record. Returns the frame start offsets (record i starts at [i]) and the
// file end as the last element.
std::vector<uint64_t> write_small_replay(const std::string& path, Tick ticks = 5) {
  Result<ReplayWriter> w = ReplayWriter::open(path, test_header());
  EXPECT_TRUE(w.ok()) << w.status().message();
  for (Tick t = 0; t < ticks; ++t) {
    EXPECT_TRUE(w->append_tick(t, inputs_for(t, 3), t == 2 ? 0b101u : 0u, checksum_for(t)).ok());
    if (t == 1 || t == 3) {
      const std::vector<uint8_t> state(17, static_cast<uint8_t>(t));
      EXPECT_TRUE(w->append_keyframe(t, state).ok());
    }
  }
  EXPECT_TRUE(w->finish(ticks - 1, "match over").ok());

  // Recover frame boundaries by walking the lengths.
  const std::vector<uint8_t> bytes = read_all(path);
  std::vector<uint64_t> starts;
  uint64_t at = kMagic.size();
  while (at < bytes.size()) {
    starts.push_back(at);
    const uint32_t len = uint32_t{bytes[at]} | uint32_t{bytes[at + 1]} << 8 |
                         uint32_t{bytes[at + 2]} << 16 | uint32_t{bytes[at + 3]} << 24;
    at += kFrameHeaderBytes + len;
  }
  EXPECT_EQ(at, bytes.size());
  starts.push_back(at);
  return starts;
}

// Reads every record after the header; returns the error message or "".
std::string drain(ReplayReader& reader, std::vector<v1::ReplayRecord>* records = nullptr) {
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader.next();
    if (!r.ok()) return r.status().message();
    if (!r->has_value()) return "";
    if (records != nullptr) records->push_back(**r);
  }
}

// Builds files record by record, bypassing the writer's checks.
struct FileBuilder {
  std::vector<uint8_t> bytes{kMagic.begin(), kMagic.end()};
  FileBuilder& header(const v1::ReplayHeader& h) {
    v1::ReplayRecord r;
    *r.mutable_header() = h;
    r.mutable_header()->set_format_version(kFormatVersion);
    return add(r);
  }
  FileBuilder& tick(Tick t, uint32_t players = 3) {
    v1::ReplayRecord r;
    r.mutable_tick()->set_tick(t);
    for (const game::PlayerInput& in : inputs_for(t, players)) {
      *r.mutable_tick()->add_inputs() = proto::to_wire(in);
    }
    return add(r);
  }
  FileBuilder& add(const v1::ReplayRecord& r) {
    EXPECT_TRUE(append_frame(r, bytes).ok());
    return *this;
  }
  std::string open_error() const {
    Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
    return reader.ok() ? "" : reader.status().message();
  }
  std::string read_error() const {
    Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
    if (!reader.ok()) return "open: " + reader.status().message();
    return drain(*reader);
  }
};

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
      const std::vector<game::PlayerInput> want = inputs_for(expected_tick, 3);
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
            "records of replay format version 3 are not read by this build "
            "(it reads formats 1 to 2)");
  {
    Result<ReplayReader> reader = ReplayReader::from_bytes(future.bytes);
    ASSERT_TRUE(reader.ok());
    EXPECT_EQ(reader->header().format_version(), 3u);
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

TEST(ReplayIo, SummaryCountsRecordsAndSubstitutions) {
  TempFile file("summary");
  write_small_replay(file.path(), 6);
  Result<ReplaySummary> s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->header.game(), "crates");
  EXPECT_EQ(s->tick_records, 6u);
  EXPECT_EQ(s->first_tick, 0);
  EXPECT_EQ(s->last_tick, 5);
  EXPECT_EQ(s->substituted_per_player, (std::vector<uint64_t>{1, 0, 1}));
  EXPECT_EQ(s->ticks_with_substitutions, 1u);
  ASSERT_EQ(s->keyframes.size(), 2u);
  EXPECT_EQ(s->keyframes[1].tick, 3);
  EXPECT_EQ(s->keyframes[1].state_bytes, 17u);
  ASSERT_TRUE(s->end.has_value());
  EXPECT_EQ(s->end->reason(), "match over");
  EXPECT_FALSE(s->error.has_value());
  EXPECT_EQ(s->state, ReadState::kComplete);
  EXPECT_EQ(s->valid_bytes, file_size(file.path()));
  EXPECT_EQ(s->header.sim_revision(), 2u);

  std::vector<uint8_t> bytes = read_all(file.path());
  bytes.resize(bytes.size() - 3);
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(s->error.has_value());
  EXPECT_NE(s->error->find("truncated frame"), std::string::npos);
  EXPECT_EQ(s->state, ReadState::kTorn);
  EXPECT_FALSE(s->end.has_value());
  EXPECT_EQ(s->last_tick, 5);

  // Cut on the boundary before the end record: no error, but incomplete.
  fs::remove(file.path());
  const std::vector<uint64_t> starts = write_small_replay(file.path(), 6);
  bytes = read_all(file.path());
  bytes.resize(starts[starts.size() - 2]);
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s->error.has_value());
  EXPECT_EQ(s->state, ReadState::kIncomplete);
  EXPECT_EQ(s->last_tick, 5);

  // A flipped bit inside a frame is corruption.
  bytes[starts[3] + kFrameHeaderBytes + 1] ^= 0x04;
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->state, ReadState::kCorrupt);
}

TEST(ReplayIo, RewriteForgesOneInputWithValidFraming) {
  TempFile in("rewrite_in");
  TempFile out("rewrite_out");
  write_small_replay(in.path(), 6);
  InputEdit edit;
  edit.tick = 3;
  edit.player = 1;
  edit.axis_x = -999;
  Result<game::PlayerInput> original = rewrite_replay_input(in.path(), out.path(), edit, false);
  ASSERT_TRUE(original.ok()) << original.status().message();
  EXPECT_EQ(*original, inputs_for(3, 3)[1]);

  Result<ReplayReader> a = ReplayReader::open(in.path());
  Result<ReplayReader> b = ReplayReader::open(out.path());
  ASSERT_TRUE(a.ok() && b.ok());
  std::vector<v1::ReplayRecord> ra;
  std::vector<v1::ReplayRecord> rb;
  ASSERT_EQ(drain(*a, &ra), "");
  ASSERT_EQ(drain(*b, &rb), "");  // every frame hash is valid
  ASSERT_EQ(ra.size(), rb.size());
  int changed = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    if (ra[i].SerializeAsString() == rb[i].SerializeAsString()) continue;
    ++changed;
    ASSERT_TRUE(rb[i].has_tick());
    EXPECT_EQ(rb[i].tick().tick(), 3);
    EXPECT_EQ(rb[i].tick().inputs(1).axis_x(), -999);
    EXPECT_EQ(rb[i].tick().inputs(1).axis_y(), ra[i].tick().inputs(1).axis_y());
    EXPECT_EQ(rb[i].tick().checksum(), ra[i].tick().checksum());
  }
  EXPECT_EQ(changed, 1);
  EXPECT_TRUE(b->ended());

  // Refusals: existing output, missing tick, missing player.
  EXPECT_FALSE(rewrite_replay_input(in.path(), out.path(), edit, false).ok());
  EXPECT_TRUE(rewrite_replay_input(in.path(), out.path(), edit, true).ok());
  edit.tick = 60;
  EXPECT_EQ(rewrite_replay_input(in.path(), out.path(), edit, true).status().code(),
            ErrorCode::kNotFound);
  EXPECT_FALSE(fs::exists(out.path()));  // no half-forged file left behind
  edit.tick = 1;
  edit.player = 3;
  EXPECT_EQ(rewrite_replay_input(in.path(), out.path(), edit, true).status().code(),
            ErrorCode::kInvalidArgument);
  edit.player = 0;
  EXPECT_FALSE(rewrite_replay_input(in.path(), in.path(), edit, true).ok());
  EXPECT_TRUE(ReplayReader::open(in.path()).ok());  // input untouched
}

}  // namespace
}  // namespace rwd::replay
