// SPDX-License-Identifier: MIT
// rewind-tune's command line, parsed without running anything.
#include "rewind/tune/tune_options.h"

#include <gtest/gtest.h>

#include <vector>

namespace rwd::tune {
namespace {

Result<TuneCommand> parse(std::vector<const char*> args) {
  args.insert(args.begin(), "rewind-tune");
  return parse_tune_command(static_cast<int>(args.size()), args.data());
}

TEST(TuneOptions, SceneGameAndTheirFlags) {
  auto scene = parse({"--scene", "stack", "--size", "10", "--budget", "penetration_mm=2",
                      "--budget=drift_m=0.05", "--quick", "--json"});
  ASSERT_TRUE(scene.ok()) << scene.status().message();
  EXPECT_EQ(scene->scene, "stack");
  EXPECT_EQ(scene->size, 10);
  EXPECT_TRUE(scene->plan.budget.overrides("penetration_mm"));
  EXPECT_TRUE(scene->plan.budget.overrides("drift_m"));
  EXPECT_EQ(scene->plan.grid.size(), 6u);
  EXPECT_TRUE(scene->json);

  auto game = parse({"--game", "crates", "--players", "3", "--seed", "9", "--ticks", "600",
                     "--window-ticks", "30", "--script", "circle", "--substeps", "2,4", "--relax",
                     "1", "--hertz", "30,60"});
  ASSERT_TRUE(game.ok()) << game.status().message();
  EXPECT_EQ(game->play.players, 3u);
  EXPECT_EQ(game->play.seed, 9u);
  EXPECT_EQ(game->play.ticks, 600);
  EXPECT_EQ(game->play.window_ticks, 30);
  EXPECT_EQ(game->play.script, tools::BotScript::kCircle);
  EXPECT_EQ(game->plan.grid.size(), 4u);

  EXPECT_EQ(parse({"--help"})->action, TuneCommand::Action::kHelp);
  EXPECT_EQ(parse({"--list"})->action, TuneCommand::Action::kList);
  EXPECT_EQ(parse({"--scene", "stack"})->plan.grid.size(), 96u);
}

TEST(TuneOptions, UsageErrorsSayWhatIsWrong) {
  struct Case {
    std::vector<const char*> args;
    const char* says;
  };
  const Case cases[] = {
      {{}, "give either --scene NAME or --game NAME"},
      {{"--scene", "stack", "--game", "crates"}, "give either --scene NAME or --game NAME"},
      {{"--scene", "stack", "--players", "2"}, "--players applies to --game only"},
      {{"--game", "crates", "--size", "5"}, "--size applies to --scene only"},
      {{"--game", "crates", "--script", "dance"},
       "--script: expected game, random, circle or idle"},
      {{"--game", "crates", "--ticks", "60", "--window-ticks", "61"}, "longer than the match"},
      {{"--scene", "stack", "--substeps", "0,2"}, "--substeps: 0 is outside [1, 64]"},
      {{"--scene", "stack", "--relax", "17"}, "--relax: 17 is outside [0, 16]"},
      {{"--scene", "stack", "--hertz", "fast"}, "--hertz: expected numbers"},
      {{"--scene", "stack", "--quick", "--substeps", "2"}, "--quick is a grid of its own"},
      {{"--scene", "stack", "--budget", "drift_m"}, "--budget: expected METRIC=LIMIT"},
      {{"--scene", "stack", "--chart", "out.png"}, "--chart: the chart is SVG"},
      {{"--scene", "stack", "--repeats", "0"}, "--repeats: 0 is outside [1, 50]"},
      {{"--scene", "stack", "--frobnicate"}, "unknown flag --frobnicate"},
  };
  for (const Case& c : cases) {
    auto parsed = parse(c.args);
    ASSERT_FALSE(parsed.ok()) << c.says;
    EXPECT_NE(parsed.status().message().find(c.says), std::string::npos)
        << "got: " << parsed.status().message();
  }
}

TEST(TuneOptions, HelpDocumentsExitCodesUnitsAndMetrics) {
  const std::string help = tune_help_text();
  for (const char* needle : {"usage: rewind-tune", "exit status:", "position_error_m", "ms/step",
                             "--budget", "--window-ticks", "gnuplot"}) {
    EXPECT_NE(help.find(needle), std::string::npos) << needle;
  }
  const std::string list = tune_list_text();
  EXPECT_NE(list.find("stack"), std::string::npos);
  EXPECT_NE(list.find("crates"), std::string::npos);
}

}  // namespace
}  // namespace rwd::tune
