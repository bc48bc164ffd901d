// SPDX-License-Identifier: MIT
#include "replay_cli.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "rewind/cli/flag_parser.h"
#include "rewind/core/player_input.h"

namespace rwd::replay_tool {
namespace {

constexpr const char* kProgram = "rewind-replay";

constexpr const char* kToolHelp =
    "usage: rewind-replay COMMAND [args]\n"
    "\n"
    "Checks and examines Rewind replay files.\n"
    "\n"
    "commands:\n"
    "  verify FILE [--json] [--ignore-version]\n"
    "                         re-simulate the match and compare every checksum\n"
    "  inspect FILE           print header, engine, world config, tick range,\n"
    "                         keyframes, substitutions, whether the file is complete\n"
    "  view FILE [--desync BIN] [--port N]\n"
    "                         watch the match in a browser: serves the viewer,\n"
    "                         which re-simulates it, and prints its address\n"
    "  tamper FILE ...        rewrite one input with valid framing (for tests)\n"
    "\n"
    "Run 'rewind-replay COMMAND --help' for a command's flags.\n"
    "exit codes:\n"
    "  0   verified and complete (inspect: intact and complete; tamper: written)\n"
    "  1   diverged (tamper: failed)\n"
    "  2   corrupt or unverifiable: a record fails its hash, does not parse or is\n"
    "      out of order, no complete header, the file cannot be read\n"
    "  3   recorded by another engine revision, game rules version or world\n"
    "      config, or for a game this build lacks: not re-simulated (inspect: a\n"
    "      newer replay format)\n"
    "  4   incomplete: no end record, or the last frame is cut short (a server\n"
    "      stopped or killed mid-match); the valid prefix verified\n"
    "  64  usage\n";

Status usage_error(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, message);
}

// Exactly one FILE positional.
Result<std::string> single_file(const std::vector<std::string>& positionals,
                                const std::string& command) {
  if (positionals.size() != 1) {
    return usage_error(command + ": expected one FILE, got " + std::to_string(positionals.size()) +
                       " (see " + kProgram + " " + command + " --help)");
  }
  return positionals.front();
}

// Optional integer flags are taken as strings so "not given" needs no
// sentinel value; the number is then held to the same strictness as
// FlagParser's own.
Result<std::optional<int64_t>> optional_int(const std::string& flag, const std::string& text,
                                            int64_t min, int64_t max) {
  if (text.empty()) return std::optional<int64_t>();
  // Decimal, or hex with 0x; never octal, so "-010" is not -8.
  const bool hex = text.rfind("0x", 0) == 0 || text.rfind("0X", 0) == 0;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, hex ? 16 : 10);
  if (errno != 0 || end == text.c_str() || *end != '\0') {
    return usage_error("--" + flag + ": expected an integer, got '" + text + "'");
  }
  if (v < min || v > max) {
    return usage_error("--" + flag + ": " + text + " is outside [" + std::to_string(min) + ", " +
                       std::to_string(max) + "]");
  }
  return std::optional<int64_t>(v);
}

Result<Command> parse_verify(int argc, const char* const* argv) {
  VerifyCommand cmd;
  cli::FlagParser flags(
      std::string(kProgram) + " verify", "rewind-replay verify FILE [--json] [--ignore-version]",
      "Re-simulates the replay headless and compares the checksum of every tick and the "
      "state of every keyframe. First it compares the engine, sim revision, game rules "
      "version and world config the replay recorded with this build's; if any differs it "
      "names both sides and does not re-simulate.\n"
      "exit codes: 0 verified and complete; 1 diverged (prints the tick and the differing "
      "fields); 2 corrupt or unverifiable (damaged, unparsable or out-of-order records; the "
      "valid prefix is still verified); 3 recorded by another engine revision, rules version "
      "or world config, not re-simulated; 4 incomplete: no end record or a cut-short last "
      "frame, the whole valid prefix verified; 64 usage");
  flags.add_bool("json", &cmd.json, "print the report as JSON");
  flags.add_bool("ignore-version", &cmd.ignore_version,
                 "re-simulate even if the replay was recorded by another engine revision, "
                 "rules version or world config (the report still names the differences)");
  std::vector<std::string> positionals;
  if (Status s = flags.parse(argc, argv, 2, &positionals); !s.ok()) return s;
  if (flags.help_requested()) return Command(HelpRequest{flags.help_text()});
  Result<std::string> file = single_file(positionals, "verify");
  if (!file.ok()) return file.status();
  cmd.file = *file;
  return Command(cmd);
}

