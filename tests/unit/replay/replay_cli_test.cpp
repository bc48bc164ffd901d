// SPDX-License-Identifier: MIT
// rewind-replay as a user runs it: output lines and exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "replay_test_support.h"
#include "rewind/game/crates_game.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/sim/version.h"

namespace rwd::replay {
namespace {

using testing_support::record_match;
using testing_support::Recording;
using testing_support::TempFile;

struct ToolRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

/// `text` as one shell word: the build tree may sit under any path.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

ToolRun run_tool(const std::string& args) {
  ToolRun run;
  const std::string command = shell_quoted(REWIND_REPLAY_TOOL) + " " + args + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buf;
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) run.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(ReplayCli, HelpForTheToolAndEveryCommand) {
  for (const char* args :
       {"--help", "verify --help", "inspect --help", "tamper --help", "view --help"}) {
    const ToolRun run = run_tool(args);
    EXPECT_EQ(run.exit_code, 0) << args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "usage: rewind-replay")) << args << "\n" << run.output;
  }
  EXPECT_TRUE(contains(run_tool("tamper --help").output, "--axis-x"));
}

TEST(ReplayCli, UsageErrorsExit64WithAMessage) {
  struct Case {
    const char* args;
    const char* says;
  };
  for (const Case& c :
       {Case{"", "missing command"}, Case{"frobnicate x.rwr", "unknown command 'frobnicate'"},
        Case{"verify", "expected one FILE, got 0"},
        Case{"verify a.rwr b.rwr", "expected one FILE, got 2"},
        Case{"verify a.rwr --jsn", "unknown flag --jsn"},
        Case{"inspect -x a.rwr", "unexpected argument '-x'"},
        Case{"tamper a.rwr --tick", "--tick: missing value"},
        Case{"tamper a.rwr --tick abc --player 0 --axis-x 1 --out b",
             "--tick: expected an integer, got 'abc'"},
        Case{"tamper a.rwr --tick 3 --player 0 --axis-x 1.5 --out b",
             "--axis-x: expected an integer, got '1.5'"},
        Case{"tamper a.rwr --tick 3 --player 0 --set axis_x --out b",
             "--set: expected FIELD=VALUE, got 'axis_x'"},
        Case{"tamper a.rwr --tick 3 --player 0 --set axis_x=1e3 --out b",
             "--set axis_x: expected an integer, got '1e3'"},
        Case{"tamper a.rwr --tick 3 --player 0 --out b", "give --set FIELD=VALUE"},
        Case{"tamper a.rwr --tick 3 --axis-x 1 --out b", "--player is required"},
        Case{"tamper a.rwr --tick 3 --player 0 --axis-x 1", "--out is required"}}) {
    const ToolRun run = run_tool(c.args);
    EXPECT_EQ(run.exit_code, 64) << c.args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, c.says)) << c.args << "\n" << run.output;
  }
}

TEST(ReplayCli, ViewWritesABundleAndRefusesWhatItCannotServe) {
  TempFile replay("cli_view");
  Recording rec;
  rec.players = 2;
  rec.ticks = 60;
  const std::vector<uint64_t> recorded = record_match(replay.path(), rec);
  TempFile bundle("cli_view_bundle");

  ToolRun run = run_tool("view " + replay.path() + " --bundle-out " + bundle.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "crates, 2 players, 60 ticks")) << run.output;
  // The bundle is a file `view` reads back like a replay.
  TempFile again("cli_view_again");
  run = run_tool("view " + bundle.path() + " --bundle-out " + again.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(std::filesystem::file_size(bundle.path()), std::filesystem::file_size(again.path()));

  // A viewer directory without the viewer: exit 1, saying how to build it.
  run = run_tool("view " + replay.path() + " --port 0 --viewer-dir " + ::testing::TempDir());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "--target rewind_viewer")) << run.output;
  // Files it cannot read, desync reports it cannot use: exit 2.
  run = run_tool("view /nonexistent/match.rwr --bundle-out " + again.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = run_tool("view " + replay.path() + " --desync /tmp/state.bin --bundle-out " + again.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "desync_pP_tT_rR.bin")) << run.output;
  run = run_tool("view " + replay.path() + " --port 70000");
  EXPECT_EQ(run.exit_code, 64) << run.output;
}

