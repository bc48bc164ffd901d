// SPDX-License-Identifier: MIT
// rewind-replay's run loop (replay_main.h): parse the command line, call the
// replay library, print.
#include <csignal>
#include <fstream>
#include <iostream>
#include <memory>
#include <variant>

#include "replay_cli.h"
#include "replay_print.h"
#include "rewind/cli/flag_parser.h"
#include "rewind/game/simulation.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_summary.h"
#include "rewind/replay/replay_verifier.h"
#include "rewind/replay/replay_view.h"
#include "rewind/server/static_files.h"
#include "rewind/tools/replay_main.h"
#include "view_server.h"

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
  // The fields are the recorded game's: its input spec comes from the game
  // this program has registered under the header's name.
  Result<replay::ReplayReader> reader = replay::ReplayReader::open(cmd.file);
  if (!reader.ok()) {
    std::cerr << "rewind-replay tamper: " << reader.status().message() << "\n";
    return 1;
  }
  game::MatchSetup setup;
  setup.player_count = reader->header().player_count();
  setup.seed = reader->header().seed();
  Result<std::unique_ptr<game::Simulation>> sim =
      game::Simulation::create(reader->header().game(), setup);
  if (!sim.ok()) {
    std::cerr << "rewind-replay tamper: " << sim.status().message() << "\n";
    return 1;
  }
  Result<replay::InputRewrite> rewrite = replay::rewrite_replay_input(
      cmd.file, cmd.out, cmd.edit, (*sim)->game().input_spec(), cmd.overwrite);
  if (!rewrite.ok()) {
    std::cerr << "rewind-replay tamper: " << rewrite.status().message() << "\n";
    return 1;
  }
  std::cout << "wrote " << cmd.out << ": tick " << cmd.edit.tick << " player " << cmd.edit.player
            << " input (" << rewrite->before_text << ") -> (" << rewrite->after_text
            << "), frames re-hashed\n";
  return 0;
}

int run(const replay_tool::ViewCommand& cmd) {
  const char* const kWhat = "rewind-replay view: ";
  replay::ReplayViewInfo info;
  Result<viewer::ViewBundle> bundle = replay::load_view_bundle(cmd.file, &info);
  if (!bundle.ok()) {
    std::cerr << kWhat << bundle.status().message() << "\n";
    return replay_tool::kExitCorrupt;
  }
  if (!info.problem.empty()) {
    std::cerr << kWhat << "viewing the first " << bundle->tick_count() << " ticks: " << info.problem
              << "\n";
  }
  if (!bundle->identity_matches) std::cerr << kWhat << bundle->identity_note << "\n";
  if (!cmd.desync.empty()) {
    if (Status s = replay::attach_desync_report(*bundle, cmd.desync); !s.ok()) {
      std::cerr << kWhat << s.message() << "\n";
      return replay_tool::kExitCorrupt;
    }
  }
  std::vector<uint8_t> bytes;
  if (Status s = viewer::encode_view_bundle(*bundle, bytes); !s.ok()) {
    std::cerr << kWhat << s.message() << "\n";
    return replay_tool::kExitCorrupt;
  }
  if (!cmd.bundle_out.empty()) {
    std::ofstream out(cmd.bundle_out, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) {
      std::cerr << kWhat << "cannot write '" << cmd.bundle_out << "'\n";
      return 1;
    }
    std::cout << "wrote " << cmd.bundle_out << ": " << bundle->game << ", "
              << bundle->setup.player_count << " players, " << bundle->tick_count() << " ticks"
              << (bundle->desync ? ", a desync report" : "") << "\n";
    return 0;
  }
  // The signals are waited for here; blocked before the server's thread
  // starts, so that thread never takes them.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  const std::string dir = cmd.viewer_dir.empty() ? server::default_viewer_dir() : cmd.viewer_dir;
  auto server = replay_tool::ViewServer::open(dir, std::move(bytes), cmd.address, cmd.port);
  if (!server.ok()) {
    std::cerr << kWhat << server.status().message() << "\n";
    return 1;
  }
  const std::string host =
      cmd.address.find(':') != std::string::npos ? "[" + cmd.address + "]" : cmd.address;
  const std::string url = "http://" + host + ":" + std::to_string((*server)->port()) + "/";
  std::cout << "viewing " << cmd.file << " (" << bundle->game << ", " << bundle->setup.player_count
            << " players, " << bundle->tick_count() << " ticks) at " << url
            << (bundle->desync ? "?desync=1" : "") << "\nopen it in a browser; Ctrl-C stops\n"
            << std::flush;
  int signal = 0;
  sigwait(&stop, &signal);
  (*server)->close();
  std::cout << "stopped\n";
  return 0;
}

}  // namespace

namespace rwd::tools {

int replay_main(int argc, const char* const* argv) {
  Result<replay_tool::Command> command = replay_tool::parse_command_line(argc, argv);
  if (!command.ok()) {
    std::cerr << "rewind-replay: " << command.status().message() << "\n";
    return cli::kExitUsage;
  }
  return std::visit([](const auto& cmd) { return run(cmd); }, *command);
}

}  // namespace rwd::tools
