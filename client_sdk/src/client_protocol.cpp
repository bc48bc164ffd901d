// SPDX-License-Identifier: MIT
// The client protocol's lifecycle and its own clockwork: joining, the tick
// clock, taking and sending our inputs, checking final ticks as they are
// simulated, the end of the match, and everything it sends.
#include <algorithm>
#include <cmath>

#include "client_protocol_impl.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"

namespace rwd::client {
namespace {

constexpr auto kJoinResend = std::chrono::milliseconds(250);
// A tokenless server takes a cookie for one to two of its windows: a join
// still unanswered after this long asks for a fresh one first.
constexpr auto kCookieRefresh = std::chrono::seconds(3);
static_assert(kCookieRefresh < std::chrono::seconds(net::kCookieWindowS));
constexpr auto kLobbyPing = std::chrono::milliseconds(100);
constexpr auto kMatchPing = std::chrono::milliseconds(250);
constexpr auto kReportResend = std::chrono::milliseconds(500);
constexpr int kMaxStepsPerUpdate = 30;      // bounds a catch-up burst
constexpr size_t kMaxInputsPerPacket = 64;  // redundancy: every unacked input, up to this
constexpr size_t kMaxQueuedEvents = 4096;

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

uint64_t micros_since_epoch(TimePoint t) {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count());
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
    impl->handshake_.emplace(*token);
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
  if (impl_->phase_ == ClientPhase::kEnded || impl_->phase_ == ClientPhase::kIdle) return;
  v1::Envelope envelope;
  envelope.mutable_disconnect()->set_reason(reason.substr(0, net::kMaxStringBytes));
  if (impl_->connection_.connection_id() != 0) impl_->send(envelope, now);
  impl_->phase_ = ClientPhase::kEnded;
}

void ClientProtocol::set_input_provider(InputProvider provider) {
  impl_->provider_ = std::move(provider);
}
Status ClientProtocol::set_input(const rwd::PlayerInput& input) {
  if (impl_->session_ != nullptr) {
    Status status = check_input(impl_->session_->simulation().game().input_spec(), input);
    if (!status.ok()) return status;
  }
  impl_->held_input_ = input;
  return Status::Ok();
}

std::optional<std::span<const uint8_t>> ClientProtocol::next_datagram() {
  return impl_->outbox_.pop();
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
  const Impl& p = *impl_;
  ClientStats out = p.stats_;
  if (p.session_) {
    out.rollbacks = p.session_->stats().rollbacks;
    out.resimulated_ticks = p.session_->stats().resimulated_ticks;
    const double one_way_ticks = out.rtt_ms / 2000.0 * p.tick_rate_hz_;
    out.ticks_ahead = static_cast<int32_t>(
        std::lround(p.session_->current_tick() - (p.server_tick_ + one_way_ticks)));
  }
  out.input_lead_ticks = p.time_sync_.smoothed_lead();
  return out;
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
      time_sync_(net::TimeSyncConfig{config.target_lead_ticks}) {}

void ClientProtocol::Impl::connect(TimePoint now) {
  if (phase_ != ClientPhase::kIdle) return;
  phase_ = ClientPhase::kJoining;
  connection_ = net::Connection(now);  // the silence clock starts now
  joined_at_ = now;
  last_update_ = now;
  last_join_sent_ = now - kJoinResend;  // send on the first update
  update(now);
}

int ClientProtocol::Impl::update(TimePoint now) {
  const double dt = std::max(0.0, seconds(now - last_update_));
  last_update_ = std::max(last_update_, now);
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
  if (seconds(now - connection_.last_receive_time()) > config_.server_timeout_s) {
    phase_ = ClientPhase::kEnded;
    emit({ClientEventType::kDisconnected, session_->current_tick(), player_, 0, 0,
          "server silent for " + std::to_string(config_.server_timeout_s) + " s"});
    return 0;
  }
  if (now - last_ping_ >= (phase_ == ClientPhase::kLobby ? kLobbyPing : kMatchPing)) {
    last_ping_ = now;
    v1::Envelope envelope;
    envelope.mutable_ping()->set_client_time_us(micros_since_epoch(now));
    send(envelope, now);
  }
  if (phase_ != ClientPhase::kRunning && phase_ != ClientPhase::kEnding) return 0;

  // The tick clock runs a little fast or slow to keep our inputs arriving
  // just ahead of the server's need.
  tick_clock_ += dt / (period_s() * time_sync_.period_scale());
  tick_clock_ += time_sync_.take_jump();
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
  if (awaiting_resync_ && now - last_report_sent_ >= kReportResend) send_desync_report(now);
  if (phase_ == ClientPhase::kEnding &&
      (stats_.last_final_tick >= end_tick_ || session_->final_tick() >= end_tick_ ||
       awaiting_resync_ || now >= ending_deadline_)) {
    finish_ending(now);
  }
  // Acknowledge new final ticks. A player's next input packet, due within a
  // tick, carries the acknowledgement, so it is not sent alone at once: that
  // would double the datagrams each player sends, and the server resends a
  // final tick only two ticks past its round trip. It goes alone when no
  // input packet took it within a tick period (at the prediction barrier,
  // after the last input) and always for a spectator, who sends no inputs.
  if (phase_ != ClientPhase::kEnded && last_final_received_ > last_final_acked_) {
    if (!ack_waiting_) {
      ack_waiting_ = true;
      ack_waiting_since_ = now;
    }
    if (spectator_ || seconds(now - ack_waiting_since_) >= period_s()) send_inputs(now);
  }
  return session_->current_tick() - before;
}

void ClientProtocol::Impl::send_join(TimePoint now) {
  last_join_sent_ = now;
  if (handshake_ && !handshake_->session()) {
    transmit(handshake_->request());  // until a challenge comes back
    return;
  }
  if (!handshake_ && (!cookie_ || now - cookie_at_ >= kCookieRefresh)) {
    cookie_.reset();
    if (hello_.empty()) hello_ = net::make_hello();
    transmit(hello_);  // until a cookie comes back
    return;
  }
  // Until the server speaks, it may have missed our response.
  if (handshake_ && !secure_confirmed_) transmit(handshake_response_);
  v1::Envelope envelope;
  v1::JoinRequest* request = envelope.mutable_join_request();
  request->set_game(config_.game);
  request->set_spectator(config_.spectator);
  request->set_client_name(config_.name.substr(0, net::kMaxClientNameBytes));
  request->set_nonce(nonce_);
  send(envelope, now);
}

void ClientProtocol::Impl::step_due_ticks(TimePoint now) {
  // Never predict further than the snapshot ring can roll back from; the
  // clock waits at the barrier instead of running on and bursting later.
  const Tick barrier = last_final_received_ + config_.snapshot_ticks - 8;
  tick_clock_ = std::min(tick_clock_, static_cast<double>(barrier) + 1.0);
  const Tick target = static_cast<Tick>(std::floor(tick_clock_));
  bool new_input = false;
  for (int steps = 0; steps < kMaxStepsPerUpdate && session_->current_tick() < target &&
                      session_->current_tick() < barrier;
       ++steps) {
    const Tick t = session_->current_tick();
    if (!spectator_ && t >= next_input_tick_) {
      rwd::PlayerInput input = provider_ ? provider_(t) : held_input_;
      // The server would refuse it, and the other players would never see
      // it: the neutral input is played and sent in its place.
      if (!check_input(session_->simulation().game().input_spec(), input).ok()) input = {};
      (void)session_->add_input(player_, t, input);
      unacked_.emplace_back(t, input);
      next_input_tick_ = t + 1;
      new_input = true;
    }
    if (!session_->advance()) {
      // The misprediction reaches past our snapshots: only the server can fix it.
      request_resync(now);
    }
    if (!session_->game_error().ok()) break;
  }
  if (new_input) send_inputs(now);
}

void ClientProtocol::Impl::send_inputs(TimePoint now) {
  while (!unacked_.empty() &&
         (unacked_.front().first <= input_ack_ || unacked_.size() > kMaxInputsPerPacket)) {
    unacked_.pop_front();
  }
  v1::Envelope envelope;
  v1::InputFrame* frame = envelope.mutable_input_frame();
  frame->set_player(player_);
  frame->set_first_tick(unacked_.empty() ? std::max<Tick>(next_input_tick_, 0)
                                         : unacked_.front().first);
  frame->set_last_final_tick_seen(last_final_received_);
  last_final_acked_ = last_final_received_;
  ack_waiting_ = false;
  for (const auto& [tick, input] : unacked_) *frame->add_inputs() = proto::to_wire(input);
  send(envelope, now);
}

void ClientProtocol::Impl::verify_finals(TimePoint now) {
  while (!pending_finals_.empty() && !awaiting_resync_) {
    const auto [tick, server_checksum] = pending_finals_.front();
    if (tick >= session_->current_tick()) break;  // not simulated yet
    std::optional<uint64_t> local;
    if (session_->finalize_through(tick)) local = session_->checksum_after(tick);
    if (!local) {
      request_resync(now);  // history we can no longer re-simulate
      break;
    }
    pending_finals_.pop_front();
    if (*local == server_checksum) {
      ++stats_.final_ticks_verified;
      stats_.last_final_tick = tick;
      agreed_through_ = tick;
      if (events_.size() < kMaxQueuedEvents) {
        emit({ClientEventType::kFinalTick, tick, player_, *local, server_checksum, {}});
      }
      continue;
    }
    ++stats_.desyncs;
    emit({ClientEventType::kDesync, tick, player_, *local, server_checksum, {}});
    awaiting_resync_ = true;
    desync_tick_ = tick;
    desync_server_checksum_ = server_checksum;
    desync_local_checksum_ = *local;
    ++report_id_;
    report_sends_ = 0;
    state_buffer_.clear();
    (void)session_->serialize_state_at(tick + 1, state_buffer_);
    send_desync_report(now);
  }
}

void ClientProtocol::Impl::finish_ending(TimePoint now) {
  phase_ = ClientPhase::kEnded;
  emit({ClientEventType::kMatchEnded, end_tick_, player_, 0, 0, end_reason_});
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("match over");
  send(bye, now);
}

void ClientProtocol::Impl::send(v1::Envelope& envelope, TimePoint now) {
  connection_.stamp(envelope, now);
  if (!net::encode_envelope(envelope, encode_buffer_).ok()) return;
  if (!handshake_) {
    if (envelope.has_join_request() && cookie_) {
      net::frame_join(*cookie_, encode_buffer_, framed_buffer_);
      transmit(framed_buffer_);
      return;
    }
    transmit(encode_buffer_);
    return;
  }
  if (!handshake_->session()) return;  // nothing leaves in the clear
  handshake_->session()->seal(encode_buffer_, sealed_buffer_);
  transmit(sealed_buffer_);
}

void ClientProtocol::Impl::transmit(std::span<const uint8_t> datagram) {
  if (!outbox_.push(datagram)) {
    ++stats_.datagrams_dropped;
    return;
  }
  ++stats_.packets_sent;
}

}  // namespace rwd::client
