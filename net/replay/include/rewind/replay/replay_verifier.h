// SPDX-License-Identifier: MIT
#pragma once
// Headless re-simulation of a replay: the same game, setup and inputs must
// give the recorded checksum at every tick and the recorded state at every
// keyframe. The first divergence is reported with its tick and, when a
// keyframe allows, the bodies and fields that differ. A replay recorded by
// another engine revision, rules version or world config is not
// re-simulated (unless asked): a divergence would say nothing about the
// match.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/tick.h"
#include "rewind/replay/engine_identity.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// How much work verify_replay does after a divergence.
struct VerifyOptions {
  /// After a divergence, read ahead to the next keyframe to name fields.
  bool name_fields = true;
  /// At most this many field differences are kept (differences_total counts
  /// all of them).
  size_t max_differences = 256;
  /// Re-simulate even when the recorded engine identity differs from this
  /// build's; the report still holds the differences.
  bool ignore_version = false;
};

/// What a verification came to, most serious first.
enum class VerifyOutcome : uint8_t {
  kVerified,         ///< every tick and keyframe matched, and the file ends with its end record
  kDiverged,         ///< a tick checksum or keyframe state disagreed
  kCorrupt,          ///< damaged or out-of-order records, or re-simulation could not run
  kVersionMismatch,  ///< recorded by another engine, rules or world config: not re-simulated
  kIncomplete,       ///< the whole valid prefix verified, but there is no end record
};

/// What disagreed first.
enum class DivergenceKind : uint8_t {
  kTickChecksum,   ///< the checksum after stepping a tick
  kKeyframeState,  ///< a keyframe's state against the re-simulated state
};

/// The outcome of verify_replay. Exactly one tick is named when anything
/// diverged; fields are named when a keyframe allows it.
struct VerifyReport {
  /// The header, when the file had a readable one.
  std::optional<v1::ReplayHeader> header;
  /// The recorded engine identity against this build's (with the header).
  std::optional<VersionCheck> versions;
  /// True once re-simulation started: false when the versions differ and
  /// VerifyOptions::ignore_version is off, or when the game cannot be made.
  bool resimulated = false;
  /// Tick records in the file's valid prefix, simulated or not.
  uint64_t tick_records = 0;
  /// Ticks re-simulated whose checksums matched (0 .. ticks_verified-1).
  uint64_t ticks_verified = 0;
  /// Checksum after the last verified tick.
  uint64_t last_checksum = 0;
  /// Keyframes whose state matched the re-simulation.
  uint64_t keyframes_verified = 0;
  /// The file holds its end record (the match finished and the writer closed).
  bool ended_cleanly = false;
  /// How reading the file ended (the rest of the file is read even when
  /// re-simulation stops or is skipped): kComplete, kIncomplete and kTorn
  /// mean every whole frame was read; kCorrupt, kUnsupported or kIoError
  /// that reading stopped there.
  ReadState file_state = ReadState::kReading;

  /// The first tick whose checksum or keyframe disagreed.
  std::optional<Tick> first_divergent_tick;
  DivergenceKind divergence_kind = DivergenceKind::kTickChecksum;
  uint64_t expected_checksum = 0;  ///< recorded
  uint64_t actual_checksum = 0;    ///< re-simulated
  /// The tick whose state `differences` compares (a keyframe at or after the
  /// divergent tick); unset when no keyframe allowed naming fields.
  std::optional<Tick> differences_tick;
  /// Recorded ("expected") against re-simulated ("actual") body fields.
  std::vector<rwd::FieldDifference> differences;
  size_t differences_total = 0;
  /// How the fields were found, or why there are none.
  std::string differences_note;

  /// Where the file ends inside a frame (a write cut short, file_state
  /// kTorn); the prefix before it was verified.
  std::optional<std::string> torn_frame;
  /// Where and why the file breaks (damaged, unparsable or out-of-order
  /// records, read errors); the prefix before it was verified.
  std::optional<std::string> framing_error;
  /// Why re-simulation could not run or continue (unknown game, keyframe
  /// bytes the simulation refuses, records of a newer format).
  std::optional<std::string> error;

  bool diverged() const { return first_divergent_tick.has_value(); }
  /// The recorded identity differs from this build's and nothing was
  /// re-simulated.
  bool version_skipped() const { return versions && !versions->matches() && !resimulated; }
  VerifyOutcome outcome() const;
  /// Everything in the file verified and the file is complete.
  bool ok() const { return outcome() == VerifyOutcome::kVerified; }
};

/// "verified", "diverged", "corrupt", "version_mismatch", "incomplete".
const char* outcome_name(VerifyOutcome outcome);

/// Re-simulates the replay at `path`.
VerifyReport verify_replay(const std::string& path, const VerifyOptions& options = {});
/// Re-simulates from an opened reader (positioned right after the header).
VerifyReport verify_replay(ReplayReader& reader, const VerifyOptions& options = {});

}  // namespace rwd::replay
