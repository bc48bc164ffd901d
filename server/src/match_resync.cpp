// SPDX-License-Identifier: MIT
// The match host's desync path: reassembling a client's desync report,
// handing it to DesyncForensics (the bodies and fields that differ, stored),
// and the resync episode that follows: a snapshot checked to load here before it
// goes out, resent in chunks until acknowledged, replaced when a client
// refuses it.
#include <algorithm>

#include "host_log.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/server/match_host.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::log_warning;
using detail::printable;
using detail::worth_logging;

constexpr auto kResyncMinInterval = std::chrono::milliseconds(250);
constexpr auto kReportMinInterval = std::chrono::seconds(2);
constexpr uint32_t kMaxReportsPerPeer = 8;

std::span<const uint8_t> bytes_of(const std::string& chunk) {
  return {reinterpret_cast<const uint8_t*>(chunk.data()), chunk.size()};
}

}  // namespace

void MatchHost::handle_desync(Peer& peer, uint32_t player, const v1::DesyncReport& report,
                              TimePoint now) {
  if (report.tick() > next_final_ - 1 || report.tick() < 0) {
    ++stats_.rejected_packets;  // only final ticks can desync
    return;
  }
  for (uint32_t id : peer.handled_reports) {
    if (id == report.report_id()) {
      send_resync(peer, now);  // the client is still waiting: our snapshot was lost
      return;
    }
  }
  DesyncAssembly& assembly = peer.desync;
  const net::ChunkHeader header{
      report.report_id(),
      report.chunk_index(),
      report.chunk_count(),
      report.total_size(),
      {static_cast<uint64_t>(report.tick()), report.client_checksum(), report.server_checksum()}};
  const net::ChunkResult result = assembly.chunks.add(header, bytes_of(report.chunk()));
  if (result == net::ChunkResult::kRejected) {
    ++stats_.rejected_packets;  // an inconsistent chunk; the client will retry
    return;
  }
  if (result != net::ChunkResult::kComplete) return;
  // Every chunk of the report said the same (the assembler checks).
  assembly.report_id = report.report_id();
  assembly.tick = report.tick();
  assembly.client_checksum = report.client_checksum();
  assembly.server_checksum = report.server_checksum();
  const std::span<const uint8_t> dump = assembly.chunks.blob();
  ++stats_.desync_reports;
  peer.handled_reports.push_back(assembly.report_id);
  if (peer.handled_reports.size() > 16) peer.handled_reports.erase(peer.handled_reports.begin());
  // Storing a report (disk, two simulations, a diff) is the expensive part:
  // a few per player, spaced out, so a client cannot stall the match or
  // fill the disk by inventing desyncs.
  if (peer.reports_stored < kMaxReportsPerPeer &&
      (peer.reports_stored == 0 || now - peer.last_report_stored >= kReportMinInterval)) {
    ++peer.reports_stored;
    peer.last_report_stored = now;
    store_desync_report(player, assembly, dump);
  }
  assembly.chunks.reset();
  send_resync(peer, now);
}

std::optional<uint64_t> MatchHost::final_checksum(Tick tick) const {
  if (tick < 0) return std::nullopt;
  const FinalRecord& record = final_history_[static_cast<size_t>(tick) % kFinalHistory];
  if (record.tick != tick) return std::nullopt;
  return record.checksum;
}

void MatchHost::store_desync_report(uint32_t player, const DesyncAssembly& assembly,
                                    std::span<const uint8_t> dump) {
  DesyncReportInfo report;
  report.player = player;
  report.report_id = assembly.report_id;
  report.tick = assembly.tick;
  report.client_checksum = assembly.client_checksum;
  report.server_checksum_received = assembly.server_checksum;
  report.server_checksum = final_checksum(assembly.tick);
  const DesyncFindings found = forensics_.examine(report, dump, *session_);
  if (found.dump_unreadable) ++stats_.desync_dumps_unreadable;
  if (found.write_failed) {
    ++stats_.desync_report_write_failures;
    log_warning("cannot write desync report " + config_.desync_dir + "/desync_p" +
                std::to_string(player) + "_t" + std::to_string(assembly.tick) + "_r" +
                std::to_string(assembly.report_id) + ".{txt,bin}");
  }
  const std::string stored = found.stored_as.empty() ? "" : " (" + found.stored_as + ")";
  if (found.problem.empty()) {
    log_line(found.headline + stored);
  } else {
    log_warning(found.headline + "; " + found.problem + stored);
  }
}

void MatchHost::send_resync(Peer& peer, TimePoint now) {
  if (peer.resynced_once && now - peer.last_resync < kResyncMinInterval) return;
  peer.resynced_once = true;
  peer.last_resync = now;
  // One snapshot per episode: resends repeat the same tick, bytes and id, so
  // an acknowledgement slower than the resend interval still matches, and
  // the client can complete it from chunks of several sends. When no
  // snapshot passes its check, nothing is sent now and the next resend
  // (or the client's next request) tries again from newer state.
  if (peer.resync_tick == kNoTick && !start_resync_episode(peer)) return;
  send_resync_chunks(peer, now);
}

