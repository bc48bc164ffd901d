// SPDX-License-Identifier: MIT
#include "rewind/server/match_resync.h"

#include <algorithm>

#include "host_log.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::log_warning;
using detail::printable;
using detail::worth_logging;

constexpr auto kResyncMinInterval = std::chrono::milliseconds(250);
constexpr auto kReportMinInterval = std::chrono::seconds(2);
constexpr uint32_t kMaxReportsPerPeer = 8;
constexpr size_t kHandledReports = 16;

std::span<const uint8_t> bytes_of(const std::string& chunk) {
  return {reinterpret_cast<const uint8_t*>(chunk.data()), chunk.size()};
}

}  // namespace

MatchResync::MatchResync(const MatchConfig& config, net::RollbackSession& session,
                         MatchSeats& seats, const MatchFinalizer& finalizer, MatchOutbox& outbox,
                         MatchStats& stats, MatchEnvironment env)
    : config_(config),
      session_(session),
      seats_(seats),
      finalizer_(finalizer),
      outbox_(outbox),
      stats_(stats),
      offers_(seats.size()),
      reports_(seats.size()),
      forensics_(config.desync_dir, std::move(env)) {}

void MatchResync::clear(uint32_t id) {
  offers_[id] = Offer{};
  reports_[id] = Report{};
}

void MatchResync::restart(uint32_t id) {
  Offer& offer = offers_[id];
  offer.tick = kNoTick;
  offer.bytes.clear();
  offer.checksum = 0;
  offer.sent_once = false;
  Report& report = reports_[id];
  report.chunks.reset();
  report.handled.clear();
}

void MatchResync::on_desync_report(uint32_t id, const v1::DesyncReport& report, TimePoint now) {
  if (report.tick() > finalizer_.next_final() - 1 || report.tick() < 0) {
    ++stats_.rejected_packets;  // only final ticks can desync
    return;
  }
  Report& assembly = reports_[id];
  if (std::find(assembly.handled.begin(), assembly.handled.end(), report.report_id()) !=
      assembly.handled.end()) {
    send(id, now);  // the client is still waiting: our snapshot was lost
    return;
  }
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
  ++stats_.desync_reports;
  assembly.handled.push_back(assembly.report_id);
  if (assembly.handled.size() > kHandledReports) assembly.handled.erase(assembly.handled.begin());
  // Storing a report (disk, two simulations, a diff) is the expensive part.
  if (assembly.stored < kMaxReportsPerPeer &&
      (assembly.stored == 0 || now - assembly.last_stored >= kReportMinInterval)) {
    ++assembly.stored;
    assembly.last_stored = now;
    store(id, assembly, assembly.chunks.blob());
  }
  assembly.chunks.reset();
  send(id, now);
}

void MatchResync::store(uint32_t id, const Report& report, std::span<const uint8_t> dump) {
  DesyncReportInfo info;
  info.player = id;
  info.report_id = report.report_id;
  info.tick = report.tick;
  info.client_checksum = report.client_checksum;
  info.server_checksum_received = report.server_checksum;
  info.server_checksum = finalizer_.checksum(report.tick);
  const DesyncFindings found = forensics_.examine(info, dump, session_);
  if (found.dump_unreadable) ++stats_.desync_dumps_unreadable;
  if (found.write_failed) {
    ++stats_.desync_report_write_failures;
    log_warning("cannot write desync report " + config_.desync_dir + "/desync_p" +
                std::to_string(id) + "_t" + std::to_string(report.tick) + "_r" +
                std::to_string(report.report_id) + ".{txt,bin}");
  }
  const std::string stored = found.stored_as.empty() ? "" : " (" + found.stored_as + ")";
  if (found.problem.empty()) {
    log_line(found.headline + stored);
  } else {
    log_warning(found.headline + "; " + found.problem + stored);
  }
}

void MatchResync::on_resync_request(uint32_t id, const v1::ResyncRequest& request, TimePoint now) {
  Offer& offer = offers_[id];
  // Only the snapshot still being resent counts as refused: later requests
  // naming it again are copies of the same refusal.
  if (request.refused_snapshot_id() != 0 && offer.tick != kNoTick &&
      request.refused_snapshot_id() == offer.snapshot_id) {
    ++stats_.resyncs_refused;
    if (worth_logging(stats_.resyncs_refused)) {
      log_warning("player " + std::to_string(id) + " could not load resync snapshot " +
                  std::to_string(offer.snapshot_id) + " (tick " + std::to_string(offer.tick) +
                  "): " + printable(request.refused_reason()) + "; building another (" +
                  std::to_string(stats_.resyncs_refused) + " so far)");
    }
    // Resending the same bytes cannot help: the next send starts a new episode.
    offer.tick = kNoTick;
    offer.bytes.clear();
  }
  send(id, now);
}

