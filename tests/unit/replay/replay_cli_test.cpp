// SPDX-License-Identifier: MIT
// rewind-replay as a user runs it: output lines and exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "replay_test_support.h"
#include "rewind/replay/replay_reader.h"

namespace rwd::replay {
namespace {

using testing_support::record_match;
using testing_support::Recording;
using testing_support::TempFile;

struct ToolRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

ToolRun run_tool(const std::string& args) {
  ToolRun run;
  const std::string command = std::string(REWIND_REPLAY_TOOL) + " " + args + " 2>&1";
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
  for (const char* args : {"--help", "verify --help", "inspect --help", "tamper --help"}) {
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
        Case{"tamper a.rwr --tick 3 --player 0 --axis-x 5000 --out b",
             "--axis-x: 5000 is outside [-1000, 1000]"},
        Case{"tamper a.rwr --tick 3 --player 0 --out b", "give at least one"},
        Case{"tamper a.rwr --tick 3 --axis-x 1 --out b", "--player is required"},
        Case{"tamper a.rwr --tick 3 --player 0 --axis-x 1", "--out is required"}}) {
    const ToolRun run = run_tool(c.args);
    EXPECT_EQ(run.exit_code, 64) << c.args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, c.says)) << c.args << "\n" << run.output;
  }
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
      recorded_x = (*r)->tick().inputs(3).axis_x();
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

  // Tampering again without --overwrite refuses to clobber the output.
  run = run_tool("tamper " + file.path() + " --tick 150 --player 3 --axis-x 0 --out " +
                 forged.path());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "already exists")) << run.output;

  std::filesystem::copy_file(file.path(), cut.path());
  testing_support::cut_inside_frame(cut.path(), 0.5);
  run = run_tool("verify " + cut.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "prefix verified: ")) << run.output;
  EXPECT_TRUE(contains(run.output, "file breaks at: ")) << run.output;
  run = run_tool("inspect " + cut.path());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "end: none")) << run.output;

  run = run_tool("verify /nonexistent/x.rwr");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "cannot open replay")) << run.output;
}

}  // namespace
}  // namespace rwd::replay