TEST(ReplayCli, VerifyTamperInspectEndToEnd) {
  TempFile file("cli_match");
  TempFile forged("cli_forged");
  TempFile cut("cli_cut");
  Recording rec;
  const std::vector<uint64_t> checksums = record_match(file.path(), rec);
  ASSERT_EQ(checksums.size(), 240u);
  char last[19];
  std::snprintf(last, sizeof last, "0x%016llx", static_cast<unsigned long long>(checksums.back()));

  ToolRun run = run_tool("verify " + file.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output,
                       "verified 240 ticks (game crates, 4 players) checksum of last "
                       "tick " +
                           std::string(last)))
      << run.output;

  run = run_tool("inspect " + file.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "ticks: 0..239 (240 tick records)")) << run.output;
  EXPECT_TRUE(contains(run.output, "player 0: 4")) << run.output;  // ticks 49, 99, 149, 199
  EXPECT_TRUE(contains(run.output, "keyframes: 4")) << run.output;
  EXPECT_TRUE(contains(run.output, "reason \"match over\"")) << run.output;

  // Axis 1000 or -1000: whichever differs from the recorded stick.
  Result<ReplayReader> reader = ReplayReader::open(file.path());
  ASSERT_TRUE(reader.ok());
  int recorded_x = 0;
  while (true) {
    auto r = reader->next();
    ASSERT_TRUE(r.ok() && r->has_value());
    if ((*r)->has_tick() && (*r)->tick().tick() == 150) {
      recorded_x = proto::from_wire((*r)->tick().inputs(3))->as<rwd::StickInput>().axis_x;
      break;
    }
  }
  const std::string forged_x = recorded_x > 0 ? "-1000" : "1000";
  run = run_tool("tamper " + file.path() + " --tick 150 --player 3 --axis-x " + forged_x +
                 " --out " + forged.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames re-hashed")) << run.output;

  run = run_tool("verify " + forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "DIVERGED at tick 150: expected 0x")) << run.output;
  EXPECT_TRUE(contains(run.output, "fields that differ at tick 179")) << run.output;
  EXPECT_TRUE(contains(run.output, "  body ")) << run.output;

  run = run_tool("verify --json " + forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "\"first_divergent_tick\": 150")) << run.output;
  EXPECT_TRUE(contains(run.output, "\"differences_tick\": 179")) << run.output;

  // Fields and ranges are the recorded game's.
  run = run_tool("tamper " + file.path() +
                 " --tick 150 --player 3 --set axis_x=5000 --overwrite --out " + forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "input field 'axis_x' = 5000 is outside [-1000, 1000]"))
      << run.output;
  run = run_tool("tamper " + file.path() +
                 " --tick 150 --player 3 --set heading=5 --overwrite --out " + forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "the input ('stick') has no field 'heading'")) << run.output;

  // Tampering again without --overwrite refuses to clobber the output.
  run = run_tool("tamper " + file.path() + " --tick 150 --player 3 --axis-x 0 --out " +
                 forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "already exists")) << run.output;

  std::filesystem::copy_file(file.path(), cut.path());
  testing_support::cut_inside_frame(cut.path(), 0.5);
  run = run_tool("verify " + cut.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_TRUE(contains(run.output, "prefix verified: ")) << run.output;
  EXPECT_TRUE(contains(run.output, "INCOMPLETE: the file ends inside a frame")) << run.output;
  run = run_tool("inspect " + cut.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_TRUE(contains(run.output, "end: none")) << run.output;

  run = run_tool("verify /nonexistent/x.rwr");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "cannot open replay")) << run.output;
}

// One recording per outcome, verified and inspected by the tool.
class ReplayCliOutcomes : public ::testing::Test {
 protected:
  void SetUp() override { checksums_ = record_match(clean_.path(), Recording{}); }

  std::string copy_of_clean(const TempFile& to) {
    std::filesystem::copy_file(clean_.path(), to.path(),
                               std::filesystem::copy_options::overwrite_existing);
    return to.path();
  }

