// SPDX-License-Identifier: MIT
#pragma once
// The server's state as Prometheus text exposition (format 0.0.4), the
// body of GET /metrics.
#include <cstdint>
#include <span>
#include <string>

#include "rewind/server/match_host.h"
#include "rewind/server/match_stats.h"
#include "rewind/server/tick_histogram.h"

namespace rwd::server {

/// What one scrape reports of one match.
struct MetricsSample {
  std::string match;  ///< MatchConfig::match_id, the `match` label
  MatchStats stats;
  MatchHost::Phase phase = MatchHost::Phase::kLobby;
  uint32_t players_connected = 0;
  TickHistogram tick_time;
  /// How late each tick started (TickSchedule); the late and dropped ticks
  /// are in stats.
  TickHistogram tick_lateness{TickHistogram::kLatenessBoundsNs};
  /// Whole periods the last tick started after it was due.
  int64_t ticks_behind = 0;
};

/// What one scrape reports of the whole process (LoadMonitor).
struct ProcessSample {
  double tick_load = 0.0;        ///< share of the match threads' time spent ticking, recent
  double tick_budget = 0.0;      ///< the share beyond which new matches are refused
  bool overloaded = false;       ///< new matches are refused now
  bool healthy = true;           ///< ticks keep their pace (Agones health pings go on)
  uint64_t matches_refused = 0;  ///< allocations refused as overloaded, so far
};

/// Every metric with its # HELP and # TYPE lines, names prefixed `rewind_`:
/// `rewind_matches` (matches not ended) and, one series per match labelled
/// `match="<id>"`, counters (`_total`) for the match's and the secure
/// gateway's counts, gauges for the phase and the players, and the
/// `rewind_tick_seconds` histogram with its `rewind_tick_seconds_max`, the
/// `rewind_tick_lateness_seconds` histogram with `rewind_ticks_behind`.
/// With `process`, the process's unlabelled `rewind_tick_load`,
/// `rewind_tick_budget`, `rewind_overloaded`, `rewind_healthy` and
/// `rewind_matches_refused_total` too. A family whose every match was
/// dropped keeps its # HELP and # TYPE.
std::string render_metrics(std::span<const MetricsSample> matches,
                           const ProcessSample* process = nullptr);

}  // namespace rwd::server
