// SPDX-License-Identifier: MIT
#pragma once
// rewind-tune's command line: flags to a TuneCommand, and the help text.
#include <string>

#include "rewind/core/status.h"
#include "rewind/tune/game_target.h"
#include "rewind/tune/tuner.h"

namespace rwd::tune {

struct TuneCommand {
  enum class Action : uint8_t {
    kTune,  ///< sweep a scene or a game
    kList,  ///< --list: print the scenes and games
    kHelp,  ///< -h/--help: print help_text()
  };
  Action action = Action::kTune;
  std::string scene;   ///< --scene; empty when tuning a game
  int size = 0;        ///< --size; 0 = the scene's chart size
  bool awake = false;  ///< --no-sleep: the scene runs with sleeping off
  std::string game;    ///< --game; empty when tuning a scene
  GamePlay play;       ///< how a game is played (--players, --seed, ...)
  SweepPlan plan;      ///< grid, budget, finalists, repeats
  std::string csv_path;
  std::string chart_path;
  bool json = false;
  bool quiet = false;  ///< no progress on stderr
};

/// Parses argv. kInvalidArgument (exit 2) names the flag or value at fault;
/// metric names in --budget are checked later, against the target's metrics.
Result<TuneCommand> parse_tune_command(int argc, const char* const* argv);

/// The full --help text.
std::string tune_help_text();

/// The --list text: scenes with their sizes, and games.
std::string tune_list_text();

}  // namespace rwd::tune
