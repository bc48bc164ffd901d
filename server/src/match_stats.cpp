// SPDX-License-Identifier: MIT
#include "rewind/server/match_stats.h"

#include <cstdio>
#include <sstream>

namespace rwd::server {
namespace {

std::string hex64(uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof(text), "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace

std::string MatchStats::to_json() const {
  std::ostringstream out;
  out << "{\"ticks_final\":" << ticks_final << ",\"rollbacks\":" << rollbacks
      << ",\"resimulated_ticks\":" << resimulated_ticks << ",\"late_inputs\":" << late_inputs
      << ",\"substituted_inputs\":" << substituted_inputs
      << ",\"rejected_inputs\":" << rejected_inputs << ",\"rejected_packets\":" << rejected_packets
      << ",\"duplicate_packets\":" << duplicate_packets << ",\"relayed_inputs\":" << relayed_inputs
      << ",\"desync_reports\":" << desync_reports << ",\"resyncs_sent\":" << resyncs_sent
      << ",\"resync_snapshot_failures\":" << resync_snapshot_failures
      << ",\"resyncs_refused\":" << resyncs_refused
      << ",\"desync_dumps_unreadable\":" << desync_dumps_unreadable
      << ",\"desync_report_write_failures\":" << desync_report_write_failures
      << ",\"keyframe_load_failures\":" << keyframe_load_failures
      << ",\"packets_in\":" << packets_in << ",\"packets_out\":" << packets_out
      << ",\"bytes_in\":" << bytes_in << ",\"bytes_out\":" << bytes_out
      << ",\"players_joined\":" << players_joined << ",\"last_final_tick\":" << last_final_tick
      << ",\"final_checksum\":\"" << hex64(final_checksum) << "\",\"duration_s\":" << duration_s
      << ",\"end_reason\":\"" << end_reason << "\",\"secure\":" << (secure ? "true" : "false")
      << ",\"secure_challenges\":" << secure_challenges
      << ",\"secure_sessions\":" << secure_sessions << ",\"secure_refused\":" << secure_refused
      << ",\"secure_dropped\":" << secure_dropped << ",\"address_cookies\":" << address_cookies
      << ",\"cookies_refused\":" << cookies_refused << ",\"udp_bytes_in\":" << udp_bytes_in
      << ",\"udp_bytes_out\":" << udp_bytes_out
      << ",\"websocket_connections\":" << websocket_connections
      << ",\"websocket_bytes_in\":" << websocket_bytes_in
      << ",\"websocket_bytes_out\":" << websocket_bytes_out << ",\"ticks_late\":" << ticks_late
      << ",\"ticks_missed\":" << ticks_missed << ",\"tick_lateness_max_s\":" << tick_lateness_max_s
      << "}";
  return out.str();
}

std::string MatchStats::to_text() const {
  std::ostringstream out;
  out << "match summary: " << ticks_final << " final ticks (last checksum " << hex64(final_checksum)
      << "), " << players_joined << " players, " << duration_s << " s, ended: " << end_reason
      << "; rollbacks " << rollbacks << " (" << resimulated_ticks
      << " ticks re-simulated), late inputs " << late_inputs << ", substituted "
      << substituted_inputs << ", rejected inputs " << rejected_inputs << ", rejected packets "
      << rejected_packets << "; desync reports " << desync_reports << " ("
      << desync_dumps_unreadable << " unreadable dumps, " << desync_report_write_failures
      << " not written), resyncs sent " << resyncs_sent << " (" << resync_snapshot_failures
      << " snapshots did not load here, " << resyncs_refused << " refused by clients)"
      << ", keyframes that did not load " << keyframe_load_failures;
  if (secure) {
    out << "; secure: " << secure_challenges << " challenges, " << secure_sessions << " sessions, "
        << secure_refused << " handshakes refused, " << secure_dropped << " datagrams dropped";
  } else {
    out << "; tokenless: " << address_cookies << " address cookies, " << cookies_refused
        << " refused";
  }
  out << "; ticks late " << ticks_late << ", missed " << ticks_missed << " (latest start "
      << tick_lateness_max_s * 1e3 << " ms after its time)";
  return out.str();
}

std::string MatchStats::problems() const {
  std::string out;
  auto add = [&out](uint64_t count, const char* what) {
    if (count == 0) return;
    if (!out.empty()) out += "; ";
    out += std::to_string(count) + " " + what;
  };
  add(resync_snapshot_failures, "resync snapshots did not load on the server and were not sent");
  add(resyncs_refused, "resync snapshots were refused by clients");
  add(desync_dumps_unreadable, "desync reports had an unreadable client dump");
  add(desync_report_write_failures, "desync reports could not be written");
  add(keyframe_load_failures, "replay keyframes did not load on the server and were left out");
  // Either way the clients saw the server's clock stutter: late ticks come
  // in bursts, dropped ones leave the match's clock behind the wall clock.
  // The usual cause is a process short of CPU (see --tick-budget).
  add(ticks_late, "ticks started a period or more late (run back to back to catch up)");
  add(ticks_missed, "ticks were dropped after the tick loop stalled");
  return out;
}

}  // namespace rwd::server
