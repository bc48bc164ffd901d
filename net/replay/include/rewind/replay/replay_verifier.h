// SPDX-License-Identifier: MIT
#pragma once
// Headless re-simulation of a replay: the same game, setup and inputs must
// give the recorded checksum at every tick and the recorded state at every
// keyframe. The first divergence is reported with its tick and, when a
// keyframe allows, the bodies and fields that differ.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rewind/replay/replay_reader.h"
#include "rewind/sim/body_record.h"
#include "rewind/sim/tick.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// How much work verify_replay does after a divergence.
struct VerifyOptions {
  /// After a divergence, read ahead to the next keyframe to name fields.
  bool name_fields = true;
  /// At most this many field differences are kept (differences_total counts
  /// all of them).
  size_t max_differences = 256;
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
  /// Ticks re-simulated whose checksums matched (0 .. ticks_verified-1).
  uint64_t ticks_verified = 0;
  /// Checksum after the last verified tick.
  uint64_t last_checksum = 0;
  /// Keyframes whose state matched the re-simulation.
  uint64_t keyframes_verified = 0;
  /// The file holds its end record (the match finished and the writer closed).
  bool ended_cleanly = false;

  /// The first tick whose checksum or keyframe disagreed.
  std::optional<Tick> first_divergent_tick;
  DivergenceKind divergence_kind = DivergenceKind::kTickChecksum;
  uint64_t expected_checksum = 0;  ///< recorded
  uint64_t actual_checksum = 0;    ///< re-simulated
  /// The tick whose state `differences` compares (a keyframe at or after the
  /// divergent tick); unset when no keyframe allowed naming fields.
  std::optional<Tick> differences_tick;
  /// Recorded ("expected") against re-simulated ("actual") body fields.
  std::vector<sim::FieldDifference> differences;
  size_t differences_total = 0;
  /// How the fields were found, or why there are none.
  std::string differences_note;

  /// Where and why the file breaks (truncated, corrupt, out of order); the
  /// prefix before it was verified.
  std::optional<std::string> framing_error;
  /// Why re-simulation could not run or continue (unknown game, keyframe
  /// bytes the simulation refuses).
  std::optional<std::string> error;

  bool diverged() const { return first_divergent_tick.has_value(); }
  /// Everything in the file verified and the file is intact.
  bool ok() const { return !diverged() && !framing_error && !error; }
};

/// Re-simulates the replay at `path`.
VerifyReport verify_replay(const std::string& path, const VerifyOptions& options = {});
/// Re-simulates from an opened reader (positioned right after the header).
VerifyReport verify_replay(ReplayReader& reader, const VerifyOptions& options = {});

}  // namespace rwd::replay
