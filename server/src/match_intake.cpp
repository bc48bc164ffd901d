// SPDX-License-Identifier: MIT
// The match host's intake: every datagram a client sends, checked against
// the seat its connection holds and handed to the part that owns it (a
// join to MatchAdmission, inputs to the session and InputRelay, a desync
// report or resync request to MatchResync).
#include <algorithm>

#include "host_log.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"
#include "rewind/server/match_host.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::printable;

// Frees everything on an arena when the scope ends.
struct ArenaReset {
  google::protobuf::Arena& arena;
  ~ArenaReset() { arena.Reset(); }
};

}  // namespace

void MatchHost::on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, TimePoint now,
                            const Admission* who) {
  ++stats_.packets_in;
  stats_.bytes_in += bytes.size();
  if (phase_ == Phase::kEnded) return;
  if (config_.secure && who == nullptr) {
    ++stats_.rejected_packets;
    return;
  }
  ArenaReset reset{receive_arena_};
  v1::Envelope& envelope = *google::protobuf::Arena::CreateMessage<v1::Envelope>(&receive_arena_);
  if (!net::decode_envelope(bytes, envelope).ok()) {
    ++stats_.rejected_packets;
    return;
  }
  if (envelope.has_join_request()) {
    if (who == nullptr) {
      // Tokenless, and the address has not answered a cookie: it may not
      // be the sender's, so nothing is taken from it nor sent to it.
      ++stats_.rejected_packets;
      return;
    }
    handle_join(envelope.join_request(), from, now, *who);
    return;
  }
  uint32_t player = 0;
  Seat* peer = seats_.find(envelope.connection_id(), &player);
  // An unknown id, or a known id from another address (spoofed or stolen),
  // is dropped before it can touch any state.
  if (peer == nullptr || peer->endpoint != from) {
    ++stats_.rejected_packets;
    return;
  }
  if (peer->left) {
    // A goodbye is final for this connection. Repeated goodbyes while the
    // match closes are normal; anything else is counted.
    if (phase_ == Phase::kRunning) ++stats_.rejected_packets;
    return;
  }
  net::ReceiveResult received = peer->connection->on_receive(envelope, now);
  if (!received.is_new()) {
    ++stats_.duplicate_packets;
    return;
  }
  peer->last_receive = now;
  if (!peer->connected && phase_ == Phase::kRunning && !envelope.has_disconnect()) {
    peer->connected = true;
    log_line("player " + std::to_string(player) + " is back");
  }

  switch (envelope.payload_case()) {
    case v1::Envelope::kInputFrame:
      if (phase_ == Phase::kRunning && player < config_.players) {
        handle_input(*peer, player, envelope.input_frame());
      } else if (envelope.input_frame().player() == player) {
        // A spectator, or closing: only the acknowledgement of final ticks
        // matters (a spectator's inputs are never taken).
        if (envelope.input_frame().inputs_size() > 0 && player >= config_.players) {
          ++stats_.rejected_inputs;
        }
        peer->sent_input = true;
        peer->final_seen =
            std::max(peer->final_seen,
                     std::min(envelope.input_frame().last_final_tick_seen(), last_final_tick()));
      }
      break;
    case v1::Envelope::kPing: {
      v1::Envelope reply;
      v1::Pong* pong = reply.mutable_pong();
      pong->set_client_time_us(envelope.ping().client_time_us());
      pong->set_server_tick(server_tick());
      pong->set_server_tick_elapsed_us(static_cast<uint32_t>(
          std::chrono::duration_cast<std::chrono::microseconds>(now - tick_started_).count()));
      outbox_.send(*peer, reply, now);
      break;
    }
    case v1::Envelope::kDesyncReport:
      resync_.on_desync_report(player, envelope.desync_report(), now);
      break;
    case v1::Envelope::kResyncRequest:
      if (phase_ == Phase::kRunning || phase_ == Phase::kClosing) {
        resync_.on_resync_request(player, envelope.resync_request(), now);
      }
      break;
    case v1::Envelope::kDisconnect:
      if (peer->connected && phase_ == Phase::kRunning) {
        log_line("player " + std::to_string(player) +
                 " left: " + printable(envelope.disconnect().reason()));
      }
      peer->connected = false;
      peer->left = true;
      break;
    default:
      // Server-to-client messages have no business arriving here.
      ++stats_.rejected_packets;
      break;
  }
}

