// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_summary.h"

#include "rewind/replay/replay_reader.h"

namespace rwd::replay {

Result<ReplaySummary> summarize_replay(const std::string& path) {
  Result<ReplayReader> reader = ReplayReader::open(path);
  if (!reader.ok()) return reader.status();
  ReplaySummary summary;
  summary.header = reader->header();
  summary.substituted_per_player.assign(summary.header.player_count(), 0);
  while (true) {
    Result<std::optional<v1::ReplayRecord>> record = reader->next();
    if (!record.ok()) {
      summary.error = record.status().message();
      break;
    }
    if (!record->has_value()) break;
    const v1::ReplayRecord& r = **record;
    if (r.has_tick()) {
      const v1::ReplayTick& t = r.tick();
      if (summary.tick_records == 0) summary.first_tick = t.tick();
      summary.last_tick = t.tick();
      ++summary.tick_records;
      const uint64_t mask = t.substituted_mask();
      if (mask != 0) ++summary.ticks_with_substitutions;
      for (uint32_t p = 0; p < summary.header.player_count(); ++p) {
        if ((mask >> p) & 1u) ++summary.substituted_per_player[p];
      }
    } else if (r.has_keyframe()) {
      summary.keyframes.push_back({r.keyframe().tick(), r.keyframe().state().size()});
    } else if (r.has_end()) {
      summary.end = r.end();
    }
  }
  summary.valid_bytes = reader->offset();
  summary.state = reader->state();
  return summary;
}

}  // namespace rwd::replay
