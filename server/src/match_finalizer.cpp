// SPDX-License-Identifier: MIT
// The match host's finalizer and broadcaster: ticks become final when
// every held slot's input is in or the window has passed (missing inputs
// substituted by what was simulated), go to the recorder (the replay and
// the live feed) with their checksum, and reach each client in its one
// datagram of the tick with the other players' new inputs and its input
// acknowledgement.
#include <algorithm>

#include "host_log.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/server/match_host.h"

namespace rwd::server {
namespace {

constexpr size_t kFinalTicksBudgetBytes = 1000;  // leaves room for the envelope header
constexpr size_t kMaxFinalHistory = 1024;        // ticks kept for clients that fall behind

}  // namespace

void MatchHost::finalize_ready_ticks() {
  const Tick current = session_->current_tick();
  while (next_final_ < current) {
    if (config_.max_ticks > 0 && next_final_ >= config_.max_ticks) break;
    const Tick t = next_final_;
    // A slot nobody holds (not taken yet, timed out, left) sends nothing:
    // waiting the window for it would only delay every tick.
    bool all_known = true;
    for (uint32_t p = 0; p < peers_.size(); ++p) {
      const Peer& peer = peers_[p];
      const bool held = peer.joined && peer.connected && !peer.left;
      all_known = all_known && (!held || session_->queue(p).is_confirmed(t));
    }
    if (!all_known && current - t < config_.window_ticks) break;

    // The deadline passed: missing inputs become the prediction the
    // simulation already used, so finalizing never re-simulates.
    uint64_t substituted = 0;
    for (uint32_t p = 0; p < peers_.size(); ++p) {
      if (!session_->queue(p).is_confirmed(t)) {
        substituted |= uint64_t{1} << p;
        (void)session_->add_final_input(p, t, session_->input_for(p, t));
        ++stats_.substituted_inputs;
      }
      final_inputs_[p] = session_->input_for(p, t);
    }
    const uint64_t checksum = session_->checksum_after(t).value_or(0);
    final_history_[static_cast<size_t>(t) % kFinalHistory] = {t, substituted, checksum};
    stats_.final_checksum = checksum;

    recorder_.record(*session_, t, final_inputs_, substituted, checksum, stats_);
    (void)session_->finalize_through(t);
    finals_.append(t, final_inputs_, substituted, checksum, current);
    ++next_final_;
  }
  if (recorder_.names_stale()) {
    std::vector<std::string> names;
    for (const Peer& peer : peers_) names.push_back(peer.joined ? peer.name : std::string());
    recorder_.publish_names(std::move(names));
  }
  // Drop history every connected client has; keep a bounded tail for the rest.
  Tick acked_by_all = next_final_ - 1;
  for (const Peer& peer : peers_) {
    if (peer.joined && peer.connected) acked_by_all = std::min(acked_by_all, peer.final_seen);
  }
  finals_.trim(acked_by_all, kMaxFinalHistory);
}

void MatchHost::attach_live_feed(std::shared_ptr<LiveFeed> feed) {
  recorder_.attach_live_feed(std::move(feed));
}

void MatchHost::broadcast(TimePoint now) {
  const Tick oldest_held = finals_.oldest();
  // Each run packed once, for every client but its player.
  // Never shrunk: each string keeps its capacity from tick to tick.
  if (relay_packed_.size() < relay_batch_.size()) relay_packed_.resize(relay_batch_.size());
  for (size_t r = 0; r < relay_batch_.size(); ++r) {
    relay_packed_[r].clear();
    proto::append_relayed_run(relay_batch_[r].player, relay_batch_[r].first_tick, server_tick(),
                              relay_batch_[r].inputs, relay_packed_[r]);
  }
  for (uint32_t p = 0; p < peers_.size(); ++p) broadcast_to(peers_[p], p, oldest_held, now);
  for (uint32_t s = 0; s < spectators_.size(); ++s) {
    broadcast_to(spectators_[s], config_.players + s, oldest_held, now);
  }
  relay_batch_.clear();
  broadcast_arena_.Reset();
}

void MatchHost::broadcast_to(Peer& peer, uint32_t p, Tick oldest_held, TimePoint now) {
  if (!peer.joined || !peer.connected) return;
  if (!peer.sent_input && phase_ == Phase::kRunning && session_->current_tick() % 10 == 0) {
    send_match_start(peer, now);  // every MatchStart so far may have been lost
  }
  // A client that fell behind the history we keep can only catch up from
  // a snapshot; one with a snapshot on the way gets it again until it
  // acknowledges the snapshot's tick.
  if (peer.final_seen + 1 < oldest_held && peer.resync_tick == kNoTick) send_resync(peer, now);
  bool resync_pending = false;
  if (peer.resync_tick != kNoTick) {
    if (peer.final_seen >= peer.resync_tick - 1) {
      peer.resync_tick = kNoTick;
      peer.resync_bytes.clear();
    } else {
      send_resync(peer, now);
      resync_pending = true;
    }
  }
  // On the broadcast arena, freed once every client's datagram is out.
  v1::Envelope& envelope = *google::protobuf::Arena::CreateMessage<v1::Envelope>(&broadcast_arena_);
  v1::FinalTicks* out = envelope.mutable_final_ticks();
  const bool player = p < config_.players;  // spectators send no inputs
  out->set_input_ack_tick(player ? session_->queue(p).contiguous_through() : kNoTick);
  out->set_input_lead_ticks(peer.last_lead);
  out->set_server_tick(server_tick());
  // The other players' new inputs first (they are what prediction waits
  // for), up to part of the budget: what does not fit arrives in final
  // ticks soon anyway.
  size_t budget = kFinalTicksBudgetBytes - 3;  // the relayed field's tag and length
  std::string* relayed = out->mutable_relayed();
  for (size_t r = 0; r < relay_batch_.size(); ++r) {
    const size_t size = relay_packed_[r].size();
    if (relay_batch_[r].player == p || size > budget - kFinalTicksBudgetBytes / 3) continue;
    budget -= size;
    *relayed += relay_packed_[r];
  }
  // While a snapshot is on its way the client ignores final ticks, but
  // still needs the server's clock and its input acknowledgements.
  if (!resync_pending) add_final_ticks(peer, *out, budget);
  send(peer, envelope, now);
}

void MatchHost::add_final_ticks(Peer& peer, v1::FinalTicks& out, size_t budget) {
  const double rtt_ticks =
      peer.connection->has_rtt()
          ? static_cast<double>(peer.connection->smoothed_rtt_us()) * config_.tick_rate_hz / 1e6
          : 0.0;
  FinalTickLog::Cursor cursor{peer.final_seen, peer.final_sent, peer.resend_cursor,
                              peer.standalone_from};
  finals_.add_to(out, budget, cursor, session_->current_tick(), rtt_ticks);
  peer.final_sent = cursor.sent;
  peer.resend_cursor = cursor.resend;
}

}  // namespace rwd::server
