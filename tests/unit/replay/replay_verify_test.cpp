// SPDX-License-Identifier: MIT
// The verifier against real recordings of the crates game: clean runs verify,
// forged inputs and keyframes diverge at exactly their tick with named
// fields, broken files verify their prefix and say where they break.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "replay_test_support.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_verifier.h"

namespace rwd::replay {
namespace {

using testing_support::record_match;
using testing_support::Recording;
using testing_support::TempFile;

// Rewrites player `player`'s axis_x at `tick` to the far opposite value.
void forge_input(const std::string& in, const std::string& out, Tick tick, uint32_t player) {
  Result<ReplayReader> reader = ReplayReader::open(in);
  ASSERT_TRUE(reader.ok());
  int16_t old_x = 0;
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader->next();
    ASSERT_TRUE(r.ok());
    ASSERT_TRUE(r->has_value()) << "tick " << tick << " not recorded";
    if ((*r)->has_tick() && (*r)->tick().tick() == tick) {
      old_x = static_cast<int16_t>((*r)->tick().inputs(static_cast<int>(player)).axis_x());
      break;
    }
  }
  InputEdit edit;
  edit.tick = tick;
  edit.player = player;
  edit.axis_x = static_cast<int16_t>(old_x > 0 ? -1000 : 1000);
  Result<game::PlayerInput> original = rewrite_replay_input(in, out, edit, true);
  ASSERT_TRUE(original.ok()) << original.status().message();
}

bool names_a_moving_field(const VerifyReport& report) {
  for (const sim::FieldDifference& d : report.differences) {
    if (d.field.find("position") != std::string::npos ||
        d.field.find("velocity") != std::string::npos) {
      return true;
    }
  }
  return false;
}

TEST(ReplayVerify, RecordedCratesRunVerifies) {
  TempFile file("verify_ok");
  Recording rec;
  const std::vector<uint64_t> checksums = record_match(file.path(), rec);
  ASSERT_EQ(checksums.size(), 240u);

  const VerifyReport report = verify_replay(file.path());
  EXPECT_TRUE(report.ok()) << report.framing_error.value_or("") << report.error.value_or("");
  EXPECT_EQ(report.ticks_verified, 240u);
  EXPECT_EQ(report.last_checksum, checksums.back());
  EXPECT_EQ(report.keyframes_verified, 4u);
  EXPECT_TRUE(report.ended_cleanly);
  ASSERT_TRUE(report.header.has_value());
  EXPECT_EQ(report.header->game(), "crates");
  EXPECT_EQ(report.header->player_count(), 4u);
}

TEST(ReplayVerify, ForgedInputDivergesAtThatTickAndNamesFieldsAtTheNextKeyframe) {
  TempFile file("verify_forge_src");
  TempFile forged("verify_forge");
  const std::vector<uint64_t> checksums = record_match(file.path(), Recording{});
  forge_input(file.path(), forged.path(), 100, 1);

  const VerifyReport report = verify_replay(forged.path());
  ASSERT_TRUE(report.diverged());
  EXPECT_EQ(*report.first_divergent_tick, 100);
  EXPECT_EQ(report.divergence_kind, DivergenceKind::kTickChecksum);
  EXPECT_EQ(report.ticks_verified, 100u);
  EXPECT_EQ(report.expected_checksum, checksums[100]);
  EXPECT_NE(report.actual_checksum, report.expected_checksum);
  ASSERT_TRUE(report.differences_tick.has_value());
  EXPECT_EQ(*report.differences_tick, 119);  // keyframes follow ticks 59, 119, ...
  ASSERT_FALSE(report.differences.empty()) << report.differences_note;
  EXPECT_TRUE(names_a_moving_field(report));
  EXPECT_EQ(report.differences_total, report.differences.size());
  EXPECT_FALSE(report.framing_error.has_value());
  EXPECT_TRUE(report.ended_cleanly);  // the rest of the file is still read

  // Cut the forged file after its next keyframe: the divergence and the
  // break are both reported.
  testing_support::cut_inside_frame(forged.path(), 0.9);
  const VerifyReport cut = verify_replay(forged.path());
  ASSERT_TRUE(cut.diverged());
  EXPECT_EQ(*cut.first_divergent_tick, 100);
  EXPECT_EQ(cut.differences_tick, report.differences_tick);
  ASSERT_TRUE(cut.framing_error.has_value());
  EXPECT_NE(cut.framing_error->find("truncated frame at byte"), std::string::npos);
  EXPECT_FALSE(cut.ended_cleanly);
}

TEST(ReplayVerify, ForgedInputOnAKeyframeTickIsComparedRightThere) {
  TempFile file("verify_forge_kf_src");
  TempFile forged("verify_forge_kf");
  record_match(file.path(), Recording{});
  forge_input(file.path(), forged.path(), 59, 2);

  const VerifyReport report = verify_replay(forged.path());
  ASSERT_TRUE(report.diverged());
  EXPECT_EQ(*report.first_divergent_tick, 59);
  ASSERT_TRUE(report.differences_tick.has_value());
  EXPECT_EQ(*report.differences_tick, 59);
  EXPECT_TRUE(names_a_moving_field(report));
}

TEST(ReplayVerify, WithoutKeyframesTheTickIsNamedAndTheReportSaysWhyNoFields) {
  TempFile file("verify_nokf_src");
  TempFile forged("verify_nokf");
  Recording rec;
  rec.keyframe_interval = 0;
  record_match(file.path(), rec);
  forge_input(file.path(), forged.path(), 30, 0);

  const VerifyReport report = verify_replay(forged.path());
  ASSERT_TRUE(report.diverged());
  EXPECT_EQ(*report.first_divergent_tick, 30);
  EXPECT_FALSE(report.differences_tick.has_value());
  EXPECT_TRUE(report.differences.empty());
  EXPECT_NE(report.differences_note.find("no keyframe at or after tick 30"), std::string::npos)
      << report.differences_note;
  EXPECT_TRUE(report.ended_cleanly);
}

TEST(ReplayVerify, KeyframeHoldingAnotherTickIsRefused) {
  TempFile file("verify_keyframe_wrong_tick");
  Recording rec;
  // The keyframe recorded after tick 119 holds the state after tick 120.
  rec.edit_keyframe = [&rec](Tick tick, std::vector<uint8_t>& state) {
    if (tick != 119) return;
    auto later = game::Simulation::create(rec.game, game::MatchSetup{rec.players, rec.seed});
    ASSERT_TRUE(later.ok());
    ASSERT_TRUE((*later)->deserialize(state).ok());
    (*later)->step(std::vector<game::PlayerInput>(rec.players));
    (*later)->serialize(state);
  };
  record_match(file.path(), rec);

  const VerifyReport report = verify_replay(file.path());
  ASSERT_TRUE(report.error.has_value());
  EXPECT_NE(report.error->find("keyframe for tick 119"), std::string::npos) << *report.error;
  EXPECT_NE(report.error->find("expected before tick 120"), std::string::npos) << *report.error;
  EXPECT_EQ(report.ticks_verified, 120u);
  EXPECT_EQ(report.keyframes_verified, 1u);
}

TEST(ReplayVerify, KeyframeFromADifferentMatchDivergesOnState) {
  TempFile file("verify_foreign_keyframe");
  TempFile other_file("verify_foreign_src");
  // Record the same match with other inputs to get a foreign state for the
  // same tick, then plant it as the keyframe after tick 59.
  Recording foreign;
  foreign.input_seed = 99;
  foreign.ticks = 60;
  foreign.keyframe_interval = 60;
  std::vector<uint8_t> foreign_state;
  foreign.edit_keyframe = [&foreign_state](Tick, std::vector<uint8_t>& state) {
    foreign_state = state;
  };
  record_match(other_file.path(), foreign);
  ASSERT_FALSE(foreign_state.empty());

  Recording rec;
  rec.edit_keyframe = [&foreign_state](Tick tick, std::vector<uint8_t>& state) {
    if (tick == 59) state = foreign_state;
  };
  record_match(file.path(), rec);

  const VerifyReport report = verify_replay(file.path());
  ASSERT_TRUE(report.diverged()) << report.error.value_or("");
  EXPECT_EQ(*report.first_divergent_tick, 59);
  EXPECT_EQ(report.divergence_kind, DivergenceKind::kKeyframeState);
  EXPECT_EQ(report.ticks_verified, 60u);  // every tick checksum before it matched
  ASSERT_TRUE(report.differences_tick.has_value());
  EXPECT_EQ(*report.differences_tick, 59);
  EXPECT_TRUE(names_a_moving_field(report));
}

TEST(ReplayVerify, GarbageKeyframeBytesAreReportedNotTrusted) {
  TempFile file("verify_garbage_keyframe");
  Recording rec;
  rec.edit_keyframe = [](Tick tick, std::vector<uint8_t>& state) {
    if (tick == 119) state.assign(64, 0xAB);
  };
  record_match(file.path(), rec);
  const VerifyReport report = verify_replay(file.path());
  EXPECT_FALSE(report.diverged());
  ASSERT_TRUE(report.error.has_value());
  EXPECT_NE(report.error->find("does not load"), std::string::npos) << *report.error;
  EXPECT_EQ(report.ticks_verified, 120u);
}

TEST(ReplayVerify, TruncatedFileVerifiesItsPrefixAndSaysWhereItBreaks) {
  TempFile file("verify_truncated");
  record_match(file.path(), Recording{});
  testing_support::cut_inside_frame(file.path(), 2.0 / 3.0);

  Result<ReplayReader> reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  uint64_t complete_ticks = 0;
  std::string error;
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader->next();
    if (!r.ok()) {
      error = r.status().message();
      break;
    }
    if (!r->has_value()) break;
    if ((*r)->has_tick()) ++complete_ticks;
  }
  ASSERT_FALSE(error.empty());

