// SPDX-License-Identifier: MIT
#pragma once
// What `rewind-replay inspect` shows: one pass over a replay, counting
// records without re-simulating anything.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// One keyframe record: the tick its state follows and its size.
struct KeyframeInfo {
  Tick tick = kNoTick;
  uint64_t state_bytes = 0;
};

/// Counts and ranges of a replay's valid prefix.
struct ReplaySummary {
  v1::ReplayHeader header;
  uint64_t tick_records = 0;
  Tick first_tick = kNoTick;  ///< kNoTick when there are no tick records
  Tick last_tick = kNoTick;
  /// Substituted inputs per player slot (index = player).
  std::vector<uint64_t> substituted_per_player;
  /// Ticks with at least one substituted input.
  uint64_t ticks_with_substitutions = 0;
  std::vector<KeyframeInfo> keyframes;
  std::optional<v1::ReplayEnd> end;
  /// Bytes of the file that were read and verified by their hashes.
  uint64_t valid_bytes = 0;
  /// Where and why reading stopped early, if it did (a torn last frame,
  /// damaged records, a newer format's records).
  std::optional<std::string> error;
  /// How the read ended: kComplete, kIncomplete (no end record), kTorn (the
  /// last frame cut short), kCorrupt, kUnsupported or kIoError.
  ReadState state = ReadState::kReading;
};

/// Summarizes the replay at `path`. Fails only when not even the header can
/// be read; a later break is reported in ReplaySummary::error.
Result<ReplaySummary> summarize_replay(const std::string& path);

}  // namespace rwd::replay
