// SPDX-License-Identifier: MIT
// rewind-tune as a user runs it: exit codes, messages, and a short real
// sweep whose pick is checked by running the scene again at that setting.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"
#include "rewind/tune/tune_chart.h"

namespace rwd::tune {
namespace {

struct ToolRun {
  int exit_code = -1;
  std::string out;  // stdout
  std::string all;  // stdout, then stderr
};

/// `text` as one shell word: the build tree may sit under any path.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

ToolRun run_tool(const std::string& args) {
  ToolRun run;
  const std::filesystem::path err =
      std::filesystem::temp_directory_path() / ("rewind_tune_cli_" + std::to_string(::getpid()));
  const std::string command =
      shell_quoted(REWIND_TUNE_TOOL) + " " + args + " 2>" + shell_quoted(err.string());
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buf;
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) run.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  run.all = run.out + text.str();
  std::filesystem::remove(err);
  return run;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

TEST(TuneCli, HelpAndList) {
  const ToolRun help = run_tool("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(contains(help.out, "usage: rewind-tune"));
  EXPECT_TRUE(contains(help.out, "exit status:"));
  const ToolRun list = run_tool("--list");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_TRUE(contains(list.out, "free_fall"));
  EXPECT_TRUE(contains(list.out, "crates"));
}

TEST(TuneCli, UsageErrorsExit2WithAMessage) {
  struct Case {
    const char* args;
    const char* says;
  };
  const Case cases[] = {
      {"", "give either --scene NAME or --game NAME"},
      {"--frobnicate", "unknown flag --frobnicate"},
      {"--scene nope", "unknown scene 'nope'"},
      {"--game chess", "unknown game 'chess'"},
      {"--scene stack --size 5 --players 3", "--players applies to --game only"},
      {"--scene stack --size 5 --substeps 1,99", "--substeps: 99 is outside [1, 64]"},
      {"--scene free_fall --quick --budget nope_mm=2", "no metric 'nope_mm'"},
      {"--scene free_fall --quick --csv /nonexistent/dir/out.csv", "--csv: cannot write"},
  };
  for (const Case& c : cases) {
    const ToolRun run = run_tool(c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args << "\n" << run.all;
    EXPECT_TRUE(contains(run.all, c.says)) << c.args << "\n" << run.all;
  }
}

// The setting named on the report's WorldConfig line.
bool read_pick(const std::string& report, SolverSetting& out) {
  const std::regex line(
      "set in WorldConfig: substeps = ([0-9]+), relax_iterations = ([0-9]+), contact_hertz = "
      "([0-9.]+)");
  std::smatch m;
  if (!std::regex_search(report, m, line)) return false;
  out = {std::stoi(m[1]), std::stoi(m[2]), std::stof(m[3])};
  return true;
}

TEST(TuneCli, QuickSweepPicksASettingThatPasses) {
  // A generous budget so that the outcome does not hang on the solver's
  // current resting depth; what is checked is that the pick meets it.
  const ToolRun run = run_tool(
      "--scene stack --size 5 --quick --repeats 3 --budget penetration_mm=20 --budget drift_m=0.5");
  ASSERT_EQ(run.exit_code, 0) << run.all;
  EXPECT_TRUE(contains(run.out, "pick:")) << run.out;
  EXPECT_TRUE(contains(run.out, "default:")) << run.out;
  // Which passing setting is cheapest is a matter of timing; the report
  // compares it with the default either way.
  EXPECT_TRUE(contains(run.out, "cost:     the pick")) << run.out;
  EXPECT_TRUE(contains(run.all, "[6/6]")) << "progress on stderr\n" << run.all;
  SolverSetting pick;
  ASSERT_TRUE(read_pick(run.out, pick)) << run.out;

  // The same scene at the pick, run here: every metric within the budget.
  auto scene = scenes::make_scene("stack", 5);
  scenes::RewindEngine engine(pick.applied_to(sim::WorldConfig{}));
  const scenes::SceneResult again = scenes::run_scene(*scene, engine);
  const scenes::Metric* drift = again.metric("drift_m");
  const scenes::Metric* depth = again.metric("penetration_mm");
  ASSERT_NE(drift, nullptr);
  ASSERT_NE(depth, nullptr);
  EXPECT_LE(drift->value, 0.5);
  EXPECT_LE(depth->value, 20.0);
}

TEST(TuneCli, NothingPassesExits1AndNamesTheClosest) {
  // Boxes resting on boxes always overlap a little: no setting rests at 0.
  const ToolRun run =
      run_tool("--scene stack --size 5 --quick --repeats 1 --budget penetration_mm=0");
  EXPECT_EQ(run.exit_code, 1) << run.all;
  EXPECT_TRUE(contains(run.out, "no setting of the 6 meets the budget")) << run.out;
  EXPECT_TRUE(contains(run.out, "closest:")) << run.out;
}

TEST(TuneCli, GameSweepWritesCsvAndJson) {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() /
                                    ("rewind_tune_" + std::to_string(::getpid()) + ".csv");
  const ToolRun run = run_tool(
      "--game crates --players 2 --ticks 120 --reference-substeps 8 --quick --repeats 1 --json "
      "--quiet --budget position_error_m=10 --csv " +
      csv.string());
  EXPECT_EQ(run.exit_code, 0) << run.all;
  EXPECT_TRUE(contains(run.out, "\"outcome\":\"found\"")) << run.out;
  EXPECT_TRUE(contains(run.out, "\"source\":\"user\"")) << run.out;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_TRUE(contains(header, "ms_per_step")) << header;
  int rows = 0;
  for (std::string row; std::getline(in, row);) ++rows;
  EXPECT_EQ(rows, 6 * 4) << "6 settings, 4 metrics each";
  std::filesystem::remove(csv);
}

TEST(TuneCli, ChartIsAnSvg) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::filesystem::path svg = std::filesystem::temp_directory_path() /
                                    ("rewind_tune_" + std::to_string(::getpid()) + ".svg");
  const ToolRun run =
      run_tool("--scene free_fall --quick --repeats 1 --quiet --chart " + svg.string());
  EXPECT_EQ(run.exit_code, 0) << run.all;
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(contains(text.str(), "<svg")) << "not an SVG: " << svg;
  EXPECT_TRUE(contains(text.str(), "pick"));
  std::filesystem::remove(svg);
}

}  // namespace
}  // namespace rwd::tune
