// SPDX-License-Identifier: MIT
#include "rewind/server/match_host.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "rewind/net/connection_id.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/net/join_token.h"
#include "rewind/proto/input_wire.h"
#include "rewind/replay/replay_header.h"
#include "rewind/sim/body_record.h"

namespace rwd::server {
namespace {

constexpr size_t kFinalTicksBudgetBytes = 1000;  // leaves room for the envelope header
constexpr size_t kMaxFinalHistory = 1024;        // ticks kept for clients that fall behind
constexpr size_t kResyncChunkBytes = 1000;
constexpr auto kResyncMinInterval = std::chrono::milliseconds(250);

double seconds_between(TimePoint a, TimePoint b) {
  return std::chrono::duration<double>(b - a).count();
}

void log_line(const std::string& text) {
  std::fprintf(stderr, "[rewind-server] %s\n", text.c_str());
}

// Text that came from a client goes into our logs only printable and short,
// so nobody can forge log lines or flood them with one long string.
std::string printable(const std::string& text) {
  std::string out;
  for (char c : text.substr(0, 64)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out;
}

constexpr auto kReportMinInterval = std::chrono::seconds(2);
constexpr uint32_t kMaxReportsPerPeer = 8;

// A failure that repeats (every resend of every waiting client) is logged
// the first few times and then at each power of two, so it stays loud
// without burying the log.
bool worth_logging(uint64_t count) {
  return count <= 3 || (count & (count - 1)) == 0;
}

std::string hex64(uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof(text), "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace

Result<std::unique_ptr<MatchHost>> MatchHost::create(const MatchConfig& config, SendFn send,
                                                     TimePoint now) {
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
    recording.started_unix_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count();
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
    std::error_code error;
    std::filesystem::create_directories(config.desync_dir, error);
    if (error) {
      return Status::Error(ErrorCode::kIo, "cannot create desync directory '" + config.desync_dir +
                                               "': " + error.message());
    }
  }
  return std::make_unique<MatchHost>(config, std::move(send), std::move(session), std::move(writer),
                                     now);
}

MatchHost::MatchHost(const MatchConfig& config, SendFn send,
                     std::unique_ptr<net::RollbackSession> session,
                     std::optional<replay::ReplayWriter> replay, TimePoint now)
    : config_(config),
      send_(std::move(send)),
      session_(std::move(session)),
      replay_(std::move(replay)),
      peers_(config.players),
      created_(now),
      started_(now),
      tick_started_(now),
      ended_(now),
      ids_(net::ConnectionIdGenerator::from_os_entropy()) {
  final_inputs_.resize(config.players);
  final_history_.assign(kFinalHistory, FinalRecord{});
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

MatchHost::Peer* MatchHost::find_peer(uint64_t connection_id, uint32_t* player) {
  for (uint32_t p = 0; p < peers_.size(); ++p) {
    Peer& peer = peers_[p];
    if (peer.joined && peer.connection && peer.connection->connection_id() == connection_id) {
      *player = p;
      return &peer;
    }
  }
  return nullptr;
}

void MatchHost::on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, TimePoint now) {
  ++stats_.packets_in;
  stats_.bytes_in += bytes.size();
  if (phase_ == Phase::kEnded) return;
  auto decoded = net::decode_envelope(bytes);
  if (!decoded.ok()) {
    ++stats_.rejected_packets;
    return;
  }
  const v1::Envelope& envelope = *decoded;
  if (envelope.has_join_request()) {
    handle_join(envelope, from, now);
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
      if (phase_ == Phase::kRunning) {
        handle_input(*peer, player, envelope.input_frame(), now);
      } else if (envelope.input_frame().player() == player) {
        // Closing: only the acknowledgement of final ticks still matters.
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

void MatchHost::handle_join(const v1::Envelope& envelope, const Endpoint& from, TimePoint now) {
  const v1::JoinRequest& request = envelope.join_request();
  auto reject = [&](const std::string& reason) {
    ++stats_.rejected_packets;
    v1::Envelope reply;
    reply.mutable_join_reject()->set_nonce(request.nonce());
    reply.mutable_join_reject()->set_reason(reason);
    send_unconnected(from, reply);
  };
  auto accept = [&](uint32_t player) {
    Peer& peer = peers_[player];
    v1::Envelope reply;
    v1::JoinAccept* answer = reply.mutable_join_accept();
    answer->set_nonce(request.nonce());
    answer->set_connection_id(peer.connection->connection_id());
    answer->set_player(player);
    answer->set_player_count(config_.players);
    answer->set_game(config_.game);
    answer->set_seed(config_.seed);
    answer->set_tick_rate_hz(config_.tick_rate_hz);
    answer->set_window_ticks(static_cast<uint32_t>(config_.window_ticks));
    send(peer, reply, now);
    if (phase_ == Phase::kRunning) send_match_start(peer, now);
  };

  // A repeated request from a joined address lost our answer: answer again.
  for (uint32_t p = 0; p < peers_.size(); ++p) {
    if (peers_[p].joined && peers_[p].endpoint == from) {
      if (peers_[p].join_nonce == request.nonce()) {
        accept(p);
      } else {
        reject("this address already holds player slot " + std::to_string(p));
      }
      return;
    }
  }
  if (request.game() != config_.game) {
    reject("this server hosts '" + config_.game + "', not '" + request.game() + "'");
    return;
  }
  std::optional<uint32_t> slot;
  if (!config_.token_secret.empty()) {
    const auto now_unix = std::chrono::duration_cast<std::chrono::seconds>(
                              std::chrono::system_clock::now().time_since_epoch())
                              .count();
    const std::string& token = request.token();
    auto verified = net::verify_join_token(
        config_.token_secret,
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(token.data()), token.size()),
        config_.match_id, static_cast<int64_t>(now_unix));
    if (!verified.ok()) {
      reject("join token refused: " + verified.status().message());
      return;
    }
    if (*verified >= config_.players || peers_[*verified].joined) {
      reject("player slot " + std::to_string(*verified) + " is not available");
      return;
    }
    slot = *verified;
  } else if (phase_ == Phase::kLobby) {
    for (uint32_t p = 0; p < peers_.size() && !slot; ++p) {
      if (!peers_[p].joined) slot = p;
    }
  }
  if (!slot) {
    reject(phase_ == Phase::kLobby ? "match is full" : "match already running");
    return;
  }
  if (phase_ != Phase::kLobby) {
    reject("match already running");
    return;
  }
  Peer& peer = peers_[*slot];
  const uint64_t id = ids_.next();
  peer.joined = true;
  peer.connected = true;
  peer.endpoint = from;
  peer.join_nonce = request.nonce();
  peer.connection.emplace(now, id);
  peer.last_receive = now;
  peer.name = request.client_name();
  ++stats_.players_joined;
  log_line("player " + std::to_string(*slot) + " joined from " + from.address().to_string() + ":" +
           std::to_string(from.port()) + " (" + printable(peer.name) + ")");
  accept(*slot);
  const bool full =
      std::all_of(peers_.begin(), peers_.end(), [](const Peer& p) { return p.joined; });
  if (full) start_match(now);
}

void MatchHost::start_match(TimePoint now) {
  phase_ = Phase::kRunning;
  started_ = now;
  tick_started_ = now;
  countdown_ticks_ = static_cast<int32_t>(std::ceil(config_.start_delay_s * config_.tick_rate_hz));
  log_line("all " + std::to_string(config_.players) + " players joined; tick 0 in " +
           std::to_string(countdown_ticks_) + " ticks");
  for (Peer& peer : peers_) send_match_start(peer, now);
}

void MatchHost::send_match_start(Peer& peer, TimePoint now) {
  v1::Envelope start;
  start.mutable_match_start()->set_start_tick(0);
  start.mutable_match_start()->set_server_tick(server_tick());
  send(peer, start, now);
}

void MatchHost::handle_input(Peer& peer, uint32_t player, const v1::InputFrame& frame,
                             TimePoint now) {
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
  v1::Envelope relay;
  v1::RelayedInputs* relayed = relay.mutable_relayed_inputs();
  relayed->set_player(player);
  Tick relay_next = kNoTick;
  Tick newest = kNoTick;

  auto flush_relay = [&]() {
    if (relayed->inputs_size() == 0) return;
    for (uint32_t p = 0; p < peers_.size(); ++p) {
      if (p != player && peers_[p].joined && peers_[p].connected) {
        v1::Envelope copy = relay;
        send(peers_[p], copy, now);
      }
    }
    stats_.relayed_inputs += static_cast<uint64_t>(relayed->inputs_size());
    relayed->clear_inputs();
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
        if (relay_next != tick) {
          flush_relay();
          relayed->set_first_tick(tick);
        }
        *relayed->add_inputs() = frame.inputs(i);
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
    return;
  }
  for (uint32_t p = 0; p < peers_.size(); ++p) {
    Peer& peer = peers_[p];
    if (peer.connected && seconds_between(peer.last_receive, now) > config_.peer_timeout_s) {
      peer.connected = false;
      log_line("player " + std::to_string(p) + " timed out; substituting its inputs");
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
  broadcast(now);
  if (replay_ && !replay_failed_) {
    if (Status status = replay_->flush_if_due(); !status.ok()) record_replay_error(status);
  }
}

void MatchHost::finalize_ready_ticks() {
  const Tick current = session_->current_tick();
  while (next_final_ < current) {
    if (config_.max_ticks > 0 && next_final_ >= config_.max_ticks) break;
    const Tick t = next_final_;
    bool all_known = true;
    for (uint32_t p = 0; p < peers_.size(); ++p) {
      all_known = all_known && session_->queue(p).is_confirmed(t);
    }
    if (!all_known && current - t < config_.window_ticks) break;

    // The deadline passed: missing inputs become the prediction the
    // simulation already used, so finalizing never re-simulates.
    uint64_t substituted = 0;
    v1::FinalTick final_tick;
    final_tick.set_tick(t);
    for (uint32_t p = 0; p < peers_.size(); ++p) {
      if (!session_->queue(p).is_confirmed(t)) {
        substituted |= uint64_t{1} << p;
        (void)session_->add_final_input(p, t, session_->input_for(p, t));
        ++stats_.substituted_inputs;
      }
      final_inputs_[p] = session_->input_for(p, t);
      *final_tick.add_inputs() = proto::to_wire(final_inputs_[p]);
    }
    const std::optional<uint64_t> checksum = session_->checksum_after(t);
    final_tick.set_substituted_mask(substituted);
    final_tick.set_checksum(checksum.value_or(0));
    final_history_[static_cast<size_t>(t) % kFinalHistory] = {t, substituted,
                                                              final_tick.checksum()};
    stats_.final_checksum = final_tick.checksum();

    if (replay_ && !replay_failed_) {
      Status status = replay_->append_tick(t, final_inputs_, substituted, final_tick.checksum());
      if (status.ok() && config_.keyframe_interval > 0 &&
          (t + 1) % config_.keyframe_interval == 0 &&
          session_->serialize_state_at(t + 1, state_buffer_)) {
        // A keyframe the verifier could not load would stop it there: check
        // it as a resync snapshot is checked, and leave out one that fails.
        if (auto loaded = session_->load_snapshot(state_buffer_, final_tick.checksum());
            loaded.ok()) {
          status = replay_->append_keyframe(t, state_buffer_);
        } else {
          ++stats_.keyframe_load_failures;
          if (worth_logging(stats_.keyframe_load_failures)) {
            log_line("WARNING: replay keyframe after tick " + std::to_string(t) +
                     " does not load on the server, left out: " + loaded.status().message() + " (" +
                     std::to_string(stats_.keyframe_load_failures) + " so far)");
          }
        }
      }
      if (!status.ok()) record_replay_error(status);
    }
    (void)session_->finalize_through(t);
    final_sizes_.push_back(static_cast<uint32_t>(final_tick.ByteSizeLong()));
    finals_.push_back(std::move(final_tick));
    ++next_final_;
  }
  // Drop history every connected client has; keep a bounded tail for the rest.
  Tick acked_by_all = next_final_ - 1;
  for (const Peer& peer : peers_) {
    if (peer.joined && peer.connected) acked_by_all = std::min(acked_by_all, peer.final_seen);
  }
  while (!finals_.empty() &&
         (finals_.front().tick() <= acked_by_all || finals_.size() > kMaxFinalHistory)) {
    finals_.pop_front();
    final_sizes_.pop_front();
  }
}

void MatchHost::broadcast(TimePoint now) {
  const Tick oldest_held = finals_.empty() ? next_final_ : finals_.front().tick();
  for (uint32_t p = 0; p < peers_.size(); ++p) {
    Peer& peer = peers_[p];
    if (!peer.joined || !peer.connected) continue;
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
    v1::Envelope envelope;
    v1::FinalTicks* out = envelope.mutable_final_ticks();
    out->set_input_ack_tick(session_->queue(p).contiguous_through());
    out->set_input_lead_ticks(peer.last_lead);
    out->set_server_tick(server_tick());
    // While a snapshot is on its way the client ignores final ticks, but
    // still needs the server's clock and its input acknowledgements.
    if (!resync_pending) add_final_ticks(peer, *out);
    send(peer, envelope, now);
  }
}

void MatchHost::add_final_ticks(Peer& peer, v1::FinalTicks& out) {
  if (finals_.empty()) return;
  const Tick oldest_held = finals_.front().tick();
  const Tick newest = next_final_ - 1;
  size_t budget = kFinalTicksBudgetBytes;
  auto add = [&](Tick t) {
    const size_t index = static_cast<size_t>(t - oldest_held);
    const size_t size = final_sizes_[index] + 3;  // tag + length prefix
    if (size > budget || out.ticks_size() >= static_cast<int>(net::kMaxFinalTicksPerPacket)) {
      return false;
    }
    budget -= size;
    *out.add_ticks() = finals_[index];
    return true;
  };
  // New ticks first, so a round trip never limits how fast finals flow;
  // then the oldest unacknowledged ones again, for loss. Clients accept
  // them in any order.
  const Tick first_new = std::max({peer.final_sent + 1, peer.final_seen + 1, oldest_held});
  Tick t = first_new;
  while (t <= newest && add(t)) ++t;
  peer.final_sent = std::max(peer.final_sent, t - 1);
  // The resend cursor walks round-robin through the unacknowledged range,
  // so after a loss burst every missing tick comes back within a few
  // packets instead of the oldest few being resent over and over.
  const Tick lowest = std::max(peer.final_seen + 1, oldest_held);
  if (lowest >= first_new) return;
  Tick r = std::clamp(peer.resend_cursor, lowest, first_new - 1);
  for (Tick sent = 0; sent < first_new - lowest && add(r); ++sent) {
    r = r + 1 < first_new ? r + 1 : lowest;
  }
  peer.resend_cursor = r;
}

void MatchHost::handle_desync(Peer& peer, uint32_t player, const v1::DesyncReport& report,
                              TimePoint now) {
  if (report.tick() > next_final_ - 1 || report.tick() < 0) {
    ++stats_.rejected_packets;  // only final ticks can desync
    return;
  }
  for (uint32_t id : peer.handled_reports) {
    if (id == report.report_id()) {
      send_resync(peer, now);  // the client is still waiting: our snapshot was lost
      return;
    }
  }
  DesyncAssembly& assembly = peer.desync;
  if (assembly.report_id != report.report_id() || assembly.chunks.size() != report.chunk_count() ||
      assembly.total_size != report.total_size()) {
    assembly = DesyncAssembly{};
    assembly.report_id = report.report_id();
    assembly.tick = report.tick();
    assembly.client_checksum = report.client_checksum();
    assembly.server_checksum = report.server_checksum();
    assembly.total_size = report.total_size();
    assembly.chunks.assign(report.chunk_count(), {});
  }
  std::vector<uint8_t>& chunk = assembly.chunks[report.chunk_index()];
  if (chunk.empty() && !report.chunk().empty()) {
    chunk.assign(report.chunk().begin(), report.chunk().end());
    ++assembly.received;
  }
  if (assembly.received < assembly.chunks.size()) return;

  std::vector<uint8_t> dump;
  dump.reserve(assembly.total_size);
  for (const auto& part : assembly.chunks) dump.insert(dump.end(), part.begin(), part.end());
  if (dump.size() != assembly.total_size) {
    ++stats_.rejected_packets;  // inconsistent chunk set; the client will retry
    assembly = DesyncAssembly{};
    return;
  }
  ++stats_.desync_reports;
  peer.handled_reports.push_back(assembly.report_id);
  if (peer.handled_reports.size() > 16) peer.handled_reports.erase(peer.handled_reports.begin());
  // Storing a report (disk, two simulations, a diff) is the expensive part:
  // a few per player, spaced out, so a client cannot stall the match or
  // fill the disk by inventing desyncs.
  if (peer.reports_stored < kMaxReportsPerPeer &&
      (peer.reports_stored == 0 || now - peer.last_report_stored >= kReportMinInterval)) {
    ++peer.reports_stored;
    peer.last_report_stored = now;
    store_desync_report(player, assembly, dump);
  }
  assembly = DesyncAssembly{};
  send_resync(peer, now);
}

std::optional<uint64_t> MatchHost::final_checksum(Tick tick) const {
  if (tick < 0) return std::nullopt;
  const FinalRecord& record = final_history_[static_cast<size_t>(tick) % kFinalHistory];
  if (record.tick != tick) return std::nullopt;
  return record.checksum;
}

void MatchHost::store_desync_report(uint32_t player, const DesyncAssembly& assembly,
                                    const std::vector<uint8_t>& dump) {
  // The headline needs nothing but the report and our final-tick history,
  // so it is written whatever fails below.
  const std::optional<uint64_t> ours = final_checksum(assembly.tick);
  const std::string headline = "player " + std::to_string(player) + " desync at tick " +
                               std::to_string(assembly.tick) + ": client " +
                               hex64(assembly.client_checksum) + " server " +
                               hex64(ours.value_or(assembly.server_checksum)) +
                               (ours ? "" : " (as the client received it; no longer held here)");
  std::string text = headline + "\n";
  // Why the report names no fields, when it cannot.
  std::string problem;

  // Name the bodies that differ: the client's state after the tick against
  // ours, when the ring still holds it.
  auto client_sim = session_->load_snapshot(dump);
  std::vector<uint8_t> server_state;
  if (!client_sim.ok()) {
    ++stats_.desync_dumps_unreadable;
    problem = "client dump unreadable: " + client_sim.status().message();
  } else {
    if ((*client_sim)->checksum() != assembly.client_checksum) {
      text += "the client dump does not reproduce the client's checksum (" +
              hex64((*client_sim)->checksum()) + ")\n";
    }
    if (!session_->serialize_state_at(assembly.tick + 1, server_state)) {
      problem = "server state for tick " + std::to_string(assembly.tick) + " is no longer held";
    } else if (auto server_sim = session_->load_snapshot(server_state); !server_sim.ok()) {
      problem = "server state unreadable: " + server_sim.status().message();
    } else {
      std::vector<sim::BodyRecord> expected, actual;
      (*server_sim)->dump_bodies(expected);
      (*client_sim)->dump_bodies(actual);
      const auto differences = sim::diff_body_records(expected, actual);
      text += std::to_string(differences.size()) +
              " differing fields (server = expected, client = actual):\n";
      char line[160];
      for (const sim::FieldDifference& d : differences) {
        std::snprintf(line, sizeof(line), "  body %u %s: expected %.9g actual %.9g\n", d.body_index,
                      d.field.c_str(), d.expected, d.actual);
        text += line;
      }
    }
  }
  if (!problem.empty()) text += problem + "\n";

  std::string stored;
  if (!config_.desync_dir.empty()) {
    const std::string base = config_.desync_dir + "/desync_p" + std::to_string(player) + "_t" +
                             std::to_string(assembly.tick) + "_r" +
                             std::to_string(assembly.report_id);
    // The raw dump first: it is the evidence when nothing else could be read.
    std::ofstream raw(base + ".bin", std::ios::binary);
    raw.write(reinterpret_cast<const char*>(dump.data()),
              static_cast<std::streamsize>(dump.size()));
    raw.close();
    std::ofstream report(base + ".txt");
    report << text;
    report.close();
    if (!raw || !report) {
      ++stats_.desync_report_write_failures;
      log_line("WARNING: cannot write desync report " + base + ".{txt,bin}");
    } else {
      stored = " (" + base + ".txt)";
    }
  }
  if (problem.empty()) {
    log_line(headline + stored);
  } else {
    log_line("WARNING: " + headline + "; " + problem + stored);
  }
}

void MatchHost::send_resync(Peer& peer, TimePoint now) {
  if (peer.resynced_once && now - peer.last_resync < kResyncMinInterval) return;
  peer.resynced_once = true;
  peer.last_resync = now;
  // One snapshot per episode: resends repeat the same tick, bytes and id, so
  // an acknowledgement slower than the resend interval still matches, and
  // the client can complete it from chunks of several sends. When no
  // snapshot passes its check, nothing is sent now and the next resend
  // (or the client's next request) tries again from newer state.
  if (peer.resync_tick == kNoTick && !start_resync_episode(peer)) return;
  send_resync_chunks(peer, now);
}

bool MatchHost::start_resync_episode(Peer& peer) {
  // The client restarts from the snapshot's tick and acknowledges the tick
  // before it. The state after the last final tick is the natural choice.
  // If that one does not load, the oldest final state the client can still
  // take is the fallback: a state that broke recently (a body thrown out of
  // range) is often fine a few ticks earlier, and the client re-simulates
  // from there without ever having to load the broken one. Both must still
  // be in the snapshot ring, and the final ticks after the fallback must
  // still be held for resending. At most two checks per episode. (A
  // snapshot right after what the client acknowledged counts as
  // acknowledged at once, so it goes out once instead of until
  // acknowledged; a client that misses a chunk asks again.)
  const Tick newest = next_final_;
  const Tick oldest_final_held = finals_.empty() ? next_final_ : finals_.front().tick();
  const Tick fallback = std::max(peer.final_seen + 1, oldest_final_held);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Tick tick = attempt == 0 ? newest : fallback;
    if (attempt > 0 && tick >= newest) break;  // no older state to fall back to
    const std::optional<uint64_t> checksum = session_->checksum_at(tick);
    if (!checksum || !session_->serialize_state_at(tick, peer.resync_bytes)) continue;
    if (snapshot_hook_) snapshot_hook_(tick, peer.resync_bytes);
    // Never send what we could not load ourselves: the same test the client
    // applies (RollbackSession::reset_from), on a fresh simulation.
    Status status = Status::Ok();
    const size_t count = (peer.resync_bytes.size() + kResyncChunkBytes - 1) / kResyncChunkBytes;
    if (count == 0 || count > net::kMaxResyncChunks) {
      status = Status::Error(ErrorCode::kCapacity,
                             std::to_string(peer.resync_bytes.size()) + " bytes is too large");
    } else if (auto loaded = session_->load_snapshot(peer.resync_bytes, *checksum); !loaded.ok()) {
      status = loaded.status();
    }
    if (!status.ok()) {
      ++stats_.resync_snapshot_failures;
      if (worth_logging(stats_.resync_snapshot_failures)) {
        log_line("WARNING: resync snapshot for tick " + std::to_string(tick) +
                 " does not load on the server, not sent: " + status.message() + " (" +
                 std::to_string(stats_.resync_snapshot_failures) + " so far)");
      }
      continue;
    }
    peer.resync_tick = tick;
    peer.resync_checksum = *checksum;
    peer.resync_id = next_snapshot_id_++;
    // Final ticks from here on are (re)sent once the client acknowledges
    // tick - 1; the round-robin resend covers any it already had before.
    peer.final_sent = std::max(peer.final_sent, tick - 1);
    ++stats_.resyncs_sent;
    return true;
  }
  peer.resync_bytes.clear();
  return false;
}

void MatchHost::on_resync_refused(Peer& peer, uint32_t player, const v1::ResyncRequest& request) {
  // Only the snapshot still being resent counts: later requests naming it
  // again are copies of the same refusal.
  if (request.refused_snapshot_id() == 0 || peer.resync_tick == kNoTick ||
      request.refused_snapshot_id() != peer.resync_id) {
    return;
  }
  ++stats_.resyncs_refused;
  if (worth_logging(stats_.resyncs_refused)) {
    log_line("WARNING: player " + std::to_string(player) + " could not load resync snapshot " +
             std::to_string(peer.resync_id) + " (tick " + std::to_string(peer.resync_tick) +
             "): " + printable(request.refused_reason()) + "; building another (" +
             std::to_string(stats_.resyncs_refused) + " so far)");
  }
  // Resending the same bytes cannot help: the next send starts a new episode.
  peer.resync_tick = kNoTick;
  peer.resync_bytes.clear();
}

void MatchHost::send_resync_chunks(Peer& peer, TimePoint now) {
  const std::vector<uint8_t>& bytes = peer.resync_bytes;
  const auto count =
      static_cast<uint32_t>((bytes.size() + kResyncChunkBytes - 1) / kResyncChunkBytes);
  for (uint32_t i = 0; i < count; ++i) {
    v1::Envelope envelope;
    v1::ResyncChunk* chunk = envelope.mutable_resync_chunk();
    chunk->set_snapshot_id(peer.resync_id);
    chunk->set_tick(peer.resync_tick);
    chunk->set_checksum(peer.resync_checksum);
    chunk->set_chunk_index(i);
    chunk->set_chunk_count(count);
    chunk->set_total_size(static_cast<uint32_t>(bytes.size()));
    const size_t begin = i * kResyncChunkBytes;
    const size_t end = std::min(bytes.size(), begin + kResyncChunkBytes);
    chunk->set_chunk(std::string(bytes.begin() + static_cast<std::ptrdiff_t>(begin),
                                 bytes.begin() + static_cast<std::ptrdiff_t>(end)));
    send(peer, envelope, now);
  }
}

void MatchHost::end(const std::string& reason, TimePoint now) {
  if (phase_ == Phase::kEnded || phase_ == Phase::kClosing) return;
  const bool was_running = phase_ == Phase::kRunning;
  ended_ = now;
  stats_.end_reason = reason;
  log_line("match ends: " + reason);
  if (replay_ && !replay_failed_) {
    Status status = replay_->finish(next_final_ - 1, reason);
    if (!status.ok()) record_replay_error(status);
  }
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
  for (Peer& peer : peers_) {
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
  if (Status status = net::encode_envelope(envelope, encode_buffer_); !status.ok()) {
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

void MatchHost::record_replay_error(const Status& status) {
  replay_failed_ = true;
  log_line("replay writing stopped: " + status.message() +
           " (the file keeps its verified prefix; the match goes on)");
}

}  // namespace rwd::server
