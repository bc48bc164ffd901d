// SPDX-License-Identifier: MIT
#include "rewind/client/client_session.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"
#include "rewind/proto/message_inputs.h"

namespace rwd::client {
namespace {

constexpr auto kJoinResend = std::chrono::milliseconds(250);
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

Status check_snapshot_ticks(const ClientConfig& config) {
  if (config.snapshot_ticks < 16 || config.snapshot_ticks > 1024) {
    return Status::Error(ErrorCode::kInvalidArgument, "snapshot_ticks must be in [16, 1024]");
  }
  return Status::Ok();
}

}  // namespace

Result<std::unique_ptr<ClientSession>> ClientSession::create(asio::io_context& io,
                                                             const ClientConfig& config) {
  std::error_code error;
  const asio::ip::address address = asio::ip::make_address(config.server_address, error);
  if (error) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "bad server address '" + config.server_address + "': " + error.message());
  }
  if (Status status = check_snapshot_ticks(config); !status.ok()) return status;
  if (config.faults) {
    if (Status status = net::validate_fault_config(*config.faults); !status.ok()) return status;
  }
  auto socket = net::UdpEndpoint::open(io, address.is_v6() ? "::" : "0.0.0.0", 0);
  if (!socket.ok()) return socket.status();
  auto session = std::make_unique<ClientSession>(
      io, config, std::move(*socket), asio::ip::udp::endpoint(address, config.server_port));
  if (Status status = use_connect_token(*session, config); !status.ok()) return status;
  return session;
}

Status ClientSession::use_connect_token(ClientSession& session, const ClientConfig& config) {
  if (config.connect_token.empty()) return Status::Ok();
  Result<net::ConnectToken> token = net::read_connect_token(config.connect_token);
  if (!token.ok()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "bad connect token: " + token.status().message());
  }
  session.handshake_.emplace(*token);
  return Status::Ok();
}

Result<std::unique_ptr<ClientSession>> ClientSession::create_detached(const ClientConfig& config,
                                                                      SendFn send) {
  if (Status status = check_snapshot_ticks(config); !status.ok()) return status;
  if (config.faults) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "network faults are injected on a socket; a detached session has none");
  }
  if (!send) return Status::Error(ErrorCode::kInvalidArgument, "a detached session needs a sender");
  auto session = std::make_unique<ClientSession>(config, std::move(send));
  if (Status status = use_connect_token(*session, config); !status.ok()) return status;
  return session;
}

ClientSession::ClientSession(const ClientConfig& config, SendFn send)
    : config_(config),
      send_(std::move(send)),
      connection_(net::SteadyClock::now()),
      time_sync_(net::TimeSyncConfig{config.target_lead_ticks}) {
  std::random_device device;
  nonce_ = (uint64_t{device()} << 32) | device();
}

ClientSession::ClientSession(asio::io_context& io, const ClientConfig& config,
                             net::UdpEndpoint socket, asio::ip::udp::endpoint server)
    : config_(config),
      socket_(std::move(socket)),
      server_(server),
      connection_(net::SteadyClock::now()),
      time_sync_(net::TimeSyncConfig{config.target_lead_ticks}) {
  if (config_.faults) {
    // Both directions see the configured conditions, with independent streams.
    net::FaultConfig out = *config_.faults;
    net::FaultConfig in = *config_.faults;
    in.seed = out.seed ^ 0xA5A5A5A5DEADBEEFull;
    outbound_faults_.emplace(std::move(*net::FaultyLink::create(
        io, out, [this](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& to) {
          socket_->send_to(bytes, to);
        })));
    inbound_faults_.emplace(std::move(*net::FaultyLink::create(
        io, in, [this](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& from) {
          on_datagram(bytes, from);
        })));
  }
  socket_->start_receiving(
      [this](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& from) {
        if (inbound_faults_) {
          inbound_faults_->send(bytes, from);
        } else {
          on_datagram(bytes, from);
        }
      });
  std::random_device device;
  nonce_ = (uint64_t{device()} << 32) | device();
}

ClientSession::~ClientSession() {
  // Close first so no receive handler can reach a half-destroyed session.
  if (socket_) socket_->close();
}

void ClientSession::connect(TimePoint now) {
  if (phase_ != Phase::kIdle) return;
  phase_ = Phase::kJoining;
  connection_ = net::Connection(now);  // the silence clock starts now, on the caller's clock
  joined_at_ = now;
  last_update_ = now;
  last_join_sent_ = now - kJoinResend;  // send on the first update
  update(now);
}

void ClientSession::disconnect(const std::string& reason, TimePoint now) {
  if (phase_ == Phase::kEnded || phase_ == Phase::kIdle) return;
  v1::Envelope envelope;
  envelope.mutable_disconnect()->set_reason(reason);
  if (connection_.connection_id() != 0) send(envelope, now);
  phase_ = Phase::kEnded;
}

bool ClientSession::poll_event(ClientEvent& out) {
  if (events_.empty()) return false;
  out = std::move(events_.front());
  events_.pop_front();
  return true;
}