  static std::string revision(uint32_t r) { return "rewind-sim r" + std::to_string(r); }
  static uint32_t rules() { return game::CratesGame().rules_version(); }

  TempFile clean_{"cli_outcome_clean"};
  std::vector<uint64_t> checksums_;
};

TEST_F(ReplayCliOutcomes, CleanFileExits0) {
  ToolRun run = run_tool("verify " + clean_.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "verified 240 ticks (game crates, 4 players)")) << run.output;
  EXPECT_FALSE(contains(run.output, "INCOMPLETE")) << run.output;

  run = run_tool("verify --json " + clean_.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  for (const char* field :
       {"\"outcome\": \"verified\"", "\"exit_code\": 0", "\"complete\": true",
        "\"file_state\": \"complete\"", "\"versions_match\": true", "\"resimulated\": true",
        "\"version_differences\": []", "\"tick_records\": 240"}) {
    EXPECT_TRUE(contains(run.output, field)) << field << "\n" << run.output;
  }

  run = run_tool("inspect " + clean_.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "  engine " + revision(sim::kSimRevision) + " (crates rules " +
                                       std::to_string(rules()) + "); this build runs the same\n"))
      << run.output;
  EXPECT_TRUE(contains(run.output, "world config:\n  gravity (0, -9.81, 0) m/s^2\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "  substeps 4\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "  bounds_upper (200, 200, 200) m\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "file: complete")) << run.output;
}

TEST_F(ReplayCliOutcomes, OlderEngineExits3NamingBothVersions) {
  TempFile older("cli_outcome_older");
  Recording rec;
  rec.edit_header = [](v1::ReplayHeader& header) {
    header.set_sim_revision(sim::kSimRevision - 1);
    header.set_rules_version(game::CratesGame().rules_version() - 1);
  };
  record_match(older.path(), rec);

  const std::string recorded =
      revision(sim::kSimRevision - 1) + " (crates rules " + std::to_string(rules() - 1) + ")";
  const std::string current =
      revision(sim::kSimRevision) + " (crates rules " + std::to_string(rules()) + ")";
  ToolRun run = run_tool("verify " + older.path());
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output, "replay was recorded by " + recorded + "; this build runs " +
                                       current + ": not re-simulated\n"))
      << run.output;
  EXPECT_TRUE(contains(run.output, "  sim revision: recorded " +
                                       std::to_string(sim::kSimRevision - 1) + ", this build " +
                                       std::to_string(sim::kSimRevision) + "\n"))
      << run.output;
  EXPECT_TRUE(contains(run.output, "--ignore-version")) << run.output;
  EXPECT_FALSE(contains(run.output, "DIVERGED")) << run.output;

  run = run_tool("verify --json " + older.path());
  EXPECT_EQ(run.exit_code, 3) << run.output;
  for (const std::string& field :
       {std::string("\"outcome\": \"version_mismatch\""), std::string("\"exit_code\": 3"),
        std::string("\"versions_match\": false"), std::string("\"resimulated\": false"),
        std::string("\"complete\": true"),
        "\"sim_revision\": " + std::to_string(sim::kSimRevision - 1),
        "\"sim_revision\": " + std::to_string(sim::kSimRevision)}) {
    EXPECT_TRUE(contains(run.output, field)) << field << "\n" << run.output;
  }

  run = run_tool("verify --ignore-version " + older.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "note: versions differ: replay was recorded by " + recorded))
      << run.output;
  EXPECT_TRUE(contains(run.output, "re-simulating anyway (--ignore-version)")) << run.output;
  EXPECT_TRUE(contains(run.output, "verified 240 ticks")) << run.output;

  // inspect shows it and still exits by the file's state.
  run = run_tool("inspect " + older.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(
      run.output, "  engine " + recorded + "; this build runs " + current + ", which differs:\n"))
      << run.output;
}

