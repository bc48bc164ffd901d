// SPDX-License-Identifier: MIT
#include "rewind/server/match_host.h"

#include <algorithm>
#include <cmath>

#include "host_log.h"
#include "rewind/net/connection_id.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/input_wire.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/replay/replay_header.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::printable;

double seconds_between(TimePoint a, TimePoint b) {
  return std::chrono::duration<double>(b - a).count();
}

google::protobuf::ArenaOptions arena_on(char* block, size_t size) {
  google::protobuf::ArenaOptions options;
  options.initial_block = block;
  options.initial_block_size = size;
  return options;
}

// Frees everything on an arena when the scope ends.
struct ArenaReset {
  google::protobuf::Arena& arena;
  ~ArenaReset() { arena.Reset(); }
};

}  // namespace

Result<std::unique_ptr<MatchHost>> MatchHost::create(const MatchConfig& config, SendFn send,
                                                     TimePoint now, MatchEnvironment env) {
  if (Status status = config.validate(); !status.ok()) return status;
  auto sim = game::Simulation::create(config.game, {config.players, config.seed});
  if (!sim.ok()) return sim.status();

  net::RollbackConfig rollback;
  rollback.snapshot_ticks = config.snapshot_ticks();
  rollback.input_ticks = 256;
  auto session = std::make_unique<net::RollbackSession>(std::move(*sim), rollback);

  std::optional<replay::ReplayWriter> writer;
  if (!config.replay_path.empty()) {
    replay::RecordingSetup recording;
    recording.match = session->simulation().setup();
    recording.tick_rate_hz = config.tick_rate_hz;
    recording.window_ticks = static_cast<uint32_t>(config.window_ticks);
    recording.keyframe_interval = static_cast<uint32_t>(config.keyframe_interval);
    recording.server_version = "rewind-server 0.1.0";
    recording.started_unix_ms = env.unix_ms();
    const v1::ReplayHeader header =
        replay::make_replay_header(session->simulation().game(), recording);
    replay::ReplayWriterOptions options;
    options.overwrite = config.replay_overwrite;
    auto opened = replay::ReplayWriter::open(config.replay_path, header, options);
    if (!opened.ok()) return opened.status();
    writer.emplace(std::move(*opened));
    // The initial state as a keyframe lets a verifier check the scene itself.
    std::vector<uint8_t> state;
    session->simulation().serialize(state);
    if (Status status = writer->append_keyframe(kNoTick, state); !status.ok()) return status;
  }
  if (!config.desync_dir.empty()) {
    if (Status status = env.create_directories(config.desync_dir); !status.ok()) {
      return Status::Error(ErrorCode::kIo, "desync directory: " + status.message());
    }
  }
  return std::make_unique<MatchHost>(config, std::move(send), std::move(session), std::move(writer),
                                     now, std::move(env));
}

MatchHost::MatchHost(const MatchConfig& config, SendFn send,
                     std::unique_ptr<net::RollbackSession> session,
                     std::optional<replay::ReplayWriter> replay, TimePoint now,
                     MatchEnvironment env)
    : config_(config),
      send_(std::move(send)),
      session_(std::move(session)),
      recorder_(std::move(replay), static_cast<uint32_t>(config.keyframe_interval)),
      peers_(config.players),
      spectators_(config.max_spectators),
      created_(now),
      started_(now),
      tick_started_(now),
      ended_(now),
      ids_(net::ConnectionIdGenerator::from_os_entropy()),
      arena_blocks_(new char[kReceiveArenaBytes + kBroadcastArenaBytes]),
      receive_arena_(arena_on(arena_blocks_.get(), kReceiveArenaBytes)),
      broadcast_arena_(arena_on(arena_blocks_.get() + kReceiveArenaBytes, kBroadcastArenaBytes)),
      forensics_(config.desync_dir, std::move(env)) {
  final_inputs_.resize(config.players);
  final_history_.assign(kFinalHistory, FinalRecord{});
}

const char* phase_name(MatchHost::Phase phase) {
  switch (phase) {
    case MatchHost::Phase::kLobby:
      return "lobby";
    case MatchHost::Phase::kRunning:
      return "running";
    case MatchHost::Phase::kClosing:
      return "closing";
    case MatchHost::Phase::kEnded:
      break;
  }
  return "ended";
}

MatchStats MatchHost::stats() const {
  MatchStats out = stats_;
  out.rollbacks = session_->stats().rollbacks;
  out.resimulated_ticks = session_->stats().resimulated_ticks;
  out.last_final_tick = next_final_ - 1;
  out.ticks_final = next_final_;
  out.duration_s = phase_ == Phase::kLobby ? 0.0 : seconds_between(started_, ended_);
  return out;
}

