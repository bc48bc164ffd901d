// SPDX-License-Identifier: MIT
#pragma once
// Command-line parsing for rewind-replay: one struct per subcommand.
#include <optional>
#include <string>
#include <variant>

#include "rewind/replay/replay_rewrite.h"
#include "rewind/sim/status.h"

namespace rwd::replay_tool {

/// --help anywhere: print `text` and exit 0.
struct HelpRequest {
  std::string text;
};

struct VerifyCommand {
  std::string file;
  bool json = false;
  bool ignore_version = false;
};

struct InspectCommand {
  std::string file;
};

struct TamperCommand {
  std::string file;
  std::string out;
  replay::InputEdit edit;
  bool overwrite = false;
};

using Command = std::variant<HelpRequest, VerifyCommand, InspectCommand, TamperCommand>;

/// Parses argv. kInvalidArgument (exit 64) names the bad argument.
Result<Command> parse_command_line(int argc, const char* const* argv);

}  // namespace rwd::replay_tool
