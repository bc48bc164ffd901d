// SPDX-License-Identifier: MIT
// The match host's admission: join requests (tokens, slots, rejoining by
// connection), the lobby, and the start of the match.
#include <algorithm>

#include "host_log.h"
#include "rewind/net/connection_id.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/server/match_host.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::printable;

}  // namespace

void MatchHost::handle_join(const v1::Envelope& envelope, const Endpoint& from, TimePoint now,
                            const Admission* who) {
  const v1::JoinRequest& request = envelope.join_request();
  auto reject = [&](const std::string& reason) {
    ++stats_.rejected_packets;
    v1::Envelope reply;
    reply.mutable_join_reject()->set_nonce(request.nonce());
    reply.mutable_join_reject()->set_reason(reason);
    send_unconnected(from, reply);
  };
  auto accept = [&](uint32_t player) {
    const bool spectator = player >= config_.players;
    Peer& peer = spectator ? spectators_[player - config_.players] : peers_[player];
    v1::Envelope reply;
    v1::JoinAccept* answer = reply.mutable_join_accept();
    answer->set_nonce(request.nonce());
    answer->set_connection_id(peer.connection->connection_id());
    answer->set_player(player);
    answer->set_spectator(spectator);
    answer->set_player_count(config_.players);
    answer->set_game(config_.game);
    answer->set_seed(config_.seed);
    answer->set_tick_rate_hz(config_.tick_rate_hz);
    answer->set_window_ticks(static_cast<uint32_t>(config_.window_ticks));
    send(peer, reply, now);
    if (phase_ == Phase::kRunning) send_match_start(peer, now);
  };

  // A repeated request from a joined address lost our answer: answer again.
  for (uint32_t p = 0; p < peers_.size() + spectators_.size(); ++p) {
    const Peer& held = p < peers_.size() ? peers_[p] : spectators_[p - peers_.size()];
    if (held.joined && held.connected && held.endpoint == from) {
      if (held.join_nonce == request.nonce()) {
        accept(p);
      } else {
        reject("this address already holds seat " + std::to_string(p));
      }
      return;
    }
  }
  if (request.game() != config_.game) {
    reject("this server hosts '" + config_.game + "', not '" + request.game() + "'");
    return;
  }
  if (config_.secure ? who->slot >= config_.players : request.spectator()) {
    uint32_t id = 0;
    if (!seat_spectator(request, from, now, who, &id)) {
      reject("no spectator seat is free");
      return;
    }
    accept(id);
    return;
  }
  std::optional<uint32_t> slot;
  if (config_.secure) {
    // The slot is the one the sender's token names (the gateway checked
    // the token and the keys). A client restarted comes back from a new
    // address with a fresh token for its client id and takes its slot
    // again; another client's token takes a slot only once its holder is
    // dropped (peer timeout, goodbye): the gateway's rule too (seated()).
    if (who->slot >= config_.players) {
      reject("player slot " + std::to_string(who->slot) + " does not exist");
      return;
    }
    const Peer& held = peers_[who->slot];
    if (held.joined && held.connected && !held.left && held.client_id != who->client_id) {
      reject("player slot " + std::to_string(who->slot) + " is held by another client");
      return;
    }
    // Running: a client that lost its connection or restarted takes its
    // slot back by its token and catches up from a snapshot.
    slot = who->slot;
  } else if (phase_ == Phase::kLobby) {
    for (uint32_t p = 0; p < peers_.size() && !slot; ++p) {
      if (!peers_[p].joined) slot = p;
    }
  } else if (phase_ == Phase::kRunning) {
    // Tokenless: a slot nobody took yet (when the match allows late join),
    // or whose player timed out or left, is free for the next joiner, who
    // catches up from a snapshot. Never-taken slots go first.
    for (uint32_t p = 0; p < peers_.size() && !slot && config_.late_join(); ++p) {
      if (!peers_[p].joined) slot = p;
    }
    for (uint32_t p = 0; p < peers_.size() && !slot; ++p) {
      if (peers_[p].joined && (!peers_[p].connected || peers_[p].left)) slot = p;
    }
  }
  if (!slot) {
    reject(phase_ == Phase::kLobby ? "match is full" : "match already running");
    return;
  }
  if (phase_ != Phase::kLobby && phase_ != Phase::kRunning) {
    reject("the match is over");
    return;
  }
  Peer& peer = peers_[*slot];
  const bool rejoin = peer.joined;
  if (phase_ == Phase::kRunning) {
    // Whatever the old connection had in flight is void: the newcomer gets
    // a snapshot (its final_seen is before everything held) and final
    // ticks from there.
    restart_peer(peer);
  }
  const uint64_t id = ids_.next();
  peer.joined = true;
  peer.connected = true;
  peer.endpoint = from;
  peer.join_nonce = request.nonce();
  peer.client_id = config_.secure ? who->client_id : 0;
  peer.connection.emplace(now, id);
  peer.last_receive = now;
  peer.name = request.client_name();
  recorder_.names_changed();
  if (!rejoin) ++stats_.players_joined;
  log_line("player " + std::to_string(*slot) + (rejoin ? " rejoined from " : " joined from ") +
           from.address().to_string() + ":" + std::to_string(from.port()) + " (" +
           printable(peer.name) + ")");
  accept(*slot);
  const auto joined = static_cast<uint32_t>(
      std::count_if(peers_.begin(), peers_.end(), [](const Peer& p) { return p.joined; }));
  if (joined >= config_.players_to_start() && phase_ == Phase::kLobby) start_match(now);
}

