// SPDX-License-Identifier: MIT
#include "rewind/server/metrics_text.h"

#include <charconv>
#include <string_view>
#include <type_traits>

namespace rwd::server {
namespace {

struct Metric {
  std::string_view name;  // without the rewind_ prefix
  std::string_view help;
  uint64_t MatchStats::*counter;  // null: a gauge read by `gauge`
  uint64_t (*gauge)(const MetricsSample&);
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

// Match ids are [A-Za-z0-9._-] (MatchConfig::validate), so they need no
// escaping inside the label's quotes.
void add_label(std::string& out, std::string_view name, const MetricsSample& match) {
  out.append("rewind_").append(name).append("{match=\"").append(match.match).append("\"");
}

void add_phase(std::string& out, std::span<const MetricsSample> matches) {
  add_header(out, "match_phase",
             "1 for the phase the match is in (lobby, running, closing, ended), 0 for the others.",
             "gauge");
  for (const MetricsSample& match : matches) {
    for (const MatchHost::Phase phase : {MatchHost::Phase::kLobby, MatchHost::Phase::kRunning,
                                         MatchHost::Phase::kClosing, MatchHost::Phase::kEnded}) {
      add_label(out, "match_phase", match);
      out.append(",phase=\"").append(phase_name(phase)).append("\"} ");
      out.append(phase == match.phase ? "1\n" : "0\n");
    }
  }
}

// One histogram family (`name`_bucket, _sum, _count) over every match.
void add_histogram(std::string& out, std::string_view name, std::string_view help,
                   std::span<const MetricsSample> matches,
                   const TickHistogram& (*of)(const MetricsSample&)) {
  add_header(out, name, help, "histogram");
  const std::string bucket = std::string(name) + "_bucket";
  const std::string sum = std::string(name) + "_sum";
  const std::string count = std::string(name) + "_count";
  for (const MetricsSample& match : matches) {
    const TickHistogram& ticks = of(match);
    uint64_t cumulative = 0;
    for (size_t b = 0; b < ticks.bucket_total(); ++b) {
      cumulative += ticks.bucket_count(b);
      add_label(out, bucket, match);
      out.append(",le=\"");
      if (b < ticks.bounds().size()) {
        add_seconds(out, ticks.bounds()[b]);
      } else {
        out.append("+Inf");
      }
      out.append("\"} ");
      add_number(out, cumulative);
      out.append("\n");
    }
    add_label(out, sum, match);
    out.append("} ");
    add_seconds(out, static_cast<int64_t>(ticks.sum_ns()));
    out.append("\n");
    add_label(out, count, match);
    out.append("} ");
    add_number(out, ticks.count());
    out.append("\n");
  }
}

void add_tick_time(std::string& out, std::span<const MetricsSample> matches) {
  add_histogram(out, "tick_seconds", "Wall time of each tick of the match's loop.", matches,
                [](const MetricsSample& m) -> const TickHistogram& { return m.tick_time; });
  add_header(out, "tick_seconds_max", "Longest tick of the match's loop so far.", "gauge");
  for (const MetricsSample& match : matches) {
    add_label(out, "tick_seconds_max", match);
    out.append("} ");
    add_seconds(out, match.tick_time.max_ns());
    out.append("\n");
  }
  add_histogram(out, "tick_lateness_seconds",
                "How long after its scheduled time each tick started.", matches,
                [](const MetricsSample& m) -> const TickHistogram& { return m.tick_lateness; });
}

void add_process(std::string& out, const ProcessSample& process) {
  auto gauge = [&out](std::string_view name, std::string_view help, std::string_view type,
                      auto value) {
    add_header(out, name, help, type);
    out.append("rewind_").append(name).append(" ");
    if constexpr (std::is_floating_point_v<decltype(value)>) {
      char text[32];
      const auto end = std::to_chars(text, text + sizeof text, value).ptr;
      out.append(text, end);
    } else {
      add_number(out, static_cast<uint64_t>(value));
    }
    out.append("\n");
  };
  gauge("tick_load",
        "Share of the match threads' time spent ticking over the last seconds (may pass 1 "
        "when the threads wait for a CPU).",
        "gauge", process.tick_load);
  gauge("tick_budget", "The tick load beyond which new matches are refused (--tick-budget).",
        "gauge", process.tick_budget);
  gauge("overloaded", "1 while new matches are refused: tick load over budget, or ticks slipping.",
        "gauge", process.overloaded ? 1 : 0);
  gauge("healthy", "0 while ticks slip persistently or stalled (Agones health pings stop).",
        "gauge", process.healthy ? 1 : 0);
  gauge("matches_refused_total", "Matches refused because the server was overloaded.", "counter",
        process.matches_refused);
}

void add_family(std::string& out, const Metric& metric, std::string_view type,
                std::span<const MetricsSample> matches) {
  add_header(out, metric.name, metric.help, type);
  for (const MetricsSample& match : matches) {
    add_label(out, metric.name, match);
    out.append("} ");
    add_number(out, metric.counter ? match.stats.*metric.counter : metric.gauge(match));
    out.append("\n");
  }
}

}  // namespace

std::string render_metrics(std::span<const MetricsSample> matches, const ProcessSample* process) {
  using S = MatchStats;
  const Metric gauges[] = {
      {"players_joined", "Player slots taken.", nullptr,
       [](const MetricsSample& m) { return uint64_t{m.stats.players_joined}; }},
      {"players_connected", "Joined players the server currently hears from.", nullptr,
       [](const MetricsSample& m) { return uint64_t{m.players_connected}; }},
      {"ticks_behind", "Whole periods the match's last tick started after it was due (0: on time).",
       nullptr, [](const MetricsSample& m) { return static_cast<uint64_t>(m.ticks_behind); }},
  };
  const Metric counters[] = {
      {"ticks_final_total", "Ticks made final (inputs fixed, broadcast with their checksum).",
       nullptr, [](const MetricsSample& m) { return static_cast<uint64_t>(m.stats.ticks_final); }},
      {"rollbacks_total", "Rollbacks on late input.", &S::rollbacks, nullptr},
      {"resimulated_ticks_total", "Ticks simulated again after a rollback.", &S::resimulated_ticks,
       nullptr},
      {"late_inputs_total",
       "Inputs that arrived after their tick was simulated, in time to be final.", &S::late_inputs,
       nullptr},
      {"substituted_inputs_total", "Inputs missing at their deadline and substituted.",
       &S::substituted_inputs, nullptr},
      {"rejected_inputs_total",
       "Inputs refused: for final ticks, too far ahead, conflicting, or claiming another slot.",
       &S::rejected_inputs, nullptr},
      {"rejected_packets_total",
       "Datagrams refused: undecodable, wrong version, unknown or spoofed connection.",
       &S::rejected_packets, nullptr},
      {"duplicate_packets_total", "Datagrams received twice.", &S::duplicate_packets, nullptr},
      {"relayed_inputs_total", "Inputs relayed to the other players.", &S::relayed_inputs, nullptr},
      {"desync_reports_total", "Desync reports received from clients.", &S::desync_reports,
       nullptr},
      {"resyncs_sent_total", "Resync snapshots sent to clients.", &S::resyncs_sent, nullptr},
      {"resync_snapshot_failures_total",
       "Resync snapshots that did not load on the server itself and were not sent.",
       &S::resync_snapshot_failures, nullptr},
      {"resyncs_refused_total", "Resync snapshots clients could not load.", &S::resyncs_refused,
       nullptr},
      {"desync_dumps_unreadable_total", "Desync reports whose client state could not be parsed.",
       &S::desync_dumps_unreadable, nullptr},
      {"desync_report_write_failures_total", "Desync reports that could not be written.",
       &S::desync_report_write_failures, nullptr},
      {"keyframe_load_failures_total",
       "Replay keyframes that did not load on the server and were left out.",
       &S::keyframe_load_failures, nullptr},
      {"packets_in_total", "Datagrams the match received.", &S::packets_in, nullptr},
      {"packets_out_total", "Datagrams the match sent.", &S::packets_out, nullptr},
      {"bytes_in_total", "Bytes the match received.", &S::bytes_in, nullptr},
      {"bytes_out_total", "Bytes the match sent.", &S::bytes_out, nullptr},
      {"secure_challenges_total", "Connection requests answered with a challenge.",
       &S::secure_challenges, nullptr},
      {"secure_sessions_total", "Secure handshakes completed.", &S::secure_sessions, nullptr},
      {"secure_refused_total",
       "Handshake packets refused (bad, expired or foreign tokens, wrong address).",
       &S::secure_refused, nullptr},
      {"secure_dropped_total",
       "Datagrams dropped before the match saw them (unauthenticated, replayed, not secure).",
       &S::secure_dropped, nullptr},
      {"address_cookies_total", "Tokenless: hellos answered with an address cookie.",
       &S::address_cookies, nullptr},
      {"cookies_refused_total",
       "Tokenless: malformed hellos and joins without a good address cookie, refused.",
       &S::cookies_refused, nullptr},
      {"udp_bytes_in_total", "Bytes of datagrams read from the match's UDP socket.",
       &S::udp_bytes_in, nullptr},
      {"udp_bytes_out_total", "Bytes of datagrams sent on the match's UDP socket.",
       &S::udp_bytes_out, nullptr},
      {"websocket_connections_total", "Browser connections the match has had over WebSocket.",
       &S::websocket_connections, nullptr},
      {"websocket_bytes_in_total", "Bytes of datagrams browsers sent the match over WebSocket.",
       &S::websocket_bytes_in, nullptr},
      {"websocket_bytes_out_total", "Bytes of datagrams the match sent browsers over WebSocket.",
       &S::websocket_bytes_out, nullptr},
      {"ticks_late_total",
       "Ticks that started a period or more after they were due (run back to back to catch up).",
       &S::ticks_late, nullptr},
      {"ticks_missed_total", "Ticks dropped from the schedule after the tick loop stalled.",
       &S::ticks_missed, nullptr},
  };
  std::string out;
  out.reserve(4096 + 6144 * matches.size());
  uint64_t live = 0;
  for (const MetricsSample& match : matches) live += match.phase != MatchHost::Phase::kEnded;
  add_header(out, "matches", "Matches this process hosts that have not ended.", "gauge");
  out.append("rewind_matches ");
  add_number(out, live);
  out.append("\n");
  if (process != nullptr) add_process(out, *process);
  for (const Metric& metric : gauges) add_family(out, metric, "gauge", matches);
  add_phase(out, matches);
  for (const Metric& metric : counters) add_family(out, metric, "counter", matches);
  add_tick_time(out, matches);
  return out;
}

}  // namespace rwd::server