bool MatchHost::start_resync_episode(Peer& peer) {
  // The client restarts from the snapshot's tick and acknowledges the tick
  // before it. The state after the last final tick is the natural choice.
  // If that one does not load, the oldest final state the client can still
  // take is the fallback: a state that broke recently (a body thrown out of
  // range) is often fine a few ticks earlier, and the client re-simulates
  // from there without ever having to load the broken one. Both must still
  // be in the snapshot ring, and the final ticks after the fallback must
  // still be held for resending. At most two checks per episode. (A
  // snapshot right after what the client acknowledged counts as
  // acknowledged at once, so it goes out once instead of until
  // acknowledged; a client that misses a chunk asks again.)
  const Tick newest = next_final_;
  const Tick oldest_final_held = finals_.oldest();
  const Tick fallback = std::max(peer.final_seen + 1, oldest_final_held);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Tick tick = attempt == 0 ? newest : fallback;
    if (attempt > 0 && tick >= newest) break;  // no older state to fall back to
    const std::optional<uint64_t> checksum = session_->checksum_at(tick);
    if (!checksum || !session_->serialize_state_at(tick, peer.resync_bytes)) continue;
    if (snapshot_hook_) snapshot_hook_(tick, peer.resync_bytes);
    // Never send what we could not load ourselves: the same test the client
    // applies (RollbackSession::reset_from), on a fresh simulation.
    Status status = net::plan_chunks(peer.resync_bytes.size(), net::kResyncChunkLimits).status();
    if (status.ok()) {
      if (auto loaded = session_->load_snapshot(peer.resync_bytes, *checksum); !loaded.ok()) {
        status = loaded.status();
      }
    }
    if (!status.ok()) {
      ++stats_.resync_snapshot_failures;
      if (worth_logging(stats_.resync_snapshot_failures)) {
        log_warning("resync snapshot for tick " + std::to_string(tick) +
                    " does not load on the server, not sent: " + status.message() + " (" +
                    std::to_string(stats_.resync_snapshot_failures) + " so far)");
      }
      continue;
    }
    peer.resync_tick = tick;
    peer.standalone_from = tick;
    peer.resync_checksum = *checksum;
    peer.resync_id = next_snapshot_id_++;
    // Final ticks from here on are (re)sent once the client acknowledges
    // tick - 1; the round-robin resend covers any it already had before.
    peer.final_sent = std::max(peer.final_sent, tick - 1);
    ++stats_.resyncs_sent;
    return true;
  }
  peer.resync_bytes.clear();
  return false;
}

void MatchHost::on_resync_refused(Peer& peer, uint32_t player, const v1::ResyncRequest& request) {
  // Only the snapshot still being resent counts: later requests naming it
  // again are copies of the same refusal.
  if (request.refused_snapshot_id() == 0 || peer.resync_tick == kNoTick ||
      request.refused_snapshot_id() != peer.resync_id) {
    return;
  }
  ++stats_.resyncs_refused;
  if (worth_logging(stats_.resyncs_refused)) {
    log_warning("player " + std::to_string(player) + " could not load resync snapshot " +
                std::to_string(peer.resync_id) + " (tick " + std::to_string(peer.resync_tick) +
                "): " + printable(request.refused_reason()) + "; building another (" +
                std::to_string(stats_.resyncs_refused) + " so far)");
  }
  // Resending the same bytes cannot help: the next send starts a new episode.
  peer.resync_tick = kNoTick;
  peer.resync_bytes.clear();
}

void MatchHost::send_resync_chunks(Peer& peer, TimePoint now) {
  // start_resync_episode() only keeps a snapshot that plans.
  const Result<uint32_t> count =
      net::plan_chunks(peer.resync_bytes.size(), net::kResyncChunkLimits);
  if (!count.ok()) return;
  for (uint32_t i = 0; i < *count; ++i) {
    const std::span<const uint8_t> part =
        net::chunk_at(peer.resync_bytes, i, net::kResyncChunkLimits);
    v1::Envelope envelope;
    v1::ResyncChunk* chunk = envelope.mutable_resync_chunk();
    chunk->set_snapshot_id(peer.resync_id);
    chunk->set_tick(peer.resync_tick);
    chunk->set_checksum(peer.resync_checksum);
    chunk->set_chunk_index(i);
    chunk->set_chunk_count(*count);
    chunk->set_total_size(static_cast<uint32_t>(peer.resync_bytes.size()));
    chunk->set_chunk(part.data(), part.size());
    send(peer, envelope, now);
  }
}

}  // namespace rwd::server
