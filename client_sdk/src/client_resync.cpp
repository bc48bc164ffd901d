// SPDX-License-Identifier: MIT
// The client protocol's desync path: reporting a checksum mismatch (the
// state dump in chunks), asking for a resync, reassembling the server's
// snapshot, checking it loads with its checksum before anything is
// replaced, and naming a snapshot it refused so the server sends another.
#include <algorithm>

#include "client_protocol_impl.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

std::span<const uint8_t> bytes_of(const std::string& chunk) {
  return {reinterpret_cast<const uint8_t*>(chunk.data()), chunk.size()};
}

}  // namespace

void ClientProtocol::Impl::request_resync(TimePoint now) {
  if (awaiting_resync_) return;
  awaiting_resync_ = true;
  desync_tick_ = kNoTick;  // nothing to report, just ask
  state_buffer_.clear();
  report_sends_ = 0;
  send_desync_report(now);
}

void ClientProtocol::Impl::send_desync_report(TimePoint now) {
  last_report_sent_ = now;
  const Result<uint32_t> count = net::plan_chunks(state_buffer_.size(), net::kDesyncChunkLimits);
  // The whole report goes out a few times; after that only a short request,
  // so a server that is slow to answer is not buried in chunks.
  if (desync_tick_ == kNoTick || !count.ok() || report_sends_++ >= 3) {
    send_resync_request(now);  // nothing to show: just ask for the snapshot
    return;
  }
  for (uint32_t i = 0; i < *count; ++i) {
    const std::span<const uint8_t> part = net::chunk_at(state_buffer_, i, net::kDesyncChunkLimits);
    v1::Envelope envelope;
    v1::DesyncReport* report = envelope.mutable_desync_report();
    report->set_tick(desync_tick_);
    report->set_client_checksum(desync_local_checksum_);
    report->set_server_checksum(desync_server_checksum_);
    report->set_report_id(report_id_);
    report->set_chunk_index(i);
    report->set_chunk_count(*count);
    report->set_total_size(static_cast<uint32_t>(state_buffer_.size()));
    report->set_chunk(part.data(), part.size());
    send(envelope, now);
  }
}

void ClientProtocol::Impl::on_resync_chunk(const v1::ResyncChunk& chunk, TimePoint now) {
  // Only a snapshot past everything we already settled can help: older ones
  // are delayed duplicates of an earlier episode.
  if (chunk.tick() <= session_->final_tick()) return;
  // Nor one before what we told the server we have: it would never resend
  // the final ticks in between.
  if (chunk.tick() - 1 < last_final_acked_) return;
  if (!awaiting_resync_ && chunk.tick() <= last_final_received_ + 1) return;
  // Resends of a snapshot that already failed to load: the server has not
  // heard yet; our requests keep naming it until it sends another.
  if (chunk.snapshot_id() == refused_snapshot_id_) return;
  const net::ChunkHeader header{chunk.snapshot_id(),
                                chunk.chunk_index(),
                                chunk.chunk_count(),
                                chunk.total_size(),
                                {static_cast<uint64_t>(chunk.tick()), chunk.checksum(), 0}};
  switch (resync_.add(header, bytes_of(chunk.chunk()))) {
    case net::ChunkResult::kRejected:
      ++stats_.packets_rejected;
      return;
    case net::ChunkResult::kComplete:
      load_resync(chunk, now);
      return;
    case net::ChunkResult::kAccepted:
    case net::ChunkResult::kDuplicate:
      return;
  }
}

void ClientProtocol::Impl::load_resync(const v1::ResyncChunk& last_chunk, TimePoint now) {
  // Every chunk named the same snapshot (the assembler checks), so the last
  // one speaks for all.
  const uint32_t snapshot_id = last_chunk.snapshot_id();
  const Tick tick = last_chunk.tick();
  const uint64_t checksum = last_chunk.checksum();
  // Decoded and checked against the server's checksum before it replaces
  // anything; a bad snapshot is dropped and another asked for.
  const Status status = session_->reset_from(resync_.blob(), checksum);
  resync_.reset();
  if (!status.ok()) {
    refuse_resync(snapshot_id, tick, status.message(), now);
    return;
  }
  last_final_received_ = tick - 1;  // the server resends final ticks from here
  last_final_inputs_.clear();       // ... and sends the first one standalone
  pending_finals_.clear();
  early_finals_.clear();
  next_input_tick_ = std::max(next_input_tick_, tick);
  // Re-anchor the clock on the server's instead of bursting through the
  // ticks the clock ran ahead while we waited.
  const double rtt_ticks = stats_.rtt_ms / 1000.0 * tick_rate_hz_;
  tick_clock_ =
      std::max(static_cast<double>(tick), server_tick_ + rtt_ticks + config_.target_lead_ticks);
  time_sync_.clear_jump();
  awaiting_resync_ = false;
  desync_tick_ = kNoTick;
  refused_snapshot_id_ = 0;
  refused_reason_.clear();
  state_buffer_.clear();
  report_sends_ = 0;
  ++stats_.resyncs;
  // The snapshot (its checksum checked) stands for the final ticks before
  // it that our own simulation never verified.
  if (tick - 1 > agreed_through_) {
    stats_.final_ticks_resynced += static_cast<uint64_t>(tick - 1 - agreed_through_);
    agreed_through_ = tick - 1;
  }
  emit(
      {ClientEventType::kResynced, tick, player_, session_->simulation().checksum(), checksum, {}});
  step_due_ticks(now);
}

void ClientProtocol::Impl::refuse_resync(uint32_t snapshot_id, Tick tick, const std::string& reason,
                                         TimePoint now) {
  ++stats_.resyncs_refused;
  emit({ClientEventType::kResyncRefused, tick, player_, 0, 0, reason});
  // The server resends one snapshot until it is acknowledged, so it has to
  // hear that this one is useless. Until another loads, final ticks are not
  // applied and the request is repeated (update() -> send_desync_report).
  awaiting_resync_ = true;
  refused_snapshot_id_ = snapshot_id;
  refused_reason_ = reason.substr(0, net::kMaxStringBytes);
  last_report_sent_ = now;
  send_resync_request(now);
}

void ClientProtocol::Impl::send_resync_request(TimePoint now) {
  v1::Envelope envelope;
  v1::ResyncRequest* request = envelope.mutable_resync_request();
  request->set_desync_tick(std::max<Tick>(desync_tick_, 0));
  if (refused_snapshot_id_ != 0) {
    request->set_refused_snapshot_id(refused_snapshot_id_);
    request->set_refused_reason(refused_reason_);
  }
  send(envelope, now);
}

}  // namespace rwd::client