  const VerifyReport report = verify_replay(file.path());
  EXPECT_FALSE(report.diverged());
  EXPECT_EQ(report.ticks_verified, complete_ticks);
  EXPECT_GT(report.ticks_verified, 100u);
  ASSERT_TRUE(report.framing_error.has_value());
  EXPECT_EQ(*report.framing_error, error);
  EXPECT_NE(report.framing_error->find("truncated frame at byte"), std::string::npos);
  EXPECT_FALSE(report.ended_cleanly);
}

TEST(ReplayVerify, UnfinishedRecordingVerifiesWithoutEnd) {
  TempFile file("verify_unfinished");
  Recording rec;
  rec.finish = false;
  rec.ticks = 90;
  record_match(file.path(), rec);
  const VerifyReport report = verify_replay(file.path());
  EXPECT_TRUE(report.ok());
  EXPECT_EQ(report.ticks_verified, 90u);
  EXPECT_FALSE(report.ended_cleanly);
}

TEST(ReplayVerify, UnknownGameAndMissingFileAreErrors) {
  TempFile file("verify_unknown_game");
  v1::ReplayHeader header;
  header.set_game("no-such-game");
  header.set_player_count(2);
  ASSERT_TRUE(ReplayWriter::open(file.path(), header).ok());
  VerifyReport report = verify_replay(file.path());
  ASSERT_TRUE(report.error.has_value());
  EXPECT_NE(report.error->find("no-such-game"), std::string::npos);
  EXPECT_FALSE(report.ok());

  report = verify_replay("/nonexistent/replay.rwr");
  EXPECT_TRUE(report.error.has_value());
  EXPECT_FALSE(report.header.has_value());
}

}  // namespace
}  // namespace rwd::replay
