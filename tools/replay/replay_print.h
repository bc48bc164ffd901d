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
/// "prefix verified: N ticks ..." and where the file breaks.
void print_verify_text(const replay::VerifyReport& report, std::ostream& out);
/// The same report as one JSON object.
void print_verify_json(const std::string& file, const replay::VerifyReport& report,
                       std::ostream& out);
/// The inspect listing.
void print_summary(const std::string& file, const replay::ReplaySummary& summary,
                   std::ostream& out);

/// Exit code for a verify report: 1 diverged, 2 broken or unverifiable, else 0.
int verify_exit_code(const replay::VerifyReport& report);

}  // namespace rwd::replay_tool
