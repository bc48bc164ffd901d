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
};

/// Every metric with its # HELP and # TYPE lines, names prefixed `rewind_`:
/// `rewind_matches` (matches not ended) and, one series per match labelled
/// `match="<id>"`, counters (`_total`) for the match's and the secure
/// gateway's counts, gauges for the phase and the players, and the
/// `rewind_tick_seconds` histogram with its `rewind_tick_seconds_max`.
/// A family whose every match was dropped keeps its # HELP and # TYPE.
std::string render_metrics(std::span<const MetricsSample> matches);

}  // namespace rwd::server