bool MatchHost::seat_spectator(const v1::JoinRequest& request, const Endpoint& from, TimePoint now,
                               const Admission* who, uint32_t* id) {
  if (phase_ != Phase::kLobby && phase_ != Phase::kRunning) return false;
  // A secure server seats a spectator where its token says; a tokenless
  // one in the first seat nobody holds (or whose holder went silent).
  std::optional<uint32_t> seat;
  if (config_.secure) {
    const uint32_t s = who->slot - config_.players;
    if (s < spectators_.size()) {
      const Peer& held = spectators_[s];
      if (!held.joined || !held.connected || held.client_id == who->client_id) seat = s;
    }
  } else {
    for (uint32_t s = 0; s < spectators_.size() && !seat; ++s) {
      if (!spectators_[s].joined || !spectators_[s].connected) seat = s;
    }
  }
  if (!seat) return false;
  Peer& peer = spectators_[*seat];
  peer = Peer{};
  peer.joined = true;
  peer.connected = true;
  peer.endpoint = from;
  peer.join_nonce = request.nonce();
  peer.client_id = config_.secure ? who->client_id : 0;
  peer.connection.emplace(now, ids_.next());
  peer.last_receive = now;
  peer.name = request.client_name();
  *id = config_.players + *seat;
  log_line("spectator " + std::to_string(*seat) + " joined from " + from.address().to_string() +
           ":" + std::to_string(from.port()) + " (" + printable(peer.name) + ")");
  return true;
}

void MatchHost::restart_peer(Peer& peer) {
  peer.final_seen = kNoTick;
  peer.final_sent = kNoTick;
  peer.resync_tick = kNoTick;
  peer.resync_bytes.clear();
  peer.resync_checksum = 0;
  peer.resend_cursor = kNoTick;
  peer.standalone_from = 0;
  peer.left = false;
  peer.last_lead = 0;
  peer.sent_input = false;
  peer.desync = DesyncAssembly{};
  peer.handled_reports.clear();
  peer.resynced_once = false;
}

void MatchHost::free_silent_lobby_seats(TimePoint now) {
  for (uint32_t p = 0; p < peers_.size() + spectators_.size(); ++p) {
    Peer& peer = p < peers_.size() ? peers_[p] : spectators_[p - peers_.size()];
    if (!peer.joined) continue;
    const bool silent =
        std::chrono::duration<double>(now - peer.last_receive).count() > config_.peer_timeout_s;
    if (!peer.left && peer.connected && !silent) continue;
    const bool player = p < peers_.size();
    log_line(std::string(player ? "player " : "spectator ") +
             std::to_string(player ? p : p - config_.players) +
             (peer.left ? " left the lobby" : " went silent in the lobby") + "; its seat is free");
    if (player) --stats_.players_joined;
    peer = Peer{};
  }
}

void MatchHost::start_match(TimePoint now) {
  phase_ = Phase::kRunning;
  started_ = now;
  tick_started_ = now;
  countdown_ticks_ = static_cast<int32_t>(std::ceil(config_.start_delay_s * config_.tick_rate_hz));
  const auto joined = static_cast<uint32_t>(
      std::count_if(peers_.begin(), peers_.end(), [](const Peer& p) { return p.joined; }));
  log_line((joined == config_.players
                ? "all " + std::to_string(joined)
                : std::to_string(joined) + " of " + std::to_string(config_.players)) +
           " players joined; tick 0 in " + std::to_string(countdown_ticks_) + " ticks" +
           (joined < config_.players ? " (the other slots are open for late joiners)" : ""));
  for (Peer& peer : peers_) send_match_start(peer, now);
}

void MatchHost::send_match_start(Peer& peer, TimePoint now) {
  v1::Envelope start;
  start.mutable_match_start()->set_start_tick(0);
  start.mutable_match_start()->set_server_tick(server_tick());
  send(peer, start, now);
}

}  // namespace rwd::server
