// SPDX-License-Identifier: MIT
#include "desync_recovery.h"

#include <algorithm>
#include <chrono>
#include <span>

#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

constexpr auto kReportResend = std::chrono::milliseconds(500);

std::span<const uint8_t> bytes_of(const std::string& chunk) {
  return {reinterpret_cast<const uint8_t*>(chunk.data()), chunk.size()};
}

}  // namespace

void DesyncRecovery::request(ServerChannel& channel, TimePoint now) {
  if (awaiting_) return;
  awaiting_ = true;
  desync_tick_ = kNoTick;
  state_buffer_.clear();
  report_sends_ = 0;
  send_report(channel, now);
}

void DesyncRecovery::on_desync(net::RollbackSession& session, Tick tick, uint64_t local_checksum,
                               uint64_t server_checksum, ServerChannel& channel, TimePoint now) {
  awaiting_ = true;
  desync_tick_ = tick;
  desync_server_checksum_ = server_checksum;
  desync_local_checksum_ = local_checksum;
  ++report_id_;
  report_sends_ = 0;
  state_buffer_.clear();
  (void)session.serialize_state_at(tick + 1, state_buffer_);
  send_report(channel, now);
}

void DesyncRecovery::resend_if_due(ServerChannel& channel, TimePoint now) {
  if (awaiting_ && now - last_report_sent_ >= kReportResend) send_report(channel, now);
}

void DesyncRecovery::send_report(ServerChannel& channel, TimePoint now) {
  last_report_sent_ = now;
  const Result<uint32_t> count = net::plan_chunks(state_buffer_.size(), net::kDesyncChunkLimits);
  // The whole report goes out a few times; after that only a short request,
  // so a server that is slow to answer is not buried in chunks.
  if (desync_tick_ == kNoTick || !count.ok() || report_sends_++ >= 3) {
    send_request(channel, now);  // nothing to show: just ask for the snapshot
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
    channel.send(envelope, now);
  }
}

void DesyncRecovery::send_request(ServerChannel& channel, TimePoint now) {
  v1::Envelope envelope;
  v1::ResyncRequest* request = envelope.mutable_resync_request();
  request->set_desync_tick(std::max<Tick>(desync_tick_, 0));
  if (refused_snapshot_id_ != 0) {
    request->set_refused_snapshot_id(refused_snapshot_id_);
    request->set_refused_reason(refused_reason_);
  }
  channel.send(envelope, now);
}

DesyncRecovery::ChunkOutcome DesyncRecovery::on_chunk(net::RollbackSession& session,
                                                      const v1::ResyncChunk& chunk,
                                                      Tick acked_final, Tick received_final,
                                                      ServerChannel& channel, TimePoint now) {
  // Only a snapshot past everything we already settled can help: older ones
  // are delayed duplicates of an earlier episode.
  if (chunk.tick() <= session.final_tick()) return {};
  // Nor one before what we told the server we have: it would never resend
  // the final ticks in between.
  if (chunk.tick() - 1 < acked_final) return {};
  if (!awaiting_ && chunk.tick() <= received_final + 1) return {};
  // Resends of a snapshot that already failed to load: the server has not
  // heard yet; our requests keep naming it until it sends another.
  if (chunk.snapshot_id() == refused_snapshot_id_) return {};
  const net::ChunkHeader header{chunk.snapshot_id(),
                                chunk.chunk_index(),
                                chunk.chunk_count(),
                                chunk.total_size(),
                                {static_cast<uint64_t>(chunk.tick()), chunk.checksum(), 0}};
  switch (resync_.add(header, bytes_of(chunk.chunk()))) {
    case net::ChunkResult::kRejected:
      return {Outcome::kRejected, chunk.tick(), 0, {}};
    case net::ChunkResult::kAccepted:
    case net::ChunkResult::kDuplicate:
      return {};
    case net::ChunkResult::kComplete:
      break;
  }
  // Every chunk named the same snapshot (the assembler checks), so the last
  // one speaks for all. Decoded and checked against the server's checksum
  // before it replaces anything; a bad snapshot is dropped and another
  // asked for.
  const Tick tick = chunk.tick();
  const uint64_t checksum = chunk.checksum();
  const Status status = session.reset_from(resync_.blob(), checksum);
  resync_.reset();
  if (!status.ok()) {
    // The server resends one snapshot until it is acknowledged, so it has
    // to hear that this one is useless. Until another loads, final ticks
    // are not applied and the request is repeated (resend_if_due).
    awaiting_ = true;
    refused_snapshot_id_ = chunk.snapshot_id();
    refused_reason_ = status.message().substr(0, net::kMaxStringBytes);
    last_report_sent_ = now;
    send_request(channel, now);
    return {Outcome::kRefused, tick, checksum, status.message()};
  }
  awaiting_ = false;
  desync_tick_ = kNoTick;
  refused_snapshot_id_ = 0;
  refused_reason_.clear();
  state_buffer_.clear();
  report_sends_ = 0;
  return {Outcome::kLoaded, tick, checksum, {}};
}

}  // namespace rwd::client
