// SPDX-License-Identifier: MIT
#include "rewind/server/metrics_text.h"

#include <charconv>
#include <string_view>

namespace rwd::server {
namespace {

struct Metric {
  std::string_view name;  // without the rewind_ prefix
  std::string_view help;
  uint64_t value;
};

void add_header(std::string& out, std::string_view name, std::string_view help,
                std::string_view type) {
  out.append("# HELP rewind_").append(name).append(" ").append(help).append("\n");
  out.append("# TYPE rewind_").append(name).append(" ").append(type).append("\n");
}

void add_number(std::string& out, uint64_t value) {
  char text[24];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  out.append(text, end);
}

// The shortest text that reads back as the same double, in the style of
// the Go client's bucket labels (0.0001, 2.5e-05); never locale-dependent.
void add_seconds(std::string& out, int64_t ns) {
  char text[32];
  const double seconds = static_cast<double>(ns) / 1e9;
  const auto end = std::to_chars(text, text + sizeof text, seconds, std::chars_format::general).ptr;
  out.append(text, end);
}

void add_sample(std::string& out, std::string_view name, uint64_t value) {
  out.append("rewind_").append(name).append(" ");
  add_number(out, value);
  out.append("\n");
}

void add_family(std::string& out, const Metric& metric, std::string_view type) {
  add_header(out, metric.name, metric.help, type);
  add_sample(out, metric.name, metric.value);
}

const char* phase_name(MatchHost::Phase phase) {
  switch (phase) {
    case MatchHost::Phase::kLobby:
      return "lobby";
    case MatchHost::Phase::kRunning:
      return "running";
    case MatchHost::Phase::kClosing:
      return "closing";
    case MatchHost::Phase::kEnded:
      break;
  }
  return "ended";
}

void add_phase(std::string& out, MatchHost::Phase current) {
  add_header(out, "match_phase",
             "1 for the phase the match is in (lobby, running, closing, ended), 0 for the others.",
             "gauge");
  for (const MatchHost::Phase phase : {MatchHost::Phase::kLobby, MatchHost::Phase::kRunning,
                                       MatchHost::Phase::kClosing, MatchHost::Phase::kEnded}) {
    out.append("rewind_match_phase{phase=\"").append(phase_name(phase)).append("\"} ");
    out.append(phase == current ? "1\n" : "0\n");
  }
}

void add_tick_time(std::string& out, const TickHistogram& ticks) {
  add_header(out, "tick_seconds", "Wall time of each tick of the server's loop.", "histogram");
  uint64_t cumulative = 0;
  for (size_t bucket = 0; bucket < TickHistogram::bucket_total(); ++bucket) {
    cumulative += ticks.bucket_count(bucket);
    out.append("rewind_tick_seconds_bucket{le=\"");
    if (bucket < TickHistogram::kBoundsNs.size()) {
      add_seconds(out, TickHistogram::kBoundsNs[bucket]);
    } else {
      out.append("+Inf");
    }
    out.append("\"} ");
    add_number(out, cumulative);
    out.append("\n");
  }
  out.append("rewind_tick_seconds_sum ");
  add_seconds(out, static_cast<int64_t>(ticks.sum_ns()));
  out.append("\nrewind_tick_seconds_count ");
  add_number(out, ticks.count());
  out.append("\n");
  add_header(out, "tick_seconds_max", "Longest tick of the server's loop so far.", "gauge");
  out.append("rewind_tick_seconds_max ");
  add_seconds(out, ticks.max_ns());
  out.append("\n");
}

}  // namespace

std::string render_metrics(const MetricsSample& sample) {
  const MatchStats& s = sample.stats;
  const Metric gauges[] = {
      {"matches", "Matches this process hosts.", 1},
      {"players_joined", "Player slots taken.", s.players_joined},
      {"players_connected", "Joined players the server currently hears from.",
       sample.players_connected},
  };
  const Metric counters[] = {
      {"ticks_final_total", "Ticks made final (inputs fixed, broadcast with their checksum).",
       static_cast<uint64_t>(s.ticks_final)},
      {"rollbacks_total", "Rollbacks on late input.", s.rollbacks},
      {"resimulated_ticks_total", "Ticks simulated again after a rollback.", s.resimulated_ticks},
      {"late_inputs_total",
       "Inputs that arrived after their tick was simulated, in time to be final.", s.late_inputs},
      {"substituted_inputs_total", "Inputs missing at their deadline and substituted.",
       s.substituted_inputs},
      {"rejected_inputs_total",
       "Inputs refused: for final ticks, too far ahead, conflicting, or claiming another slot.",
       s.rejected_inputs},
      {"rejected_packets_total",
       "Datagrams refused: undecodable, wrong version, unknown or spoofed connection.",
       s.rejected_packets},
      {"duplicate_packets_total", "Datagrams received twice.", s.duplicate_packets},
      {"relayed_inputs_total", "Inputs relayed to the other players.", s.relayed_inputs},
      {"desync_reports_total", "Desync reports received from clients.", s.desync_reports},
      {"resyncs_sent_total", "Resync snapshots sent to clients.", s.resyncs_sent},
      {"resync_snapshot_failures_total",
       "Resync snapshots that did not load on the server itself and were not sent.",
       s.resync_snapshot_failures},
      {"resyncs_refused_total", "Resync snapshots clients could not load.", s.resyncs_refused},
      {"desync_dumps_unreadable_total", "Desync reports whose client state could not be parsed.",
       s.desync_dumps_unreadable},
      {"desync_report_write_failures_total", "Desync reports that could not be written.",
       s.desync_report_write_failures},
      {"keyframe_load_failures_total",
       "Replay keyframes that did not load on the server and were left out.",
       s.keyframe_load_failures},
      {"packets_in_total", "Datagrams the match received.", s.packets_in},
      {"packets_out_total", "Datagrams the match sent.", s.packets_out},
      {"bytes_in_total", "Bytes the match received.", s.bytes_in},
      {"bytes_out_total", "Bytes the match sent.", s.bytes_out},
      {"secure_challenges_total", "Connection requests answered with a challenge.",
       s.secure_challenges},
      {"secure_sessions_total", "Secure handshakes completed.", s.secure_sessions},
      {"secure_refused_total",
       "Handshake packets refused (bad, expired or foreign tokens, wrong address).",
       s.secure_refused},
      {"secure_dropped_total",
       "Datagrams dropped before the match saw them (unauthenticated, replayed, not secure).",
       s.secure_dropped},
  };
  std::string out;
  out.reserve(8192);
  for (const Metric& metric : gauges) add_family(out, metric, "gauge");
  add_phase(out, sample.phase);
  for (const Metric& metric : counters) add_family(out, metric, "counter");
  add_tick_time(out, sample.tick_time);
  return out;
}

}  // namespace rwd::server
