// SPDX-License-Identifier: MIT
// The verifier against real recordings of the crates game: clean runs verify,
// forged inputs and keyframes diverge at exactly their tick with named
// fields, broken files verify their prefix and say where they break.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "replay_test_support.h"
#include "rewind/game/crates_game.h"
#include "rewind/replay/engine_identity.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_verifier.h"
#include "rewind/sim/version.h"
#include "rewind/sim/world3d.h"

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
      old_x = proto::from_wire((*r)->tick().inputs(static_cast<int>(player)))
                  ->as<rwd::StickInput>()
                  .axis_x;
      break;
    }
  }
  InputEdit edit;
  edit.tick = tick;
  edit.player = player;
  edit.fields = {{"axis_x", old_x > 0 ? -1000 : 1000}};
  Result<InputRewrite> original =
      rewrite_replay_input(in, out, edit, rwd::stick_input_spec(), true);
  ASSERT_TRUE(original.ok()) << original.status().message();
}

// "rewind-sim r2 (crates rules 2)" for whatever this build's revisions are.
std::string this_build_label() {
  return std::string(sim::kEngineName) + " r" + std::to_string(sim::kSimRevision) +
         " (crates rules " + std::to_string(game::CratesGame().rules_version()) + ")";
}

// The header a build one sim revision and one rules version older wrote.
void older_engine(v1::ReplayHeader& header) {
  header.set_sim_revision(sim::kSimRevision - 1);
  header.set_rules_version(game::CratesGame().rules_version() - 1);
}

bool names_a_moving_field(const VerifyReport& report) {
  for (const rwd::FieldDifference& d : report.differences) {
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
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVerified);
  EXPECT_EQ(report.ticks_verified, 240u);
  EXPECT_EQ(report.tick_records, 240u);
  EXPECT_EQ(report.last_checksum, checksums.back());
  EXPECT_EQ(report.keyframes_verified, 4u);
  EXPECT_TRUE(report.ended_cleanly);
  EXPECT_EQ(report.file_state, ReadState::kComplete);
  EXPECT_TRUE(report.resimulated);
  ASSERT_TRUE(report.header.has_value());
  EXPECT_EQ(report.header->game(), "crates");
  EXPECT_EQ(report.header->player_count(), 4u);
  // The header says who recorded it, and that is this build.
  EXPECT_EQ(report.header->format_version(), kFormatVersion);
  EXPECT_EQ(report.header->engine(), sim::kEngineName);
  EXPECT_EQ(report.header->sim_revision(), sim::kSimRevision);
  EXPECT_EQ(report.header->rules_version(), game::CratesGame().rules_version());
  ASSERT_TRUE(report.versions.has_value());
  EXPECT_TRUE(report.versions->matches());
  EXPECT_EQ(report.versions->recorded.label(), this_build_label());
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
  EXPECT_EQ(cut.outcome(), VerifyOutcome::kDiverged);
  EXPECT_EQ(*cut.first_divergent_tick, 100);
  EXPECT_EQ(cut.differences_tick, report.differences_tick);
  ASSERT_TRUE(cut.torn_frame.has_value());
  EXPECT_NE(cut.torn_frame->find("truncated frame at byte"), std::string::npos);
  EXPECT_FALSE(cut.framing_error.has_value());
  EXPECT_EQ(cut.file_state, ReadState::kTorn);
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
    ASSERT_TRUE((*later)->step(std::vector<rwd::PlayerInput>(rec.players)).ok());
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

// Counts the tick records before the reader stops, and its message.
uint64_t complete_ticks_in(const std::string& path, std::string* error) {
  Result<ReplayReader> reader = ReplayReader::open(path);
  EXPECT_TRUE(reader.ok());
  if (!reader.ok()) return 0;
  uint64_t ticks = 0;
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader->next();
    if (!r.ok()) {
      *error = r.status().message();
      break;
    }
    if (!r->has_value()) break;
    if ((*r)->has_tick()) ++ticks;
  }
  return ticks;
}