ClientStats ClientSession::stats() const {
  ClientStats out = stats_;
  if (session_) {
    out.rollbacks = session_->stats().rollbacks;
    out.resimulated_ticks = session_->stats().resimulated_ticks;
    const double one_way_ticks = out.rtt_ms / 2000.0 * tick_rate_hz_;
    out.ticks_ahead = static_cast<int32_t>(
        std::lround(session_->current_tick() - (server_tick_ + one_way_ticks)));
  }
  out.input_lead_ticks = time_sync_.smoothed_lead();
  return out;
}

int ClientSession::update(TimePoint now) {
  const double dt = std::max(0.0, seconds(now - last_update_));
  last_update_ = now;
  switch (phase_) {
    case Phase::kIdle:
    case Phase::kEnded:
      return 0;
    case Phase::kJoining:
      if (seconds(now - joined_at_) > config_.join_timeout_s) {
        phase_ = Phase::kEnded;
        emit({ClientEventType::kDisconnected, kNoTick, 0, 0, 0, "no answer to join"});
        return 0;
      }
      if (now - last_join_sent_ >= kJoinResend) {
        last_join_sent_ = now;
        if (handshake_ && !handshake_->session()) {
          transmit(handshake_->request());  // until a challenge comes back
          return 0;
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
      return 0;
    case Phase::kLobby:
    case Phase::kRunning:
    case Phase::kEnding:
      break;
  }
  if (seconds(now - connection_.last_receive_time()) > config_.server_timeout_s) {
    phase_ = Phase::kEnded;
    emit({ClientEventType::kDisconnected, session_->current_tick(), player_, 0, 0,
          "server silent for " + std::to_string(config_.server_timeout_s) + " s"});
    return 0;
  }
  if (now - last_ping_ >= (phase_ == Phase::kLobby ? kLobbyPing : kMatchPing)) {
    last_ping_ = now;
    v1::Envelope envelope;
    envelope.mutable_ping()->set_client_time_us(micros_since_epoch(now));
    send(envelope, now);
  }
  if (phase_ != Phase::kRunning && phase_ != Phase::kEnding) return 0;

  // The tick clock runs a little fast or slow to keep our inputs arriving
  // just ahead of the server's need.
  tick_clock_ += dt / (period_s() * time_sync_.period_scale());
  tick_clock_ += time_sync_.take_jump();
  const Tick before = session_->current_tick();
  step_due_ticks(now);
  verify_finals(now);
  if (awaiting_resync_ && now - last_report_sent_ >= kReportResend) send_desync_report(now);
  if (phase_ == Phase::kEnding &&
      (stats_.last_final_tick >= end_tick_ || session_->final_tick() >= end_tick_ ||
       awaiting_resync_ || now >= ending_deadline_)) {
    finish_ending(now);
  }
  // Acknowledge new final ticks even when no tick was stepped (at the
  // prediction barrier nothing else would carry the acknowledgement).
  if (phase_ != Phase::kEnded && last_final_received_ > last_final_acked_) send_inputs(now);
  return session_->current_tick() - before;
}

void ClientSession::step_due_ticks(TimePoint now) {
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
      game::PlayerInput input = provider_ ? provider_(t) : held_input_;
      input.axis_x =
          static_cast<int16_t>(std::clamp<int>(input.axis_x, -game::kAxisMax, game::kAxisMax));
      input.axis_y =
          static_cast<int16_t>(std::clamp<int>(input.axis_y, -game::kAxisMax, game::kAxisMax));
      (void)session_->add_input(player_, t, input);
      unacked_.emplace_back(t, input);
      next_input_tick_ = t + 1;
      new_input = true;
    }
    if (!session_->advance()) {
      // The misprediction reaches past our snapshots: only the server can fix it.
      request_resync(now);
    }
  }
  if (new_input) send_inputs(now);
}

void ClientSession::send_inputs(TimePoint now) {
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
  for (const auto& [tick, input] : unacked_) *frame->add_inputs() = proto::to_wire(input);
  send(envelope, now);
}

void ClientSession::on_datagram(std::span<const uint8_t> bytes,
                                const asio::ip::udp::endpoint& from) {
  if (from != server_) {
    ++stats_.packets_received;
    ++stats_.packets_rejected;
    return;
  }
  receive(bytes, net::SteadyClock::now());
}

