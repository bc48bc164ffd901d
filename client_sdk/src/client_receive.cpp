// SPDX-License-Identifier: MIT
// The client protocol's inbound side: a tokenless server's cookie, opening
// (on a secure connection) and decoding the server's datagrams, dropping
// whatever is not for this connection or repeats, and the messages that
// move the phase on: the join's answer, the match's start and end, a pong,
// a disconnect.
#include <chrono>

#include "client_protocol_impl.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

constexpr auto kJoinResend = std::chrono::milliseconds(250);
constexpr auto kLobbyPing = std::chrono::milliseconds(100);
constexpr auto kEndingWait = std::chrono::milliseconds(1500);

uint64_t micros_since_epoch(TimePoint t) {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count());
}

}  // namespace

void ClientProtocol::Impl::receive(std::span<const uint8_t> datagram, TimePoint now) {
  ++stats_.packets_received;
  if (phase_ == ClientPhase::kIdle) {
    ++stats_.packets_rejected;  // nothing asked for yet
    return;
  }
  if (handshake_) {
    // A secure server: a challenge answers our request; anything else must
    // be a payload sealed for our session.
    const std::optional<net::SecurePacket> kind = net::secure_packet_kind(datagram);
    if (kind == net::SecurePacket::kChallenge && phase_ == ClientPhase::kJoining) {
      if (!handshake_->on_challenge(datagram, handshake_response_).ok()) {
        ++stats_.packets_rejected;
        return;
      }
      transmit(handshake_response_);
      last_join_sent_ = now - kJoinResend;  // the join goes out on the next update
      return;
    }
    if (kind != net::SecurePacket::kPayload || !handshake_->session() ||
        !handshake_->session()->open(datagram, opened_buffer_).ok()) {
      ++stats_.packets_rejected;
      return;
    }
    secure_confirmed_ = true;
    datagram = opened_buffer_;
  } else if (net::cookie_packet_kind(datagram) == net::CookiePacket::kCookie) {
    // A tokenless server's answer to our Hello: the join goes out at once
    // with it (a second cookie, the answer to a resent Hello, only renews).
    const std::optional<net::AddressCookie> cookie = net::read_cookie(datagram);
    if (!cookie || phase_ != ClientPhase::kJoining) {
      ++stats_.packets_rejected;
      return;
    }
    const bool first = !cookie_;
    cookie_ = *cookie;
    cookie_at_ = now;
    if (first) send_join(now);
    return;
  }
  auto decoded = net::decode_envelope(datagram);
  if (!decoded.ok()) {
    ++stats_.packets_rejected;
    return;
  }
  handle(*decoded, now);
}

void ClientProtocol::Impl::handle(const v1::Envelope& envelope, TimePoint now) {
  if (envelope.has_join_reject()) {
    if (phase_ == ClientPhase::kJoining && envelope.join_reject().nonce() == nonce_) {
      phase_ = ClientPhase::kEnded;
      emit({ClientEventType::kRejected, kNoTick, 0, 0, 0, envelope.join_reject().reason()});
    } else {
      ++stats_.packets_rejected;
    }
    return;
  }
  if (envelope.has_join_accept()) {
    if (phase_ != ClientPhase::kJoining || envelope.join_accept().nonce() != nonce_) {
      ++stats_.packets_rejected;  // a late copy, or another join's
      return;
    }
    connection_.set_connection_id(envelope.join_accept().connection_id());
  }
  if (connection_.connection_id() == 0 || envelope.connection_id() != connection_.connection_id()) {
    ++stats_.packets_rejected;
    return;
  }
  if (!connection_.on_receive(envelope, now).is_new()) return;

  switch (envelope.payload_case()) {
    case v1::Envelope::kJoinAccept:
      on_join_accept(envelope.join_accept(), now);
      break;
    case v1::Envelope::kMatchStart:
      if (phase_ == ClientPhase::kLobby) on_match_start(envelope.match_start(), now);
      break;
    case v1::Envelope::kMatchEnd:
      on_match_end(envelope.match_end(), now);
      break;
    case v1::Envelope::kPong:
      on_pong(envelope.pong(), now);
      break;
    case v1::Envelope::kRelayedInputs:
      // decode_envelope has read and checked the run.
      if (session_ && proto::relayed_run_inputs(envelope.relayed_inputs(), relayed_buffer_).ok()) {
        on_relayed(envelope.relayed_inputs().player(), envelope.relayed_inputs().first_tick(),
                   relayed_buffer_);
      }
      break;
    case v1::Envelope::kFinalTicks:
      if (!session_) break;
      // decode_envelope has read and checked the runs.
      if (proto::relayed_runs(envelope.final_ticks(), relayed_runs_).ok()) {
        for (const proto::RelayedRun& run : relayed_runs_) {
          on_relayed(run.player, run.first_tick, run.inputs);
        }
      }
      on_final_ticks(envelope.final_ticks(), now);
      break;
    case v1::Envelope::kResyncChunk:
      if (session_ && (phase_ == ClientPhase::kRunning || phase_ == ClientPhase::kEnding)) {
        on_resync_chunk(envelope.resync_chunk(), now);
      }
      break;
    case v1::Envelope::kDisconnect:
      phase_ = ClientPhase::kEnded;
      emit(
          {ClientEventType::kDisconnected, kNoTick, player_, 0, 0, envelope.disconnect().reason()});
      break;
    default:
      ++stats_.packets_rejected;
      break;
  }
}

