// SPDX-License-Identifier: MIT
// rewind-tune: parse the command line, check the outputs can be written,
// build the target, sweep, report. The logic is in the rewind_tune library.
#include <fstream>
#include <iostream>
#include <memory>

#include "rewind/tune/game_target.h"
#include "rewind/tune/scene_target.h"
#include "rewind/tune/tune_chart.h"
#include "rewind/tune/tune_options.h"
#include "rewind/tune/tune_report.h"

namespace {

using namespace rwd::tune;

int usage_error(const std::string& message) {
  std::cerr << "rewind-tune: " << message << "\n";
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  rwd::Result<TuneCommand> parsed = parse_tune_command(argc, argv);
  if (!parsed.ok()) return usage_error(parsed.status().message());
  const TuneCommand& cmd = *parsed;
  if (cmd.action == TuneCommand::Action::kHelp) {
    std::cout << tune_help_text();
    return 0;
  }
  if (cmd.action == TuneCommand::Action::kList) {
    std::cout << tune_list_text();
    return 0;
  }

  // Outputs are checked before a sweep that may take minutes.
  std::ofstream csv;
  if (!cmd.csv_path.empty()) {
    csv.open(cmd.csv_path);
    if (!csv) return usage_error("--csv: cannot write " + cmd.csv_path);
  }
  if (!cmd.chart_path.empty()) {
    if (!gnuplot_available()) {
      return usage_error("--chart needs gnuplot on PATH (Debian: gnuplot-nox; scripts/setup.sh)");
    }
    if (!std::ofstream(cmd.chart_path))
      return usage_error("--chart: cannot write " + cmd.chart_path);
  }

  std::ostream* progress = cmd.quiet ? nullptr : &std::cerr;
  std::unique_ptr<TuneTarget> target;
  if (!cmd.scene.empty()) {
    auto scene = SceneTarget::create(cmd.scene, cmd.size, !cmd.awake);
    if (!scene.ok()) return usage_error(scene.status().message());
    target = std::move(*scene);
  } else {
    auto game = GameTarget::create(cmd.play, progress);
    if (!game.ok()) return usage_error(game.status().message());
    target = std::move(*game);
  }

  rwd::Result<TuneResult> result = tune(*target, cmd.plan, progress);
  if (!result.ok()) return usage_error(result.status().message());

  if (cmd.json) {
    print_json(*target, cmd.plan, *result, std::cout);
  } else {
    print_text(*target, cmd.plan, *result, std::cout);
  }
  std::cout.flush();

  int status = exit_code(*result);
  if (csv.is_open()) {
    write_csv(*target, cmd.plan, *result, csv);
    csv.close();
    if (!csv) {
      std::cerr << "rewind-tune: could not write all of " << cmd.csv_path << "\n";
      status = kExitOutputFailed;
    }
  }
  if (!cmd.chart_path.empty()) {
    if (rwd::Status drawn = write_chart(*target, *result, cmd.chart_path); !drawn.ok()) {
      std::cerr << "rewind-tune: " << drawn.message() << "\n";
      status = kExitOutputFailed;
    } else if (progress != nullptr) {
      *progress << "rewind-tune: chart " << cmd.chart_path << "\n";
    }
  }
  return status;
}
