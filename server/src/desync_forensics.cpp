// SPDX-License-Identifier: MIT
#include "rewind/server/desync_forensics.h"

#include <cstdio>
#include <vector>

#include "host_log.h"
#include "rewind/core/body_field.h"

namespace rwd::server {

using detail::hex64;

DesyncFindings DesyncForensics::examine(const DesyncReportInfo& report,
                                        std::span<const uint8_t> dump,
                                        net::RollbackSession& session) const {
  DesyncFindings out;
  // The headline needs nothing but the report and the server's final-tick
  // history, so it is written whatever fails below.
  out.headline =
      "player " + std::to_string(report.player) + " desync at tick " + std::to_string(report.tick) +
      ": client " + hex64(report.client_checksum) + " server " +
      hex64(report.server_checksum.value_or(report.server_checksum_received)) +
      (report.server_checksum ? "" : " (as the client received it; no longer held here)");
  out.text = out.headline + "\n";

  // Name the bodies that differ: the client's state after the tick against
  // ours, when the ring still holds it.
  auto client_sim = session.load_snapshot(dump);
  std::vector<uint8_t> server_state;
  if (!client_sim.ok()) {
    out.dump_unreadable = true;
    out.problem = "client dump unreadable: " + client_sim.status().message();
  } else {
    if ((*client_sim)->checksum() != report.client_checksum) {
      out.text += "the client dump does not reproduce the client's checksum (" +
                  hex64((*client_sim)->checksum()) + ")\n";
    }
    if (!session.serialize_state_at(report.tick + 1, server_state)) {
      out.problem = "server state for tick " + std::to_string(report.tick) + " is no longer held";
    } else if (auto server_sim = session.load_snapshot(server_state); !server_sim.ok()) {
      out.problem = "server state unreadable: " + server_sim.status().message();
    } else {
      std::vector<rwd::BodyField> expected, actual;
      (*server_sim)->dump_bodies(expected);
      (*client_sim)->dump_bodies(actual);
      const auto differences = rwd::diff_body_fields(expected, actual);
      out.text += std::to_string(differences.size()) +
                  " differing fields (server = expected, client = actual):\n";
      char line[160];
      for (const rwd::FieldDifference& d : differences) {
        std::snprintf(line, sizeof(line), "  body %u %s: expected %.9g actual %.9g\n", d.body_index,
                      d.field.c_str(), d.expected, d.actual);
        out.text += line;
      }
    }
  }
  if (!out.problem.empty()) out.text += out.problem + "\n";

  if (!dir_.empty()) {
    const std::string base = dir_ + "/desync_p" + std::to_string(report.player) + "_t" +
                             std::to_string(report.tick) + "_r" + std::to_string(report.report_id);
    // The raw dump first: it is the evidence when nothing else could be read.
    const Status raw = env_.write_file(base + ".bin", dump);
    const Status text = env_.write_file(
        base + ".txt", std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(out.text.data()),
                                                out.text.size()));
    out.write_failed = !raw.ok() || !text.ok();
    if (text.ok()) out.stored_as = base + ".txt";
  }
  return out;
}

}  // namespace rwd::server