TEST(ReplayVerify, TornLastFrameVerifiesThePrefixAndIsIncomplete) {
  // Cut inside a frame header and inside a payload: both are writes that
  // did not finish.
  for (const uint64_t into : {uint64_t{5}, uint64_t{kFrameHeaderBytes + 3}}) {
    SCOPED_TRACE("cut " + std::to_string(into) + " bytes into the frame");
    TempFile file("verify_torn");
    const std::vector<uint64_t> checksums = record_match(file.path(), Recording{});
    testing_support::cut_inside_frame(file.path(), 2.0 / 3.0, into);
    std::string error;
    const uint64_t complete_ticks = complete_ticks_in(file.path(), &error);
    ASSERT_FALSE(error.empty());

    const VerifyReport report = verify_replay(file.path());
    EXPECT_EQ(report.outcome(), VerifyOutcome::kIncomplete);
    EXPECT_FALSE(report.ok());
    EXPECT_FALSE(report.diverged());
    EXPECT_EQ(report.ticks_verified, complete_ticks);
    EXPECT_EQ(report.tick_records, complete_ticks);
    EXPECT_GT(report.ticks_verified, 100u);
    EXPECT_EQ(report.last_checksum, checksums[complete_ticks - 1]);
    ASSERT_TRUE(report.torn_frame.has_value());
    EXPECT_EQ(*report.torn_frame, error);
    EXPECT_NE(report.torn_frame->find("truncated frame at byte"), std::string::npos);
    EXPECT_FALSE(report.framing_error.has_value());
    EXPECT_FALSE(report.error.has_value());
    EXPECT_EQ(report.file_state, ReadState::kTorn);
    EXPECT_FALSE(report.ended_cleanly);
  }
}

TEST(ReplayVerify, RecordingCutOnAFrameBoundaryVerifiesThePrefixAndIsIncomplete) {
  TempFile file("verify_cut_boundary");
  const std::vector<uint64_t> checksums = record_match(file.path(), Recording{});
  testing_support::cut_after_tick(file.path(), 150);
  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kIncomplete);
  EXPECT_EQ(report.ticks_verified, 151u);
  EXPECT_EQ(report.last_checksum, checksums[150]);
  EXPECT_EQ(report.keyframes_verified, 2u);
  EXPECT_EQ(report.file_state, ReadState::kIncomplete);
  EXPECT_FALSE(report.torn_frame.has_value());
  EXPECT_FALSE(report.framing_error.has_value());

  // The same from a writer that was never finished.
  TempFile unfinished("verify_unfinished");
  Recording rec;
  rec.finish = false;
  rec.ticks = 90;
  record_match(unfinished.path(), rec);
  const VerifyReport open_ended = verify_replay(unfinished.path());
  EXPECT_EQ(open_ended.outcome(), VerifyOutcome::kIncomplete);
  EXPECT_EQ(open_ended.ticks_verified, 90u);
  EXPECT_FALSE(open_ended.ended_cleanly);
}

TEST(ReplayVerify, BitFlipInsideAFrameIsCorruptAfterThePrefixVerified) {
  TempFile file("verify_flip");
  record_match(file.path(), Recording{});
  // Flip one payload bit in the frame that follows tick 100's record.
  uint64_t frame = 0;
  {
    Result<ReplayReader> reader = ReplayReader::open(file.path());
    ASSERT_TRUE(reader.ok());
    while (reader->last_tick() != 100) ASSERT_TRUE(reader->next().ok());
    frame = reader->offset();
  }
  std::fstream f(file.path(), std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(frame + kFrameHeaderBytes + 2));
  char byte = 0;
  f.get(byte);
  f.seekp(static_cast<std::streamoff>(frame + kFrameHeaderBytes + 2));
  f.put(static_cast<char>(byte ^ 0x10));
  f.close();

  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kCorrupt);
  EXPECT_EQ(report.ticks_verified, 101u);
  ASSERT_TRUE(report.framing_error.has_value());
  EXPECT_EQ(report.framing_error->rfind("hash mismatch at byte " + std::to_string(frame), 0), 0u)
      << *report.framing_error;
  EXPECT_FALSE(report.torn_frame.has_value());
  EXPECT_EQ(report.file_state, ReadState::kCorrupt);
}

