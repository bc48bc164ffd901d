// SPDX-License-Identifier: MIT
#pragma once
// How rewind-replay shows reports: plain text for people, JSON for scripts.
#include <ostream>
#include <string>

#include "rewind/replay/replay_summary.h"
#include "rewind/replay/replay_verifier.h"

namespace rwd::replay_tool {

/// "verified N ticks (game crates, 4 players) checksum of last tick 0x..."
/// or "DIVERGED at tick T: expected 0x.. got 0x.." and the field list, or
/// "prefix verified: N ticks ..." and where the file breaks or that it is
/// incomplete, or "replay was recorded by ...; this build runs ...: not
/// re-simulated" and every difference.
void print_verify_text(const replay::VerifyReport& report, std::ostream& out);
/// The same report as one JSON object.
void print_verify_json(const std::string& file, const replay::VerifyReport& report,
                       std::ostream& out);
/// The inspect listing.
void print_summary(const std::string& file, const replay::ReplaySummary& summary,
                   std::ostream& out);

/// rewind-replay's exit codes (usage errors are cli::kExitUsage, 64). The
/// same numbers mean the same thing for verify and inspect.
inline constexpr int kExitVerified = 0;         ///< verified (inspect: intact) and complete
inline constexpr int kExitDiverged = 1;         ///< re-simulation disagrees with the recording
inline constexpr int kExitCorrupt = 2;          ///< damaged or out-of-order records, unreadable
inline constexpr int kExitVersionMismatch = 3;  ///< another engine, rules or world config
inline constexpr int kExitIncomplete = 4;       ///< no end record or a cut-short last frame

/// Exit code for a verify report: its outcome's code above.
int verify_exit_code(const replay::VerifyReport& report);
/// Exit code for inspect: 0 complete, 4 incomplete or torn, 3 newer format,
/// 2 corrupt or unreadable.
int inspect_exit_code(const replay::ReplaySummary& summary);

}  // namespace rwd::replay_tool