void ClientProtocol::Impl::on_join_accept(const v1::JoinAccept& accept, TimePoint now) {
  auto sim = game::Simulation::create(accept.game(), {accept.player_count(), accept.seed()});
  // A player's slot is below player_count, a spectator's seat past it.
  const bool seat_ok = accept.spectator() ? accept.player() >= accept.player_count()
                                          : accept.player() < accept.player_count();
  if (!sim.ok() || !seat_ok || accept.tick_rate_hz() == 0) {
    phase_ = ClientPhase::kEnded;
    emit({ClientEventType::kRejected, kNoTick, 0, 0, 0,
          "cannot build the server's match: " +
              (sim.ok() ? std::string("bad seat or tick rate") : sim.status().message())});
    return;
  }
  // The join exchange is itself a round trip, and the match may start the
  // moment we join, before any ping returns: take it as the first RTT
  // sample. Measured from the first request, so a lost request makes it an
  // overestimate (a little extra lead), never an underestimate (late inputs).
  if (stats_.rtt_ms == 0.0) {
    stats_.rtt_ms = std::chrono::duration<double, std::milli>(now - joined_at_).count();
  }
  player_ = accept.player();
  player_count_ = accept.player_count();
  spectator_ = accept.spectator();
  tick_rate_hz_ = accept.tick_rate_hz();
  if (static_cast<int64_t>(accept.window_ticks()) + 16 > config_.snapshot_ticks) {
    phase_ = ClientPhase::kEnded;
    emit({ClientEventType::kRejected, kNoTick, 0, 0, 0,
          "the server's window of " + std::to_string(accept.window_ticks()) +
              " ticks needs snapshot_ticks >= window + 16"});
    return;
  }
  net::RollbackConfig rollback;
  rollback.snapshot_ticks = config_.snapshot_ticks;
  // Inputs are held from the last final tick to as far as we predict.
  rollback.input_ticks = config_.snapshot_ticks + 256;
  session_ = std::make_unique<net::RollbackSession>(std::move(*sim), rollback);
  if (config_.debug_corrupt_at_tick != kNoTick) {
    const Tick corrupt_at = config_.debug_corrupt_at_tick;
    session_->set_step_hook([corrupt_at](game::Simulation& simulation, Tick tick) {
      if (tick != corrupt_at) return;
      (void)simulation.lane().perturb_for_drill();
    });
  }
  phase_ = ClientPhase::kLobby;
  last_ping_ = now - kLobbyPing;
  emit({ClientEventType::kJoined, kNoTick, player_, 0, 0, {}});
}

void ClientProtocol::Impl::on_match_start(const v1::MatchStart& start, TimePoint now) {
  phase_ = ClientPhase::kRunning;
  server_tick_ = start.server_tick();
  // The announced server tick is a one-way delay old when it arrives, and
  // our inputs take another one-way delay to reach the server: start a
  // round trip plus the target lead ahead of the announced tick.
  const double rtt_ticks = stats_.rtt_ms / 1000.0 * tick_rate_hz_;
  tick_clock_ = start.server_tick() + rtt_ticks + config_.target_lead_ticks;
  time_sync_.set_round_trip_ticks(rtt_ticks);
  last_update_ = now;
  emit({ClientEventType::kMatchStarted, start.server_tick(), player_, 0, 0, {}});
}

void ClientProtocol::Impl::on_match_end(const v1::MatchEnd& end, TimePoint now) {
  if (phase_ == ClientPhase::kRunning) {
    // Keep verifying until the last final tick is checked (or a moment has
    // passed), then report the end.
    phase_ = ClientPhase::kEnding;
    end_tick_ = end.last_final_tick();
    end_reason_ = end.reason();
    ending_deadline_ = now + kEndingWait;
  } else if (phase_ == ClientPhase::kLobby) {
    end_tick_ = end.last_final_tick();
    end_reason_ = end.reason();
    finish_ending(now);
  } else if (phase_ == ClientPhase::kEnded) {
    v1::Envelope bye;  // our goodbye was lost: the server is still waiting
    bye.mutable_disconnect()->set_reason("match over");
    send(bye, now);
  }
}

void ClientProtocol::Impl::on_pong(const v1::Pong& pong, TimePoint now) {
  const double rtt_ms =
      (static_cast<double>(micros_since_epoch(now)) - static_cast<double>(pong.client_time_us())) /
      1000.0;
  if (rtt_ms >= 0 && rtt_ms < 10000) {
    stats_.rtt_ms =
        stats_.rtt_ms == 0.0 ? rtt_ms : stats_.rtt_ms + 0.125 * (rtt_ms - stats_.rtt_ms);
    time_sync_.set_round_trip_ticks(stats_.rtt_ms / 1000.0 * tick_rate_hz_);
  }
  server_tick_ = std::max(server_tick_, pong.server_tick());
}

}  // namespace rwd::client
