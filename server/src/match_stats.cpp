// SPDX-License-Identifier: MIT
#include "rewind/server/match_stats.h"

#include <cstdio>
#include <sstream>

namespace rwd::server {

std::string MatchStats::to_json() const {
  char checksum[19];
  std::snprintf(checksum, sizeof(checksum), "0x%016llx",
                static_cast<unsigned long long>(final_checksum));
  std::ostringstream out;
  out << "{\"ticks_final\":" << ticks_final << ",\"rollbacks\":" << rollbacks
      << ",\"resimulated_ticks\":" << resimulated_ticks << ",\"late_inputs\":" << late_inputs
      << ",\"substituted_inputs\":" << substituted_inputs
      << ",\"rejected_inputs\":" << rejected_inputs << ",\"rejected_packets\":" << rejected_packets
      << ",\"duplicate_packets\":" << duplicate_packets << ",\"relayed_inputs\":" << relayed_inputs
      << ",\"desync_reports\":" << desync_reports << ",\"resyncs_sent\":" << resyncs_sent
      << ",\"packets_in\":" << packets_in << ",\"packets_out\":" << packets_out
      << ",\"bytes_in\":" << bytes_in << ",\"bytes_out\":" << bytes_out
      << ",\"players_joined\":" << players_joined << ",\"last_final_tick\":" << last_final_tick
      << ",\"final_checksum\":\"" << checksum << "\",\"duration_s\":" << duration_s
      << ",\"end_reason\":\"" << end_reason << "\"}";
  return out.str();
}

}  // namespace rwd::server