uint32_t MatchHost::players_connected() const {
  uint32_t count = 0;
  for (const Peer& peer : peers_) count += (peer.joined && peer.connected) ? 1 : 0;
  return count;
}

bool MatchHost::seated(uint32_t slot, const Endpoint& endpoint) const {
  if (slot >= peers_.size() + spectators_.size()) return false;
  const Peer& peer = slot < peers_.size() ? peers_[slot] : spectators_[slot - peers_.size()];
  return peer.joined && peer.connected && !peer.left && peer.endpoint == endpoint;
}

MatchHost::Peer* MatchHost::find_peer(uint64_t connection_id, uint32_t* player) {
  for (uint32_t p = 0; p < peers_.size() + spectators_.size(); ++p) {
    Peer& peer = p < peers_.size() ? peers_[p] : spectators_[p - peers_.size()];
    if (peer.joined && peer.connection && peer.connection->connection_id() == connection_id) {
      *player = p;
      return &peer;
    }
  }
  return nullptr;
}

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
    handle_join(envelope, from, now, who);
    return;
  }
  uint32_t player = 0;
  Peer* peer = find_peer(envelope.connection_id(), &player);
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
                     std::min(envelope.input_frame().last_final_tick_seen(), next_final_ - 1));
      }
      break;
    case v1::Envelope::kPing: {
      v1::Envelope reply;
      v1::Pong* pong = reply.mutable_pong();
      pong->set_client_time_us(envelope.ping().client_time_us());
      pong->set_server_tick(server_tick());
      pong->set_server_tick_elapsed_us(static_cast<uint32_t>(
          std::chrono::duration_cast<std::chrono::microseconds>(now - tick_started_).count()));
      send(*peer, reply, now);
      break;
    }
    case v1::Envelope::kDesyncReport:
      handle_desync(*peer, player, envelope.desync_report(), now);
      break;
    case v1::Envelope::kResyncRequest:
      if (phase_ == Phase::kRunning || phase_ == Phase::kClosing) {
        on_resync_refused(*peer, player, envelope.resync_request());
        send_resync(*peer, now);
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

void MatchHost::handle_input(Peer& peer, uint32_t player, const v1::InputFrame& frame) {
  if (frame.player() != player) {
    // Inputs for another slot: never applied, whoever sent them.
    ++stats_.rejected_packets;
    stats_.rejected_inputs += static_cast<uint64_t>(frame.inputs_size());
    return;
  }
  peer.sent_input = true;
  if (frame.last_final_tick_seen() > peer.final_seen) {
    peer.final_seen = std::min(frame.last_final_tick_seen(), next_final_ - 1);
  }
  const Tick now_tick = session_->current_tick();
  const Tick clock_tick = server_tick();
  Tick relay_first = kNoTick;
  Tick relay_next = kNoTick;
  Tick newest = kNoTick;

  // New inputs wait for the tick's one datagram to each client (broadcast)
  // instead of going out at once: O(players) datagrams a tick, not
  // O(players^2).
  // Runs are packed (each input against the one before it) and at most
  // kMaxPackedInputs long.
  auto flush_relay = [&]() {
    if (relay_run_.empty()) return;
    stats_.relayed_inputs += relay_run_.size();
    relay_batch_.push_back({player, relay_first, relay_run_});
    relay_run_.clear();
  };

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
        if (relay_next != tick || relay_run_.size() == proto::kMaxPackedInputs) {
          flush_relay();
          relay_first = tick;
        }
        relay_run_.push_back(*input);
        relay_next = tick + 1;
        break;
      case net::InputResult::kDuplicate:
        newest = std::max(newest, tick);
        break;
      case net::InputResult::kFinal: {
        // Late inputs still say how late the client runs: its time sync
        // needs exactly that (negative) lead to jump ahead.
        newest = std::max(newest, tick);
        // Resends of inputs the server had are normal; an input that only
        // arrives after its tick was finalized without it is rejected.
        const FinalRecord& record = final_history_[static_cast<size_t>(tick) % kFinalHistory];
        if (record.tick == tick && (record.substituted >> player) & 1u) ++stats_.rejected_inputs;
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
  flush_relay();
  if (newest != kNoTick) {
    // 64-bit and clamped: ticks near INT32_MAX minus a negative countdown
    // clock must not overflow.
    const int64_t lead = int64_t{newest} - int64_t{clock_tick};
    const int64_t limit = config_.max_input_lead_ticks;
    peer.last_lead = static_cast<int32_t>(std::clamp<int64_t>(lead, -limit, limit));
  }
}

void MatchHost::on_tick(TimePoint now) {
  if (phase_ == Phase::kEnded) return;
  if (phase_ == Phase::kLobby) {
    free_silent_lobby_seats(now);
    if (seconds_between(created_, now) > config_.join_timeout_s) {
      end("lobby timeout: " + std::to_string(stats_.players_joined) + " of " +
              std::to_string(config_.players) + " players joined",
          now);
    }
    return;
  }
  if (phase_ == Phase::kClosing) {
    broadcast(now);
    send_match_end(now);  // until each client says goodbye
    close_if_done(now);
    return;
  }
  tick_started_ = now;
  if (countdown_ticks_ > 0) {
    --countdown_ticks_;
    for (Peer& peer : peers_) send_match_start(peer, now);
    for (Peer& peer : spectators_) send_match_start(peer, now);
    return;
  }
  for (uint32_t p = 0; p < peers_.size(); ++p) {
    Peer& peer = peers_[p];
    if (peer.connected && seconds_between(peer.last_receive, now) > config_.peer_timeout_s) {
      peer.connected = false;
      log_line("player " + std::to_string(p) + " timed out; substituting its inputs");
    }
  }
  for (Peer& peer : spectators_) {  // a silent spectator's seat is free again
    if (peer.connected && seconds_between(peer.last_receive, now) > config_.peer_timeout_s) {
      peer.connected = false;
    }
  }

  if (!session_->synchronize()) {
    // Cannot happen while the window is smaller than the snapshot ring;
    // reported loudly because it would mean a broken invariant.
    log_line("internal error: rollback target outside the snapshot ring");
  }
  finalize_ready_ticks();
  if (config_.max_ticks > 0 && next_final_ >= config_.max_ticks) {
    broadcast(now);
    end("tick budget reached", now);
    return;
  }
  session_->advance();
  if (!session_->game_error().ok()) {
    // The rules refused the state they made: no further tick can be
    // simulated, so the match ends with their message.
    broadcast(now);
    end("the game's rules failed: " + session_->game_error().message(), now);
    return;
  }
  broadcast(now);
  recorder_.flush_if_due();
}

void MatchHost::end(const std::string& reason, TimePoint now) {
  if (phase_ == Phase::kEnded || phase_ == Phase::kClosing) return;
  const bool was_running = phase_ == Phase::kRunning;
  ended_ = now;
  stats_.end_reason = reason;
  log_line("match ends: " + reason);
  recorder_.finish(next_final_ - 1, reason);
  if (!was_running) {
    started_ = now;
    phase_ = Phase::kEnded;
    send_match_end(now);
    return;
  }
  phase_ = Phase::kClosing;
  closing_deadline_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(config_.closing_s));
  send_match_end(now);
  close_if_done(now);
}

void MatchHost::send_match_end(TimePoint now) {
  for (uint32_t p = 0; p < peers_.size() + spectators_.size(); ++p) {
    Peer& peer = p < peers_.size() ? peers_[p] : spectators_[p - peers_.size()];
    if (!peer.joined || !peer.connected) continue;
    v1::Envelope envelope;
    envelope.mutable_match_end()->set_last_final_tick(next_final_ - 1);
    envelope.mutable_match_end()->set_reason(stats_.end_reason);
    send(peer, envelope, now);
  }
}

void MatchHost::close_if_done(TimePoint now) {
  // Done when every client still with us has said goodbye (it does once it
  // has verified the last final tick), or when the closing time is up.
  bool all_gone = true;
  for (const Peer& peer : peers_) all_gone = all_gone && (!peer.joined || !peer.connected);
  if (all_gone || now >= closing_deadline_) phase_ = Phase::kEnded;
}

void MatchHost::send(Peer& peer, v1::Envelope& envelope, TimePoint now) {
  if (!peer.connection) return;
  peer.connection->stamp(envelope, now);
  // The tick's final ticks and relayed inputs were checked when they came
  // in and packed by this host: checking them again would unpack every
  // packed input for every client. Everything else is checked in full.
  const net::EncodeCheck check =
      envelope.has_final_ticks() ? net::EncodeCheck::kHeader : net::EncodeCheck::kFull;
  if (Status status = net::encode_envelope(envelope, encode_buffer_, check); !status.ok()) {
    log_line("dropping an unencodable message: " + status.message());
    return;
  }
  ++stats_.packets_out;
  stats_.bytes_out += encode_buffer_.size();
  send_(peer.endpoint, encode_buffer_);
}

void MatchHost::send_unconnected(const Endpoint& to, v1::Envelope& envelope) {
  envelope.set_protocol_version(net::kProtocolVersion);
  if (Status status = net::encode_envelope(envelope, encode_buffer_); !status.ok()) return;
  ++stats_.packets_out;
  stats_.bytes_out += encode_buffer_.size();
  send_(to, encode_buffer_);
}

}  // namespace rwd::server
