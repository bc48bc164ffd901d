// SPDX-License-Identifier: MIT
// rewind-replay: parse the command line, call the replay library, print.
#include <iostream>
#include <variant>

#include "replay_cli.h"
#include "replay_print.h"
#include "rewind/cli/flag_parser.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_summary.h"
#include "rewind/replay/replay_verifier.h"

namespace {

using namespace rwd;

int run(const replay_tool::HelpRequest& help) {
  std::cout << help.text;
  return 0;
}

int run(const replay_tool::VerifyCommand& cmd) {
  replay::VerifyOptions options;
  options.ignore_version = cmd.ignore_version;
  const replay::VerifyReport report = replay::verify_replay(cmd.file, options);
  if (cmd.json) {
    replay_tool::print_verify_json(cmd.file, report, std::cout);
  } else {
    replay_tool::print_verify_text(report, std::cout);
  }
  return replay_tool::verify_exit_code(report);
}

int run(const replay_tool::InspectCommand& cmd) {
  Result<replay::ReplaySummary> summary = replay::summarize_replay(cmd.file);
  if (!summary.ok()) {
    std::cerr << "rewind-replay inspect: " << summary.status().message() << "\n";
    return replay_tool::kExitCorrupt;
  }
  replay_tool::print_summary(cmd.file, *summary, std::cout);
  return replay_tool::inspect_exit_code(*summary);
}

int run(const replay_tool::TamperCommand& cmd) {
  Result<game::PlayerInput> original =
      replay::rewrite_replay_input(cmd.file, cmd.out, cmd.edit, cmd.overwrite);
  if (!original.ok()) {
    std::cerr << "rewind-replay tamper: " << original.status().message() << "\n";
    return 1;
  }
  std::cout << "wrote " << cmd.out << ": tick " << cmd.edit.tick << " player " << cmd.edit.player
            << " input (" << original->axis_x << ", " << original->axis_y << ", buttons "
            << original->buttons << ") -> (" << cmd.edit.axis_x.value_or(original->axis_x) << ", "
            << cmd.edit.axis_y.value_or(original->axis_y) << ", buttons "
            << cmd.edit.buttons.value_or(original->buttons) << "), frames re-hashed\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Result<replay_tool::Command> command = replay_tool::parse_command_line(argc, argv);
  if (!command.ok()) {
    std::cerr << "rewind-replay: " << command.status().message() << "\n";
    return cli::kExitUsage;
  }
  return std::visit([](const auto& cmd) { return run(cmd); }, *command);
}
