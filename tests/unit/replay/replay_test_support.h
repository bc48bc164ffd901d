// SPDX-License-Identifier: MIT
#pragma once
// Records real matches of a built-in game for the verifier and CLI tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "rewind/game/simulation.h"
#include "rewind/proto/input_wire.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_header.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_writer.h"

namespace rwd::replay::testing_support {

/// A fresh path under the test temp dir, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((std::filesystem::path(::testing::TempDir()) /
               (name + "_" + std::to_string(::getpid()) + ".rwr"))
                  .string()) {
    std::filesystem::remove(path_);
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct Recording {
  std::string game = "crates";
  uint32_t players = 4;
  uint64_t seed = 7;
  Tick ticks = 240;
  uint32_t input_seed = 7;          ///< seeds the random inputs, independent of the match seed
  uint32_t keyframe_interval = 60;  ///< keyframe after ticks interval-1, 2*interval-1, ...
  bool finish = true;
  /// Lets a test replace the state a keyframe records (forged keyframes).
  std::function<void(Tick, std::vector<uint8_t>&)> edit_keyframe;
  /// Lets a test change the header before it is written (a file that
  /// claims another engine, rules or world config).
  std::function<void(v1::ReplayHeader&)> edit_header;
};

/// Plays `rec` with seeded random inputs and records it the way the server
/// does: per tick the inputs and the checksum after stepping. Returns the
/// recorded checksums, index = tick.
inline std::vector<uint64_t> record_match(const std::string& path, const Recording& rec) {
  std::vector<uint64_t> checksums;
  game::MatchSetup setup;
  setup.player_count = rec.players;
  setup.seed = rec.seed;
  Result<std::unique_ptr<game::Simulation>> sim = game::Simulation::create(rec.game, setup);
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  if (!sim.ok()) return checksums;

  RecordingSetup recording;
  recording.match = setup;
  recording.tick_rate_hz = 60;
  recording.window_ticks = 8;
  recording.keyframe_interval = rec.keyframe_interval;
  recording.server_version = "replay tests";
  v1::ReplayHeader header = make_replay_header((*sim)->game(), recording);
  if (rec.edit_header) rec.edit_header(header);
  ReplayWriterOptions options;
  options.overwrite = true;
  Result<ReplayWriter> writer = ReplayWriter::open(path, header, options);
  EXPECT_TRUE(writer.ok()) << writer.status().message();
  if (!writer.ok()) return checksums;

  std::mt19937 rng(rec.input_seed);
  std::uniform_int_distribution<int> axis(-1000, 1000);
  std::uniform_int_distribution<int> press(0, 19);
  std::vector<rwd::StickInput> sticks(rec.players);
  std::vector<uint8_t> state;
  for (Tick t = 0; t < rec.ticks; ++t) {
    uint64_t substituted = 0;
    for (uint32_t p = 0; p < rec.players; ++p) {
      // Players hold the stick for a while, as people do, and sometimes
      // press buttons; player 0 drops out now and then (substituted input).
      if (t % 15 == 0) {
        sticks[p].axis_x = static_cast<int16_t>(axis(rng));
        sticks[p].axis_y = static_cast<int16_t>(axis(rng));
      }
      sticks[p].buttons = press(rng) == 0 ? (1u << (t % 2)) : 0u;
      if (p == 0 && t % 50 == 49) substituted |= 1u;
    }
    const std::vector<rwd::PlayerInput> inputs = rwd::stick_inputs(sticks);
    EXPECT_TRUE((*sim)->step(inputs).ok());
    checksums.push_back((*sim)->checksum());
    EXPECT_TRUE(writer->append_tick(t, inputs, substituted, checksums.back()).ok());
    if (rec.keyframe_interval > 0 && (t + 1) % static_cast<Tick>(rec.keyframe_interval) == 0) {
      (*sim)->serialize(state);
      if (rec.edit_keyframe) rec.edit_keyframe(t, state);
      EXPECT_TRUE(writer->append_keyframe(t, state).ok());
    }
  }
  if (rec.finish) {
    EXPECT_TRUE(writer->finish(rec.ticks - 1, "match over").ok());
  }
  return checksums;
}

/// Truncates `path` `into` bytes into the first frame that starts past
/// `fraction` of the file, so the cut never falls on a frame boundary: the
/// default 5 tears the 12-byte frame header, kFrameHeaderBytes + n the
/// payload.
inline void cut_inside_frame(const std::string& path, double fraction, uint64_t into = 5) {
  const uint64_t size = std::filesystem::file_size(path);
  uint64_t cut = 0;
  {
    Result<ReplayReader> reader = ReplayReader::open(path);
    ASSERT_TRUE(reader.ok());
    while (reader->offset() < static_cast<uint64_t>(static_cast<double>(size) * fraction)) {
      Result<std::optional<v1::ReplayRecord>> r = reader->next();
      ASSERT_TRUE(r.ok() && r->has_value());
    }
    cut = reader->offset() + into;
  }
  ASSERT_LT(cut, size);
  std::filesystem::resize_file(path, cut);
}

/// Truncates `path` at the end of the frame that holds tick `tick`'s record:
/// a recording that stops on a frame boundary without its end record.
inline void cut_after_tick(const std::string& path, Tick tick) {
  uint64_t cut = 0;
  {
    Result<ReplayReader> reader = ReplayReader::open(path);
    ASSERT_TRUE(reader.ok());
    while (true) {
      Result<std::optional<v1::ReplayRecord>> r = reader->next();
      ASSERT_TRUE(r.ok() && r->has_value()) << "tick " << tick << " not recorded";
      if ((*r)->has_tick() && (*r)->tick().tick() == tick) break;
    }
    cut = reader->offset();
  }
  std::filesystem::resize_file(path, cut);
}

/// Copies `in` to `out` frame by frame with `edit` applied to the header
/// and every frame re-hashed: a file that says what the edit says, whatever
/// the writer would allow.
inline void rewrite_header(const std::string& in, const std::string& out,
                           const std::function<void(v1::ReplayHeader&)>& edit) {
  Result<ReplayReader> reader = ReplayReader::open(in);
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  std::vector<uint8_t> bytes(kMagic.begin(), kMagic.end());
  v1::ReplayRecord header;
  *header.mutable_header() = reader->header();
  edit(*header.mutable_header());
  ASSERT_TRUE(append_frame(header, bytes).ok());
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader->next();
    ASSERT_TRUE(r.ok()) << r.status().message();
    if (!r->has_value()) break;
    ASSERT_TRUE(append_frame(**r, bytes).ok());
  }
  std::FILE* f = std::fopen(out.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
  std::fclose(f);
}

}  // namespace rwd::replay::testing_support