bool MatchResync::before_broadcast(uint32_t id, TimePoint now) {
  const Seat& seat = seats_[id];
  Offer& offer = offers_[id];
  // A client that fell behind the history held can only catch up from a
  // snapshot; one with a snapshot on the way gets it again until it
  // acknowledges the snapshot's tick.
  if (seat.final_seen + 1 < finalizer_.held().oldest() && offer.tick == kNoTick) send(id, now);
  if (offer.tick == kNoTick) return false;
  if (seat.final_seen >= offer.tick - 1) {
    offer.tick = kNoTick;
    offer.bytes.clear();
    return false;
  }
  send(id, now);
  return true;
}

void MatchResync::send(uint32_t id, TimePoint now) {
  Offer& offer = offers_[id];
  if (offer.sent_once && now - offer.last_sent < kResyncMinInterval) return;
  offer.sent_once = true;
  offer.last_sent = now;
  // One snapshot per episode: resends repeat the same tick, bytes and id, so
  // an acknowledgement slower than the resend interval still matches, and
  // the client can complete it from chunks of several sends. When no
  // snapshot passes its check, nothing is sent now and the next resend
  // (or the client's next request) tries again from newer state.
  if (offer.tick == kNoTick && !start_episode(id)) return;
  send_chunks(id, now);
}

bool MatchResync::start_episode(uint32_t id) {
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
  Seat& seat = seats_[id];
  Offer& offer = offers_[id];
  const Tick newest = finalizer_.next_final();
  const Tick fallback = std::max(seat.final_seen + 1, finalizer_.held().oldest());
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Tick tick = attempt == 0 ? newest : fallback;
    if (attempt > 0 && tick >= newest) break;  // no older state to fall back to
    const std::optional<uint64_t> checksum = session_.checksum_at(tick);
    if (!checksum || !session_.serialize_state_at(tick, offer.bytes)) continue;
    if (snapshot_hook_) snapshot_hook_(tick, offer.bytes);
    // Never send what we could not load ourselves: the same test the client
    // applies (RollbackSession::reset_from), on a fresh simulation.
    Status status = net::plan_chunks(offer.bytes.size(), net::kResyncChunkLimits).status();
    if (status.ok()) {
      if (auto loaded = session_.load_snapshot(offer.bytes, *checksum); !loaded.ok()) {
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
    offer.tick = tick;
    offer.checksum = *checksum;
    offer.snapshot_id = next_snapshot_id_++;
    seat.standalone_from = tick;
    // Final ticks from here on are (re)sent once the client acknowledges
    // tick - 1; the round-robin resend covers any it already had before.
    seat.final_sent = std::max(seat.final_sent, tick - 1);
    ++stats_.resyncs_sent;
    return true;
  }
  offer.bytes.clear();
  return false;
}

void MatchResync::send_chunks(uint32_t id, TimePoint now) {
  const Offer& offer = offers_[id];
  // start_episode() only keeps a snapshot that plans.
  const Result<uint32_t> count = net::plan_chunks(offer.bytes.size(), net::kResyncChunkLimits);
  if (!count.ok()) return;
  for (uint32_t i = 0; i < *count; ++i) {
    const std::span<const uint8_t> part = net::chunk_at(offer.bytes, i, net::kResyncChunkLimits);
    v1::Envelope envelope;
    v1::ResyncChunk* chunk = envelope.mutable_resync_chunk();
    chunk->set_snapshot_id(offer.snapshot_id);
    chunk->set_tick(offer.tick);
    chunk->set_checksum(offer.checksum);
    chunk->set_chunk_index(i);
    chunk->set_chunk_count(*count);
    chunk->set_total_size(static_cast<uint32_t>(offer.bytes.size()));
    chunk->set_chunk(part.data(), part.size());
    outbox_.send(seats_[id], envelope, now);
  }
}

}  // namespace rwd::server