Result<Command> parse_inspect(int argc, const char* const* argv) {
  InspectCommand cmd;
  cli::FlagParser flags(
      std::string(kProgram) + " inspect", "rewind-replay inspect FILE",
      "Prints the header, the engine, sim revision, game rules version and world config "
      "that recorded it (and whether this build runs the same), tick range, record counts, "
      "substituted inputs per player, keyframes and whether the file is complete, without "
      "re-simulating.\n"
      "exit codes: 0 intact and complete; 2 corrupt (the valid prefix is still summarized); "
      "3 a newer replay format (only its header is shown); 4 incomplete: no end record or a "
      "cut-short last frame; 64 usage");
  std::vector<std::string> positionals;
  if (Status s = flags.parse(argc, argv, 2, &positionals); !s.ok()) return s;
  if (flags.help_requested()) return Command(HelpRequest{flags.help_text()});
  Result<std::string> file = single_file(positionals, "inspect");
  if (!file.ok()) return file.status();
  cmd.file = *file;
  return Command(cmd);
}

Result<Command> parse_tamper(int argc, const char* const* argv) {
  TamperCommand cmd;
  int64_t tick = -1;
  int64_t player = -1;
  std::string set;
  std::string axis_x;
  std::string axis_y;
  std::string buttons;
  cli::FlagParser flags(std::string(kProgram) + " tamper",
                        "rewind-replay tamper FILE --tick T --player P --set FIELD=V[,FIELD=V...] "
                        "--out OUT",
                        "Writes a copy of FILE with one recorded input changed and every frame "
                        "hashed correctly: a consistent forgery that only re-simulation catches "
                        "(used to test 'verify'). FIELD is a field of the game's input (its "
                        "InputSpec; the built-in games: axis_x, axis_y, buttons).\nexit codes: "
                        "0 written, 1 failed, 64 usage");
  flags.add_int("tick", &tick, 0, std::numeric_limits<int32_t>::max(), "tick to change (required)");
  flags.add_int("player", &player, 0, 63, "player slot to change (required)");
  flags.add_string("set", &set, "fields to change, FIELD=VALUE separated by commas");
  flags.add_string("axis-x", &axis_x, "the same as --set axis_x=V");
  flags.add_string("axis-y", &axis_y, "the same as --set axis_y=V");
  flags.add_string("buttons", &buttons, "the same as --set buttons=B (decimal or 0x hex)");
  flags.add_string("out", &cmd.out, "file to write (required)");
  flags.add_bool("overwrite", &cmd.overwrite, "replace OUT if it exists");
  std::vector<std::string> positionals;
  if (Status s = flags.parse(argc, argv, 2, &positionals); !s.ok()) return s;
  if (flags.help_requested()) return Command(HelpRequest{flags.help_text()});
  Result<std::string> file = single_file(positionals, "tamper");
  if (!file.ok()) return file.status();
  cmd.file = *file;
  if (tick < 0) return usage_error("tamper: --tick is required");
  if (player < 0) return usage_error("tamper: --player is required");
  if (cmd.out.empty()) return usage_error("tamper: --out is required");
  cmd.edit.tick = static_cast<Tick>(tick);
  cmd.edit.player = static_cast<uint32_t>(player);

  // The field's range is the game's, checked when the replay is read.
  constexpr int64_t kAny = std::numeric_limits<uint32_t>::max();
  size_t at = 0;
  while (at < set.size()) {
    const size_t comma = std::min(set.find(',', at), set.size());
    const std::string item = set.substr(at, comma - at);
    at = comma + 1;
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      return usage_error("--set: expected FIELD=VALUE, got '" + item + "'");
    }
    Result<std::optional<int64_t>> v =
        optional_int("set " + item.substr(0, eq), item.substr(eq + 1), -kAny, kAny);
    if (!v.ok()) return v.status();
    if (!*v) return usage_error("--set: no value for '" + item.substr(0, eq) + "'");
    cmd.edit.fields.push_back({item.substr(0, eq), **v});
  }
  for (const auto& [flag, text, field] :
       {std::tuple{"axis-x", &axis_x, "axis_x"}, std::tuple{"axis-y", &axis_y, "axis_y"},
        std::tuple{"buttons", &buttons, "buttons"}}) {
    Result<std::optional<int64_t>> v = optional_int(flag, *text, -kAny, kAny);
    if (!v.ok()) return v.status();
    if (*v) cmd.edit.fields.push_back({field, **v});
  }
  if (cmd.edit.fields.empty()) {
    return usage_error("tamper: give --set FIELD=VALUE (or --axis-x, --axis-y, --buttons)");
  }
  return Command(cmd);
}