TEST(ReplayVerify, OlderEngineRevisionIsNamedAndNotResimulated) {
  TempFile file("verify_older_engine");
  Recording rec;
  rec.edit_header = older_engine;
  record_match(file.path(), rec);

  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  EXPECT_FALSE(report.resimulated);
  EXPECT_EQ(report.ticks_verified, 0u);
  EXPECT_FALSE(report.diverged());
  ASSERT_TRUE(report.versions.has_value());
  const uint32_t rules = game::CratesGame().rules_version();
  EXPECT_EQ(report.versions->recorded.label(),
            std::string(sim::kEngineName) + " r" + std::to_string(sim::kSimRevision - 1) +
                " (crates rules " + std::to_string(rules - 1) + ")");
  EXPECT_EQ(report.versions->this_build.label(), this_build_label());
  EXPECT_EQ(
      report.versions->differences,
      (std::vector<std::string>{"sim revision: recorded " + std::to_string(sim::kSimRevision - 1) +
                                    ", this build " + std::to_string(sim::kSimRevision),
                                "crates rules version: recorded " + std::to_string(rules - 1) +
                                    ", this build " + std::to_string(rules)}));
  // The file is still read through: it is whole.
  EXPECT_EQ(report.tick_records, 240u);
  EXPECT_EQ(report.file_state, ReadState::kComplete);

  // Re-simulating anyway: the ticks were really made by this build, so
  // they verify, and the report still holds the differences.
  VerifyOptions anyway;
  anyway.ignore_version = true;
  const VerifyReport forced = verify_replay(file.path(), anyway);
  EXPECT_EQ(forced.outcome(), VerifyOutcome::kVerified);
  EXPECT_TRUE(forced.resimulated);
  EXPECT_EQ(forced.ticks_verified, 240u);
  ASSERT_TRUE(forced.versions.has_value());
  EXPECT_EQ(forced.versions->differences.size(), 2u);
}

TEST(ReplayVerify, IgnoringTheVersionReportsADivergenceAsUsual) {
  TempFile file("verify_older_forged_src");
  TempFile forged("verify_older_forged");
  Recording rec;
  rec.edit_header = older_engine;
  record_match(file.path(), rec);
  forge_input(file.path(), forged.path(), 100, 1);

  EXPECT_EQ(verify_replay(forged.path()).outcome(), VerifyOutcome::kVersionMismatch);
  VerifyOptions anyway;
  anyway.ignore_version = true;
  const VerifyReport report = verify_replay(forged.path(), anyway);
  EXPECT_EQ(report.outcome(), VerifyOutcome::kDiverged);
  EXPECT_EQ(*report.first_divergent_tick, 100);
  ASSERT_TRUE(report.versions.has_value());
  EXPECT_FALSE(report.versions->matches());
}

TEST(ReplayVerify, OtherWorldConfigIsNamedFieldByField) {
  TempFile file("verify_other_config");
  Recording rec;
  rec.edit_header = [](v1::ReplayHeader& header) {
    sim::WorldConfig config = game::CratesGame().world_config();
    config.gravity.y = -20.0f;
    config.substeps = 8;
    std::vector<uint8_t> bytes;
    sim::World3D::encode_config(config, bytes);
    header.set_world_config(bytes.data(), bytes.size());
  };
  record_match(file.path(), rec);

  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  ASSERT_TRUE(report.versions.has_value());
  EXPECT_EQ(report.versions->differences,
            (std::vector<std::string>{
                "world config gravity: recorded (0, -20, 0) m/s^2, this build (0, -9.81, 0) m/s^2",
                "world config substeps: recorded 8, this build 4"}));

  // Bytes this build cannot decode are named as such.
  TempFile garbled("verify_garbled_config");
  rec.edit_header = [](v1::ReplayHeader& header) { header.set_world_config("\x01\x02\x03"); };
  record_match(garbled.path(), rec);
  const VerifyReport bad = verify_replay(garbled.path());
  EXPECT_EQ(bad.outcome(), VerifyOutcome::kVersionMismatch);
  ASSERT_TRUE(bad.versions.has_value());
  ASSERT_EQ(bad.versions->differences.size(), 1u);
  EXPECT_EQ(bad.versions->differences[0].rfind(
                "world config: the recorded 3 bytes do not decode in this build", 0),
            0u)
      << bad.versions->differences[0];
}

