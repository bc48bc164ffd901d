// SPDX-License-Identifier: MIT
// The client protocol's inbound side: each datagram through the channel
// (cookie, handshake, opening), decoded, dropped unless it is for this
// connection and new, and dispatched: the messages that move the phase on
// (the join's answer, the match's start and end, a disconnect) are handled
// here; the rest go to the part they concern, and what one part's news
// means for another is decided here.
#include <chrono>

#include "client_protocol_impl.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

constexpr auto kEndingWait = std::chrono::milliseconds(1500);

}  // namespace

void ClientProtocol::Impl::receive(std::span<const uint8_t> datagram, TimePoint now) {
  ++stats_.packets_received;
  if (phase_ == ClientPhase::kIdle) {
    ++stats_.packets_rejected;  // nothing asked for yet
    return;
  }
  const ServerChannel::Opened opened =
      channel_.open(datagram, phase_ == ClientPhase::kJoining, now);
  switch (opened.kind) {
    case ServerChannel::Inbound::kRejected:
      ++stats_.packets_rejected;
      return;
    case ServerChannel::Inbound::kConsumed:
      return;
    case ServerChannel::Inbound::kJoinNow:
      send_join(now);
      return;
    case ServerChannel::Inbound::kJoinSoon:
      last_join_sent_ = now - kJoinResend;  // the join goes out on the next update
      return;
    case ServerChannel::Inbound::kEnvelope:
      break;
  }
  auto decoded = net::decode_envelope(opened.bytes);
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
    channel_.set_connection_id(envelope.join_accept().connection_id());
  }
  switch (channel_.admit(envelope, now)) {
    case ServerChannel::Admission::kForeign:
      ++stats_.packets_rejected;
      return;
    case ServerChannel::Admission::kRepeat:
      return;
    case ServerChannel::Admission::kNew:
      break;
  }

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
      clock_.on_pong(envelope.pong().client_time_us(), envelope.pong().server_tick(), now);
      break;
    case v1::Envelope::kRelayedInputs:
      if (session_) finals_.on_relayed(*session_, envelope.relayed_inputs());
      break;
    case v1::Envelope::kFinalTicks:
      if (session_) on_final_ticks(envelope.final_ticks(), now);
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
  clock_.seed_round_trip(std::chrono::duration<double, std::milli>(now - joined_at_).count());
  player_ = accept.player();
  player_count_ = accept.player_count();
  spectator_ = accept.spectator();
  finals_.seat(player_, player_count_);
  clock_.set_tick_rate(accept.tick_rate_hz());
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
  clock_.ping_now(now);
  emit({ClientEventType::kJoined, kNoTick, player_, 0, 0, {}});
}

void ClientProtocol::Impl::on_match_start(const v1::MatchStart& start, TimePoint now) {
  phase_ = ClientPhase::kRunning;
  clock_.start_match(start.server_tick(), now);
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
    channel_.send(bye, now);
  }
}

void ClientProtocol::Impl::on_final_ticks(const v1::FinalTicks& finals, TimePoint now) {
  // Other players' inputs ride along, whatever becomes of the final ticks.
  finals_.on_relayed_runs(*session_, finals);
  clock_.on_server_tick(finals.server_tick());
  inputs_.on_ack(finals.input_ack_tick());
  if (inputs_.next_input_tick() > 0) clock_.on_lead_report(finals.input_lead_ticks());
  // While desynced, final ticks are neither applied nor acknowledged: the
  // server resends them from the resync snapshot's tick on.
  if (resync_.awaiting()) return;
  switch (finals_.apply(*session_, finals)) {
    case FinalTickVerifier::Applied::kOk:
      return;
    case FinalTickVerifier::Applied::kRejected:
      ++stats_.packets_rejected;
      return;
    case FinalTickVerifier::Applied::kTooFar:
      resync_.request(channel_, now);
      return;
  }
}

void ClientProtocol::Impl::on_resync_chunk(const v1::ResyncChunk& chunk, TimePoint now) {
  const DesyncRecovery::ChunkOutcome result = resync_.on_chunk(
      *session_, chunk, inputs_.last_final_acked(), finals_.last_received(), channel_, now);
  switch (result.outcome) {
    case DesyncRecovery::Outcome::kNone:
      return;
    case DesyncRecovery::Outcome::kRejected:
      ++stats_.packets_rejected;
      return;
    case DesyncRecovery::Outcome::kRefused:
      ++stats_.resyncs_refused;
      emit({ClientEventType::kResyncRefused, result.tick, player_, 0, 0, result.reason});
      return;
    case DesyncRecovery::Outcome::kLoaded:
      break;
  }
  // The server resends final ticks from the snapshot's tick; the snapshot
  // (its checksum checked) stands for the final ticks before it that our
  // own simulation never verified.
  stats_.final_ticks_resynced += finals_.on_resync_loaded(result.tick);
  inputs_.skip_to(result.tick);
  clock_.reanchor(result.tick);
  ++stats_.resyncs;
  emit({ClientEventType::kResynced,
        result.tick,
        player_,
        session_->simulation().checksum(),
        result.checksum,
        {}});
  step_due_ticks(now);
}

}  // namespace rwd::client