Result<Command> parse_view(int argc, const char* const* argv) {
  ViewCommand cmd;
  int64_t port = cmd.port;
  cli::FlagParser flags(
      std::string(kProgram) + " view",
      "rewind-replay view FILE [--desync DESYNC.bin] [--address A] [--port N] "
      "[--viewer-dir DIR] [--bundle-out PATH]",
      "Serves the browser viewer for the replay FILE (or a view bundle --bundle-out wrote) and "
      "prints its address; open it in a "
      "browser. The viewer re-simulates the match in WebAssembly and compares every tick's "
      "checksum with the recorded one: play, pause, step, scrub to any tick, speed, camera, "
      "debug-draw overlays, stats. With --desync (a server's desync_pP_tT_rR.bin, its .txt "
      "beside it) the viewer opens at that tick and draws the bodies whose fields differ "
      "from the client's state in red, listing both values. Runs until interrupted "
      "(Ctrl-C). A damaged or cut-short replay is viewed up to its last whole tick.\n"
      "exit codes: 0 served and stopped, or the bundle written; 1 the viewer could not be "
      "served (not built, port taken); 2 the replay or desync report cannot be read; 64 usage");
  flags.add_string("desync", &cmd.desync, "a desync report's .bin to open the viewer at");
  flags.add_string("address", &cmd.address, "address to listen on (default 127.0.0.1)");
  flags.add_int("port", &port, 0, 65535, "port to listen on; 0 picks a free one (default 8080)");
  flags.add_string("viewer-dir", &cmd.viewer_dir,
                   "the built viewer's files (default: this build's viewer_web)");
  flags.add_string("bundle-out", &cmd.bundle_out,
                   "write the view bundle (what the viewer loads) to PATH and stop");
  std::vector<std::string> positionals;
  if (Status s = flags.parse(argc, argv, 2, &positionals); !s.ok()) return s;
  if (flags.help_requested()) return Command(HelpRequest{flags.help_text()});
  Result<std::string> file = single_file(positionals, "view");
  if (!file.ok()) return file.status();
  cmd.file = *file;
  cmd.port = static_cast<uint16_t>(port);
  return Command(cmd);
}

}  // namespace

Result<Command> parse_command_line(int argc, const char* const* argv) {
  if (argc < 2) return usage_error(std::string("missing command\n\n") + kToolHelp);
  const std::string_view command = argv[1];
  if (command == "--help" || command == "-h" || command == "help") {
    return Command(HelpRequest{kToolHelp});
  }
  if (command == "verify") return parse_verify(argc, argv);
  if (command == "inspect") return parse_inspect(argc, argv);
  if (command == "tamper") return parse_tamper(argc, argv);
  if (command == "view") return parse_view(argc, argv);
  return usage_error("unknown command '" + std::string(command) + "' (see " + kProgram +
                     " --help)");
}

}  // namespace rwd::replay_tool
