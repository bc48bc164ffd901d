// SPDX-License-Identifier: MIT
#pragma once
// Records real matches of a built-in game for the verifier and CLI tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "rewind/game/simulation.h"
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

  v1::ReplayHeader header;
  header.set_game(rec.game);
  header.set_player_count(rec.players);
  header.set_seed(rec.seed);
  header.set_tick_rate_hz(60);
  header.set_window_ticks(8);
  header.set_keyframe_interval(rec.keyframe_interval);
  ReplayWriterOptions options;
  options.overwrite = true;
  Result<ReplayWriter> writer = ReplayWriter::open(path, header, options);
  EXPECT_TRUE(writer.ok()) << writer.status().message();
  if (!writer.ok()) return checksums;

  std::mt19937 rng(rec.input_seed);
  std::uniform_int_distribution<int> axis(-1000, 1000);
  std::uniform_int_distribution<int> press(0, 19);
  std::vector<game::PlayerInput> inputs(rec.players);
  std::vector<uint8_t> state;
  for (Tick t = 0; t < rec.ticks; ++t) {
    uint64_t substituted = 0;
    for (uint32_t p = 0; p < rec.players; ++p) {
      // Players hold the stick for a while, as people do, and sometimes
      // press buttons; player 0 drops out now and then (substituted input).
      if (t % 15 == 0) {
        inputs[p].axis_x = static_cast<int16_t>(axis(rng));
        inputs[p].axis_y = static_cast<int16_t>(axis(rng));
      }
      inputs[p].buttons = press(rng) == 0 ? (1u << (t % 2)) : 0u;
      if (p == 0 && t % 50 == 49) substituted |= 1u;
    }
    (*sim)->step(inputs);
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

/// Truncates `path` a few bytes into the first frame that starts past
/// `fraction` of the file, so the cut never falls on a frame boundary.
inline void cut_inside_frame(const std::string& path, double fraction) {
  const uint64_t size = std::filesystem::file_size(path);
  uint64_t cut = 0;
  {
    Result<ReplayReader> reader = ReplayReader::open(path);
    ASSERT_TRUE(reader.ok());
    while (reader->offset() < static_cast<uint64_t>(static_cast<double>(size) * fraction)) {
      Result<std::optional<v1::ReplayRecord>> r = reader->next();
      ASSERT_TRUE(r.ok() && r->has_value());
    }
    cut = reader->offset() + 5;
  }
  ASSERT_LT(cut, size);
  std::filesystem::resize_file(path, cut);
}

}  // namespace rwd::replay::testing_support