TEST_F(ReplayCliOutcomes, CutShortRecordingsExit4AfterTheirPrefixVerified) {
  TempFile boundary("cli_outcome_boundary");
  testing_support::cut_after_tick(copy_of_clean(boundary), 150);
  ToolRun run = run_tool("verify " + boundary.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  char last[19];
  std::snprintf(last, sizeof last, "0x%016llx", static_cast<unsigned long long>(checksums_[150]));
  EXPECT_TRUE(contains(run.output,
                       "prefix verified: 151 ticks (game crates, 4 players) checksum "
                       "of last tick " +
                           std::string(last)))
      << run.output;
  EXPECT_TRUE(contains(run.output,
                       "INCOMPLETE: no end record; the recording stops after tick 150 on a frame "
                       "boundary"))
      << run.output;
  run = run_tool("verify --json " + boundary.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  for (const char* field :
       {"\"outcome\": \"incomplete\"", "\"exit_code\": 4", "\"complete\": false",
        "\"file_state\": \"incomplete\"", "\"ticks_verified\": 151", "\"torn_frame\": null"}) {
    EXPECT_TRUE(contains(run.output, field)) << field << "\n" << run.output;
  }
  run = run_tool("inspect " + boundary.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_TRUE(contains(run.output, "file: INCOMPLETE: no end record")) << run.output;

  TempFile torn("cli_outcome_torn");
  testing_support::cut_inside_frame(copy_of_clean(torn), 0.5, kFrameHeaderBytes + 2);
  run = run_tool("verify " + torn.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_TRUE(contains(run.output, "prefix verified: ")) << run.output;
  EXPECT_TRUE(contains(run.output,
                       "INCOMPLETE: the file ends inside a frame, as a write cut "
                       "short leaves it: truncated frame at byte "))
      << run.output;
  EXPECT_FALSE(contains(run.output, "file breaks at")) << run.output;
  run = run_tool("verify --json " + torn.path());
  EXPECT_TRUE(contains(run.output, "\"file_state\": \"torn\"")) << run.output;
  EXPECT_TRUE(contains(run.output, "\"exit_code\": 4")) << run.output;
  run = run_tool("inspect " + torn.path());
  EXPECT_EQ(run.exit_code, 4) << run.output;
}

TEST_F(ReplayCliOutcomes, BitFlipInsideAFrameExits2) {
  TempFile flipped("cli_outcome_flip");
  copy_of_clean(flipped);
  const uint64_t size = std::filesystem::file_size(flipped.path());
  {
    std::fstream f(flipped.path(), std::ios::in | std::ios::out | std::ios::binary);
    const auto at = static_cast<std::streamoff>(size / 2);
    f.seekg(at);
    char byte = 0;
    f.get(byte);
    f.seekp(at);
    f.put(static_cast<char>(byte ^ 0x01));
  }
  ToolRun run = run_tool("verify " + flipped.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "prefix verified: ")) << run.output;
  EXPECT_TRUE(contains(run.output, "file breaks at: ")) << run.output;
  EXPECT_FALSE(contains(run.output, "INCOMPLETE")) << run.output;
  run = run_tool("verify --json " + flipped.path());
  EXPECT_TRUE(contains(run.output, "\"outcome\": \"corrupt\"")) << run.output;
  EXPECT_TRUE(contains(run.output, "\"file_state\": \"corrupt\"")) << run.output;
  run = run_tool("inspect " + flipped.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "file: CORRUPT: breaks at: ")) << run.output;
}

TEST_F(ReplayCliOutcomes, FormatOneFileExits3AndInspects) {
  TempFile old_format("cli_outcome_format1");
  Recording rec;
  rec.edit_header = [](v1::ReplayHeader& header) {
    header.set_format_version(1);
    header.clear_engine();
    header.clear_sim_revision();
    header.clear_rules_version();
    header.clear_world_config();
  };
  record_match(old_format.path(), rec);
  ToolRun run = run_tool("verify " + old_format.path());
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output,
                       "replay was recorded by an earlier engine that did not record its version "
                       "(replay format 1); this build runs " +
                           revision(sim::kSimRevision)))
      << run.output;
  run = run_tool("inspect " + old_format.path());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "engine not recorded (replay format 1)")) << run.output;
  EXPECT_TRUE(contains(run.output, "world config: not recorded")) << run.output;
}

}  // namespace
}  // namespace rwd::replay