void MatchHost::handle_join(const v1::JoinRequest& request, const Endpoint& from, TimePoint now,
                            const Admission& who) {
  const MatchAdmission::Decision decision = admission_.admit(request, from, phase_, who, now);
  if (decision.kind == MatchAdmission::Decision::Kind::kRejected) {
    ++stats_.rejected_packets;
    v1::Envelope reply;
    reply.mutable_join_reject()->set_nonce(request.nonce());
    reply.mutable_join_reject()->set_reason(decision.reason);
    outbox_.send_unconnected(from, reply);
    return;
  }
  const uint32_t id = decision.seat;
  const bool player = seats_.is_player(id);
  if (decision.kind == MatchAdmission::Decision::Kind::kSeated) {
    // What the host keeps per seat starts over with its new connection.
    if (!player) {
      resync_.clear(id);
    } else if (phase_ == Phase::kRunning) {
      resync_.restart(id);
    }
    if (player) {
      recorder_.names_changed();
      if (!decision.rejoin) ++stats_.players_joined;
    }
  }
  Seat& seat = seats_[id];
  v1::Envelope reply;
  v1::JoinAccept* answer = reply.mutable_join_accept();
  answer->set_nonce(request.nonce());
  answer->set_connection_id(seat.connection->connection_id());
  answer->set_player(id);
  answer->set_spectator(!player);
  answer->set_player_count(config_.players);
  answer->set_game(config_.game);
  answer->set_seed(config_.seed);
  answer->set_tick_rate_hz(config_.tick_rate_hz);
  answer->set_window_ticks(static_cast<uint32_t>(config_.window_ticks));
  outbox_.send(seat, reply, now);
  if (phase_ == Phase::kRunning) send_match_start(seat, now);
  if (decision.kind == MatchAdmission::Decision::Kind::kSeated && player &&
      phase_ == Phase::kLobby && seats_.players_joined() >= config_.players_to_start()) {
    start_match(now);
  }
}

void MatchHost::handle_input(Seat& peer, uint32_t player, const v1::InputFrame& frame) {
  if (frame.player() != player) {
    // Inputs for another slot: never applied, whoever sent them.
    ++stats_.rejected_packets;
    stats_.rejected_inputs += static_cast<uint64_t>(frame.inputs_size());
    return;
  }
  peer.sent_input = true;
  if (frame.last_final_tick_seen() > peer.final_seen) {
    peer.final_seen = std::min(frame.last_final_tick_seen(), last_final_tick());
  }
  const Tick now_tick = session_->current_tick();
  const Tick clock_tick = server_tick();
  Tick newest = kNoTick;
  // New inputs wait for the tick's one datagram to each client.
  relay_.begin(player);
  for (int i = 0; i < frame.inputs_size(); ++i) {
    const Tick tick = frame.first_tick() + i;
    auto input = proto::from_wire(frame.inputs(i));
    if (!input.ok() || tick > clock_tick + config_.max_input_lead_ticks) {
      ++stats_.rejected_inputs;
      continue;
    }
    switch (session_->add_input(player, tick, *input)) {
      case net::InputResult::kAccepted:
        newest = std::max(newest, tick);
        if (tick < now_tick) ++stats_.late_inputs;
        relay_.add(tick, *input);
        break;
      case net::InputResult::kDuplicate:
        newest = std::max(newest, tick);
        break;
      case net::InputResult::kFinal: {
        // Late inputs still say how late the client runs: its time sync
        // needs exactly that (negative) lead to jump ahead.
        newest = std::max(newest, tick);
        // Resends of inputs the server had are normal; an input that only
        // arrives after its tick was finalized without it is rejected, and
        // counted once: the client resends it until it hears the tick is
        // final, and those copies are the same refusal.
        if (finalizer_.substituted(tick, player) && tick > peer.late_counted) {
          ++stats_.rejected_inputs;
          peer.late_counted = tick;
        }
        break;
      }
      case net::InputResult::kConflict:
      case net::InputResult::kTooFar:
      case net::InputResult::kBadPlayer:
      case net::InputResult::kBadInput:
        ++stats_.rejected_inputs;
        break;
    }
  }
  stats_.relayed_inputs += relay_.end();
  if (newest != kNoTick) {
    // 64-bit and clamped: ticks near INT32_MAX minus a negative countdown
    // clock must not overflow.
    const int64_t lead = int64_t{newest} - int64_t{clock_tick};
    const int64_t limit = config_.max_input_lead_ticks;
    peer.last_lead = static_cast<int32_t>(std::clamp<int64_t>(lead, -limit, limit));
  }
}

}  // namespace rwd::server