void ClientSession::receive(std::span<const uint8_t> datagram, TimePoint now) {
  ++stats_.packets_received;
  if (handshake_) {
    // A secure server: a challenge answers our request; anything else must
    // be a payload sealed for our session.
    const std::optional<net::SecurePacket> kind = net::secure_packet_kind(datagram);
    if (kind == net::SecurePacket::kChallenge && phase_ == Phase::kJoining) {
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
  }
  auto decoded = net::decode_envelope(datagram);
  if (!decoded.ok()) {
    ++stats_.packets_rejected;
    return;
  }
  handle(*decoded, now);
}

void ClientSession::handle(const v1::Envelope& envelope, TimePoint now) {
  if (envelope.has_join_reject()) {
    if (phase_ == Phase::kJoining && envelope.join_reject().nonce() == nonce_) {
      phase_ = Phase::kEnded;
      emit({ClientEventType::kRejected, kNoTick, 0, 0, 0, envelope.join_reject().reason()});
    }
    return;
  }
  if (envelope.has_join_accept()) {
    if (phase_ != Phase::kJoining || envelope.join_accept().nonce() != nonce_) return;
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
      if (phase_ == Phase::kLobby) on_match_start(envelope.match_start(), now);
      break;
    case v1::Envelope::kMatchEnd:
      if (phase_ == Phase::kRunning) {
        // Keep verifying until the last final tick is checked (or a moment
        // has passed), then report the end.
        phase_ = Phase::kEnding;
        end_tick_ = envelope.match_end().last_final_tick();
        end_reason_ = envelope.match_end().reason();
        ending_deadline_ = now + std::chrono::milliseconds(1500);
      } else if (phase_ == Phase::kLobby) {
        end_tick_ = envelope.match_end().last_final_tick();
        end_reason_ = envelope.match_end().reason();
        finish_ending(now);
      } else if (phase_ == Phase::kEnded) {
        v1::Envelope bye;  // our goodbye was lost: the server is still waiting
        bye.mutable_disconnect()->set_reason("match over");
        send(bye, now);
      }
      break;
    case v1::Envelope::kPong: {
      const double rtt_ms = (static_cast<double>(micros_since_epoch(now)) -
                             static_cast<double>(envelope.pong().client_time_us())) /
                            1000.0;
      if (rtt_ms >= 0 && rtt_ms < 10000) {
        stats_.rtt_ms =
            stats_.rtt_ms == 0.0 ? rtt_ms : stats_.rtt_ms + 0.125 * (rtt_ms - stats_.rtt_ms);
        time_sync_.set_round_trip_ticks(stats_.rtt_ms / 1000.0 * tick_rate_hz_);
      }
      server_tick_ = std::max(server_tick_, envelope.pong().server_tick());
      break;
    }
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
      if (session_ && (phase_ == Phase::kRunning || phase_ == Phase::kEnding))
        on_resync_chunk(envelope.resync_chunk(), now);
      break;
    case v1::Envelope::kDisconnect:
      phase_ = Phase::kEnded;
      emit(
          {ClientEventType::kDisconnected, kNoTick, player_, 0, 0, envelope.disconnect().reason()});
      break;
    default:
      ++stats_.packets_rejected;
      break;
  }
}

void ClientSession::on_join_accept(const v1::JoinAccept& accept, TimePoint now) {
  auto sim = game::Simulation::create(accept.game(), {accept.player_count(), accept.seed()});
  // A player's slot is below player_count, a spectator's seat past it.
  const bool seat_ok = accept.spectator() ? accept.player() >= accept.player_count()
                                          : accept.player() < accept.player_count();
  if (!sim.ok() || !seat_ok || accept.tick_rate_hz() == 0) {
    phase_ = Phase::kEnded;
    emit({ClientEventType::kRejected, kNoTick, 0, 0, 0,
          "cannot build the server's match: " + sim.status().message()});
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
    phase_ = Phase::kEnded;
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
      // Nudge the highest-index dynamic body by a millimetre: small enough
      // to look like a real float divergence, big enough to matter.
      std::vector<sim::BodyId> ids;
      simulation.world().body_ids(ids);
      for (auto it = ids.rbegin(); it != ids.rend(); ++it) {
        if (simulation.world().kind(*it) != sim::BodyKind::kDynamic) continue;
        sim::Vec3 p = simulation.world().position(*it);
        p.x += 0.001f;
        (void)simulation.world().set_transform(*it, p, simulation.world().rotation(*it));
        break;
      }
    });
  }
  phase_ = Phase::kLobby;
  last_ping_ = now - kLobbyPing;
  emit({ClientEventType::kJoined, kNoTick, player_, 0, 0, {}});
}

void ClientSession::on_match_start(const v1::MatchStart& start, TimePoint now) {
  phase_ = Phase::kRunning;
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

void ClientSession::finish_ending(TimePoint now) {
  phase_ = Phase::kEnded;
  emit({ClientEventType::kMatchEnded, end_tick_, player_, 0, 0, end_reason_});
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("match over");
  send(bye, now);
}

void ClientSession::verify_finals(TimePoint now) {
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

void ClientSession::send(v1::Envelope& envelope, TimePoint now) {
  connection_.stamp(envelope, now);
  if (!net::encode_envelope(envelope, encode_buffer_).ok()) return;
  if (!handshake_) {
    transmit(encode_buffer_);
    return;
  }
  if (!handshake_->session()) return;  // nothing leaves in the clear
  handshake_->session()->seal(encode_buffer_, sealed_buffer_);
  transmit(sealed_buffer_);
}

void ClientSession::transmit(std::span<const uint8_t> datagram) {
  ++stats_.packets_sent;
  if (send_) {
    send_(datagram);
  } else if (outbound_faults_) {
    outbound_faults_->send(datagram, server_);
  } else {
    socket_->send_to(datagram, server_);
  }
}

}  // namespace rwd::client
