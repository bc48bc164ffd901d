// SPDX-License-Identifier: MIT
#pragma once
// Command-line parsing for rewind-replay: one struct per subcommand.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "rewind/core/status.h"
#include "rewind/replay/replay_rewrite.h"

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

struct ViewCommand {
  std::string file;
  std::string desync;  ///< a server's desync_pP_tT_rR.bin to open, or empty
  std::string address = "127.0.0.1";
  uint16_t port = 8080;    ///< 0: any free port
  std::string viewer_dir;  ///< empty: the build's viewer
  std::string bundle_out;  ///< write the view bundle here and stop, serving nothing
};

using Command =
    std::variant<HelpRequest, VerifyCommand, InspectCommand, TamperCommand, ViewCommand>;

/// Parses argv. kInvalidArgument (exit 64) names the bad argument.
Result<Command> parse_command_line(int argc, const char* const* argv);

}  // namespace rwd::replay_tool
