// SPDX-License-Identifier: MIT
// The client protocol's lifecycle and its clockwork: joining, each update
// (timeouts, pings, stepping due ticks with our inputs, checking final
// ticks as they are simulated, the acknowledgement of final ticks, the end
// of the match), and the public API, which only forwards to the parts.
#include <chrono>

#include "client_protocol_impl.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

constexpr int kMaxStepsPerUpdate = 30;  // bounds a catch-up burst
constexpr size_t kMaxQueuedEvents = 4096;

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

Result<ClientProtocol> ClientProtocol::create(const ClientConfig& config, uint64_t join_nonce) {
  if (config.snapshot_ticks < 16 || config.snapshot_ticks > 1024) {
    return Status::Error(ErrorCode::kInvalidArgument, "snapshot_ticks must be in [16, 1024]");
  }
  auto impl = std::make_unique<Impl>(config, join_nonce);
  if (!config.connect_token.empty()) {
    Result<net::ConnectToken> token = net::read_connect_token(config.connect_token);
    if (!token.ok()) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "bad connect token: " + token.status().message());
    }
    impl->channel_.secure_with(*token);
  }
  return ClientProtocol(std::move(impl));
}

ClientProtocol::ClientProtocol(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ClientProtocol::ClientProtocol(ClientProtocol&&) noexcept = default;
ClientProtocol& ClientProtocol::operator=(ClientProtocol&&) noexcept = default;
ClientProtocol::~ClientProtocol() = default;

void ClientProtocol::connect(TimePoint now) {
  impl_->connect(now);
}
void ClientProtocol::receive(std::span<const uint8_t> datagram, TimePoint now) {
  impl_->receive(datagram, now);
}
int ClientProtocol::update(TimePoint now) {
  return impl_->update(now);
}
void ClientProtocol::disconnect(const std::string& reason, TimePoint now) {
  impl_->disconnect(reason, now);
}

void ClientProtocol::set_input_provider(InputProvider provider) {
  impl_->inputs_.set_provider(std::move(provider));
}
Status ClientProtocol::set_input(const rwd::PlayerInput& input) {
  if (impl_->session_ != nullptr) {
    Status status = check_input(impl_->session_->simulation().game().input_spec(), input);
    if (!status.ok()) return status;
  }
  impl_->inputs_.hold(input);
  return Status::Ok();
}

std::optional<std::span<const uint8_t>> ClientProtocol::next_datagram() {
  return impl_->channel_.next_datagram();
}

bool ClientProtocol::poll_event(ClientEvent& out) {
  if (impl_->events_.empty()) return false;
  out = std::move(impl_->events_.front());
  impl_->events_.pop_front();
  return true;
}

ClientPhase ClientProtocol::phase() const {
  return impl_->phase_;
}
uint32_t ClientProtocol::player() const {
  return impl_->player_;
}
ClientStats ClientProtocol::stats() const {
  return impl_->stats();
}

const game::Simulation* ClientProtocol::simulation() const {
  return impl_->session_ ? &impl_->session_->simulation() : nullptr;
}
const net::RollbackSession* ClientProtocol::rollback() const {
  return impl_->session_.get();
}

ClientProtocol::Impl::Impl(const ClientConfig& config, uint64_t join_nonce)
    : config_(config),
      nonce_(join_nonce),
      clock_(config.target_lead_ticks),
      finals_(config.snapshot_ticks) {}

ClientStats ClientProtocol::Impl::stats() const {
  ClientStats out = stats_;
  out.rtt_ms = clock_.rtt_ms();
  out.packets_sent = channel_.packets_sent();
  out.datagrams_dropped = channel_.datagrams_dropped();
  if (session_) {
    out.rollbacks = session_->stats().rollbacks;
    out.resimulated_ticks = session_->stats().resimulated_ticks;
    out.ticks_ahead = clock_.ticks_ahead(session_->current_tick());
  }
  out.input_lead_ticks = clock_.smoothed_lead();
  return out;
}

void ClientProtocol::Impl::connect(TimePoint now) {
  if (phase_ != ClientPhase::kIdle) return;
  phase_ = ClientPhase::kJoining;
  channel_.start(now);  // the silence clock starts now
  joined_at_ = now;
  clock_.start(now);
  last_join_sent_ = now - kJoinResend;  // send on the first update
  update(now);
}

void ClientProtocol::Impl::disconnect(const std::string& reason, TimePoint now) {
  if (phase_ == ClientPhase::kEnded || phase_ == ClientPhase::kIdle) return;
  v1::Envelope envelope;
  envelope.mutable_disconnect()->set_reason(reason.substr(0, net::kMaxStringBytes));
  if (channel_.connection_id() != 0) channel_.send(envelope, now);
  phase_ = ClientPhase::kEnded;
}

int ClientProtocol::Impl::update(TimePoint now) {
  const double dt = clock_.elapse(now);
  switch (phase_) {
    case ClientPhase::kIdle:
    case ClientPhase::kEnded:
      return 0;
    case ClientPhase::kJoining:
      if (seconds(now - joined_at_) > config_.join_timeout_s) {
        phase_ = ClientPhase::kEnded;
        emit({ClientEventType::kDisconnected, kNoTick, 0, 0, 0, "no answer to join"});
        return 0;
      }
      if (now - last_join_sent_ >= kJoinResend) send_join(now);
      return 0;
    case ClientPhase::kLobby:
    case ClientPhase::kRunning:
    case ClientPhase::kEnding:
      break;
  }
  if (seconds(now - channel_.last_receive_time()) > config_.server_timeout_s) {
    phase_ = ClientPhase::kEnded;
    emit({ClientEventType::kDisconnected, session_->current_tick(), player_, 0, 0,
          "server silent for " + std::to_string(config_.server_timeout_s) + " s"});
    return 0;
  }
  if (clock_.ping_due(now, phase_ == ClientPhase::kLobby)) {
    v1::Envelope envelope;
    envelope.mutable_ping()->set_client_time_us(TickClock::client_time_us(now));
    channel_.send(envelope, now);
  }
  if (phase_ != ClientPhase::kRunning && phase_ != ClientPhase::kEnding) return 0;

  clock_.run(dt);
  const Tick before = session_->current_tick();
  step_due_ticks(now);
  if (!session_->game_error().ok()) {
    // The rules failed here as they must have on the server, which ends
    // the match; nothing more can be simulated.
    phase_ = ClientPhase::kEnded;
    emit({ClientEventType::kDisconnected, session_->current_tick(), player_, 0, 0,
          "the game's rules failed: " + session_->game_error().message()});
    return session_->current_tick() - before;
  }
  verify_finals(now);
  resync_.resend_if_due(channel_, now);
  if (phase_ == ClientPhase::kEnding &&
      (stats_.last_final_tick >= end_tick_ || session_->final_tick() >= end_tick_ ||
       resync_.awaiting() || now >= ending_deadline_)) {
    finish_ending(now);
  }
  // Acknowledge new final ticks. A player's next input packet, due within a
  // tick, carries the acknowledgement, so it is not sent alone at once: that
  // would double the datagrams each player sends, and the server resends a
  // final tick only two ticks past its round trip. It goes alone when no
  // input packet took it within a tick period (at the prediction barrier,
  // after the last input) and always for a spectator, who sends no inputs.
  if (phase_ != ClientPhase::kEnded) {
    const InputSender::AckWait ack =
        inputs_.ack_wait(finals_.last_received(), now, clock_.period_s());
    if (ack == InputSender::AckWait::kDue ||
        (ack == InputSender::AckWait::kWaiting && spectator_)) {
      send_inputs(now);
    }
  }
  return session_->current_tick() - before;
}

void ClientProtocol::Impl::send_join(TimePoint now) {
  last_join_sent_ = now;
  if (!channel_.prepare_join(now)) return;
  v1::Envelope envelope;
  v1::JoinRequest* request = envelope.mutable_join_request();
  request->set_game(config_.game);
  request->set_spectator(config_.spectator);
  request->set_client_name(config_.name.substr(0, net::kMaxClientNameBytes));
  request->set_nonce(nonce_);
  channel_.send(envelope, now);
}

void ClientProtocol::Impl::step_due_ticks(TimePoint now) {
  // Never predict further than the snapshot ring can roll back from; the
  // clock waits at the barrier instead of running on and bursting later.
  const Tick barrier = finals_.last_received() + config_.snapshot_ticks - 8;
  const Tick target = clock_.due_through(barrier);
  bool new_input = false;
  for (int steps = 0; steps < kMaxStepsPerUpdate && session_->current_tick() < target &&
                      session_->current_tick() < barrier;
       ++steps) {
    const Tick t = session_->current_tick();
    if (!spectator_ && inputs_.due(t)) {
      const rwd::PlayerInput input = inputs_.take(t, session_->simulation().game().input_spec());
      (void)session_->add_input(player_, t, input);
      new_input = true;
    }
    if (!session_->advance()) {
      // The misprediction reaches past our snapshots: only the server can fix it.
      resync_.request(channel_, now);
    }
    if (!session_->game_error().ok()) break;
  }
  if (new_input) send_inputs(now);
}

void ClientProtocol::Impl::send_inputs(TimePoint now) {
  v1::Envelope envelope;
  inputs_.write_frame(player_, finals_.last_received(), *envelope.mutable_input_frame());
  channel_.send(envelope, now);
}

void ClientProtocol::Impl::verify_finals(TimePoint now) {
  while (!resync_.awaiting()) {
    const FinalTickVerifier::Check check = finals_.check_next(*session_);
    switch (check.verdict) {
      case FinalTickVerifier::Verdict::kNone:
        return;
      case FinalTickVerifier::Verdict::kLost:
        resync_.request(channel_, now);  // history we can no longer re-simulate
        return;
      case FinalTickVerifier::Verdict::kAgreed:
        ++stats_.final_ticks_verified;
        stats_.last_final_tick = check.tick;
        if (events_.size() < kMaxQueuedEvents) {
          emit({ClientEventType::kFinalTick,
                check.tick,
                player_,
                check.local_checksum,
                check.server_checksum,
                {}});
        }
        break;
      case FinalTickVerifier::Verdict::kMismatch:
        ++stats_.desyncs;
        emit({ClientEventType::kDesync,
              check.tick,
              player_,
              check.local_checksum,
              check.server_checksum,
              {}});
        resync_.on_desync(*session_, check.tick, check.local_checksum, check.server_checksum,
                          channel_, now);
        break;
    }
  }
}

void ClientProtocol::Impl::finish_ending(TimePoint now) {
  phase_ = ClientPhase::kEnded;
  emit({ClientEventType::kMatchEnded, end_tick_, player_, 0, 0, end_reason_});
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("match over");
  channel_.send(bye, now);
}

}  // namespace rwd::client
