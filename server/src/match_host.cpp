// SPDX-License-Identifier: MIT
#include "rewind/server/match_host.h"

#include <algorithm>
#include <cmath>

#include "host_log.h"
#include "rewind/replay/replay_header.h"

namespace rwd::server {
namespace {

using detail::log_line;

double seconds_between(TimePoint a, TimePoint b) {
  return std::chrono::duration<double>(b - a).count();
}

google::protobuf::ArenaOptions arena_on(char* block, size_t size) {
  google::protobuf::ArenaOptions options;
  options.initial_block = block;
  options.initial_block_size = size;
  return options;
}

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
      session_(std::move(session)),
      seats_(config_.players, config_.max_spectators),
      outbox_(std::move(send), stats_),
      recorder_(std::move(replay), static_cast<uint32_t>(config_.keyframe_interval)),
      finalizer_(config_, *session_, seats_, recorder_, stats_),
      admission_(config_, seats_),
      resync_(config_, *session_, seats_, finalizer_, outbox_, stats_, std::move(env)),
      created_(now),
      started_(now),
      tick_started_(now),
      ended_(now),
      arena_blocks_(new char[kReceiveArenaBytes + kBroadcastArenaBytes]),
      receive_arena_(arena_on(arena_blocks_.get(), kReceiveArenaBytes)),
      broadcast_arena_(arena_on(arena_blocks_.get() + kReceiveArenaBytes, kBroadcastArenaBytes)) {}

const char* phase_name(MatchPhase phase) {
  switch (phase) {
    case MatchPhase::kLobby:
      return "lobby";
    case MatchPhase::kRunning:
      return "running";
    case MatchPhase::kClosing:
      return "closing";
    case MatchPhase::kEnded:
      break;
  }
  return "ended";
}

MatchStats MatchHost::stats() const {
  MatchStats out = stats_;
  out.rollbacks = session_->stats().rollbacks;
  out.resimulated_ticks = session_->stats().resimulated_ticks;
  out.last_final_tick = finalizer_.next_final() - 1;
  out.ticks_final = finalizer_.next_final();
  out.duration_s = phase_ == Phase::kLobby ? 0.0 : seconds_between(started_, ended_);
  return out;
}

void MatchHost::on_tick(TimePoint now) {
  if (phase_ == Phase::kEnded) return;
  if (phase_ == Phase::kLobby) {
    for (uint32_t id : admission_.free_silent_lobby_seats(now)) {
      resync_.clear(id);
      if (seats_.is_player(id)) --stats_.players_joined;
    }
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
    for (Seat& seat : seats_.all()) send_match_start(seat, now);
    return;
  }
  time_out_silent_seats(now);
  if (!session_->synchronize()) {
    // Cannot happen while the window is smaller than the snapshot ring;
    // reported loudly because it would mean a broken invariant.
    log_line("internal error: rollback target outside the snapshot ring");
  }
  finalizer_.finalize_ready_ticks();
  if (config_.max_ticks > 0 && finalizer_.next_final() >= config_.max_ticks) {
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

void MatchHost::time_out_silent_seats(TimePoint now) {
  for (uint32_t id = 0; id < seats_.size(); ++id) {
    Seat& seat = seats_[id];
    if (!seat.connected || seconds_between(seat.last_receive, now) <= config_.peer_timeout_s) {
      continue;
    }
    // A silent player's inputs are substituted from now on; a silent
    // spectator's seat is free again.
    seat.connected = false;
    if (seats_.is_player(id)) {
      log_line("player " + std::to_string(id) + " timed out; substituting its inputs");
    }
  }
}

void MatchHost::start_match(TimePoint now) {
  phase_ = Phase::kRunning;
  started_ = now;
  tick_started_ = now;
  countdown_ticks_ = static_cast<int32_t>(std::ceil(config_.start_delay_s * config_.tick_rate_hz));
  const uint32_t joined = seats_.players_joined();
  log_line((joined == config_.players
                ? "all " + std::to_string(joined)
                : std::to_string(joined) + " of " + std::to_string(config_.players)) +
           " players joined; tick 0 in " + std::to_string(countdown_ticks_) + " ticks" +
           (joined < config_.players ? " (the other slots are open for late joiners)" : ""));
  for (Seat& seat : seats_.player_seats()) send_match_start(seat, now);
}

void MatchHost::send_match_start(Seat& seat, TimePoint now) {
  v1::Envelope start;
  start.mutable_match_start()->set_start_tick(0);
  start.mutable_match_start()->set_server_tick(server_tick());
  outbox_.send(seat, start, now);
}

void MatchHost::broadcast(TimePoint now) {
  // Each run packed once, for every client but its player.
  relay_.pack(server_tick());
  for (uint32_t id = 0; id < seats_.size(); ++id) {
    Seat& seat = seats_[id];
    if (!seat.joined || !seat.connected) continue;
    if (!seat.sent_input && phase_ == Phase::kRunning && session_->current_tick() % 10 == 0) {
      send_match_start(seat, now);  // every MatchStart so far may have been lost
    }
    const bool resync_pending = resync_.before_broadcast(id, now);
    // On the broadcast arena, freed once every client's datagram is out.
    v1::Envelope& envelope =
        *google::protobuf::Arena::CreateMessage<v1::Envelope>(&broadcast_arena_);
    finalizer_.compose(seat, id, server_tick(), relay_, resync_pending,
                       *envelope.mutable_final_ticks());
    outbox_.send(seat, envelope, now);
  }
  relay_.clear();
  broadcast_arena_.Reset();
}

void MatchHost::end(const std::string& reason, TimePoint now) {
  if (phase_ == Phase::kEnded || phase_ == Phase::kClosing) return;
  const bool was_running = phase_ == Phase::kRunning;
  ended_ = now;
  stats_.end_reason = reason;
  log_line("match ends: " + reason);
  recorder_.finish(finalizer_.next_final() - 1, reason);
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
  for (Seat& seat : seats_.all()) {
    if (!seat.joined || !seat.connected) continue;
    v1::Envelope envelope;
    envelope.mutable_match_end()->set_last_final_tick(finalizer_.next_final() - 1);
    envelope.mutable_match_end()->set_reason(stats_.end_reason);
    outbox_.send(seat, envelope, now);
  }
}

void MatchHost::close_if_done(TimePoint now) {
  // Done when every client still with us has said goodbye (it does once it
  // has verified the last final tick), or when the closing time is up.
  bool all_gone = true;
  for (const Seat& seat : seats_.player_seats()) {
    all_gone = all_gone && (!seat.joined || !seat.connected);
  }
  if (all_gone || now >= closing_deadline_) phase_ = Phase::kEnded;
}

}  // namespace rwd::server