TEST(ReplayVerify, FormatOneFileComesFromAnUnknownEarlierEngine) {
  TempFile file("verify_format1");
  Recording rec;
  rec.edit_header = [](v1::ReplayHeader& header) {
    header.set_format_version(1);
    header.clear_engine();
    header.clear_sim_revision();
    header.clear_rules_version();
    header.clear_world_config();
  };
  record_match(file.path(), rec);

  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  EXPECT_FALSE(report.framing_error.has_value());
  ASSERT_TRUE(report.versions.has_value());
  EXPECT_EQ(report.versions->recorded.label(),
            "an earlier engine that did not record its version (replay format 1)");
  EXPECT_EQ(report.versions->differences,
            (std::vector<std::string>{"engine: not recorded (replay format 1), this build " +
                                      std::string(sim::kEngineName) + " r" +
                                      std::to_string(sim::kSimRevision)}));
  EXPECT_EQ(report.file_state, ReadState::kComplete);

  VerifyOptions anyway;
  anyway.ignore_version = true;
  EXPECT_EQ(verify_replay(file.path(), anyway).outcome(), VerifyOutcome::kVerified);
}

TEST(ReplayVerify, NewerFormatIsAVersionMismatchNotCorruption) {
  TempFile src("verify_newer_src");
  TempFile file("verify_newer");
  record_match(src.path(), Recording{});
  testing_support::rewrite_header(src.path(), file.path(), [](v1::ReplayHeader& header) {
    header.set_format_version(kFormatVersion + 1);
    header.set_sim_revision(sim::kSimRevision + 1);
  });

  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  EXPECT_FALSE(report.framing_error.has_value());
  EXPECT_FALSE(report.error.has_value());
  EXPECT_EQ(report.file_state, ReadState::kUnsupported);
  ASSERT_TRUE(report.versions.has_value());
  ASSERT_EQ(report.versions->differences.size(), 2u);
  EXPECT_EQ(report.versions->differences[0],
            "replay format: recorded version 4, this build reads formats 1 to 3");

  // Its records cannot be read, so re-simulating anyway cannot run.
  VerifyOptions anyway;
  anyway.ignore_version = true;
  const VerifyReport forced = verify_replay(file.path(), anyway);
  EXPECT_EQ(forced.outcome(), VerifyOutcome::kCorrupt);
  ASSERT_TRUE(forced.error.has_value());
  EXPECT_NE(forced.error->find("not read by this build"), std::string::npos) << *forced.error;
}

TEST(ReplayVerify, VersionMismatchStillSaysTheFileIsIncomplete) {
  TempFile file("verify_older_torn");
  Recording rec;
  rec.edit_header = older_engine;
  record_match(file.path(), rec);
  testing_support::cut_inside_frame(file.path(), 0.5);
  const VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  EXPECT_EQ(report.file_state, ReadState::kTorn);
  EXPECT_TRUE(report.torn_frame.has_value());
}

TEST(ReplayVerify, UnknownGameIsAVersionMismatchAndMissingFileAnError) {
  TempFile file("verify_unknown_game");
  Recording rec;
  rec.edit_header = [](v1::ReplayHeader& header) { header.set_game("no-such-game"); };
  rec.ticks = 10;
  record_match(file.path(), rec);
  VerifyReport report = verify_replay(file.path());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kVersionMismatch);
  ASSERT_TRUE(report.versions.has_value());
  EXPECT_EQ(report.versions->differences,
            (std::vector<std::string>{"game: this build has no game \"no-such-game\" (it has: "
                                      "arena, crates, joust)"}));
  EXPECT_EQ(report.versions->this_build.label(), std::string(sim::kEngineName) + " r" +
                                                     std::to_string(sim::kSimRevision) +
                                                     " (no game \"no-such-game\")");

  VerifyOptions anyway;
  anyway.ignore_version = true;
  report = verify_replay(file.path(), anyway);
  EXPECT_EQ(report.outcome(), VerifyOutcome::kCorrupt);
  ASSERT_TRUE(report.error.has_value());
  EXPECT_NE(report.error->find("no-such-game"), std::string::npos);

  report = verify_replay("/nonexistent/replay.rwr");
  EXPECT_TRUE(report.error.has_value());
  EXPECT_EQ(report.outcome(), VerifyOutcome::kCorrupt);
  EXPECT_FALSE(report.header.has_value());
}

TEST(ReplayVerify, WorldConfigIsDescribedByTheRecordedGamesLane) {
  std::vector<uint8_t> bytes;
  game::CratesGame().encode_world_config(bytes);
  auto fields = describe_world_config("crates", bytes);
  ASSERT_TRUE(fields.ok()) << fields.status().message();
  EXPECT_EQ(*fields, sim::World3D::describe_config(game::CratesGame().world_config()));

  auto unknown = describe_world_config("chess", bytes);
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(unknown.status().message(), "this build has no game \"chess\"");
}

}  // namespace
}  // namespace rwd::replay
