// SPDX-License-Identifier: MIT
#include "rewind/server/match_admission.h"

#include <optional>

#include "host_log.h"

namespace rwd::server {
namespace {

using detail::log_line;
using detail::printable;

MatchAdmission::Decision rejected(std::string reason) {
  MatchAdmission::Decision decision;
  decision.kind = MatchAdmission::Decision::Kind::kRejected;
  decision.reason = std::move(reason);
  return decision;
}

MatchAdmission::Decision seated(MatchAdmission::Decision::Kind kind, uint32_t seat) {
  MatchAdmission::Decision decision;
  decision.kind = kind;
  decision.seat = seat;
  return decision;
}

std::string address_text(const Endpoint& from) {
  return from.address().to_string() + ":" + std::to_string(from.port());
}

}  // namespace

MatchAdmission::MatchAdmission(const MatchConfig& config, MatchSeats& seats)
    : config_(config), seats_(seats), ids_(net::ConnectionIdGenerator::from_os_entropy()) {}

MatchAdmission::Decision MatchAdmission::admit(const v1::JoinRequest& request, const Endpoint& from,
                                               MatchPhase phase, const Admission& who,
                                               TimePoint now) {
  // A repeated request from a joined address lost our answer: answer again.
  if (const std::optional<uint32_t> held = seats_.held_from(from)) {
    if (seats_[*held].join_nonce == request.nonce()) {
      return seated(Decision::Kind::kAnswerAgain, *held);
    }
    return rejected("this address already holds seat " + std::to_string(*held));
  }
  if (request.game() != config_.game) {
    return rejected("this server hosts '" + config_.game + "', not '" + request.game() + "'");
  }
  if (config_.secure ? who.slot >= config_.players : request.spectator()) {
    return seat_spectator(request, from, phase, who, now);
  }
  return seat_player(request, from, phase, who, now);
}

MatchAdmission::Decision MatchAdmission::seat_player(const v1::JoinRequest& request,
                                                     const Endpoint& from, MatchPhase phase,
                                                     const Admission& who, TimePoint now) {
  std::optional<uint32_t> slot;
  if (config_.secure) {
    // The slot is the one the sender's token names (the gateway checked
    // the token and the keys). A client restarted comes back from a new
    // address with a fresh token for its client id and takes its slot
    // again; another client's token takes a slot only once its holder is
    // dropped (peer timeout, goodbye): the gateway's rule too (seated()).
    const Seat& held = seats_[who.slot];
    if (held.present() && held.client_id != who.client_id) {
      return rejected("player slot " + std::to_string(who.slot) + " is held by another client");
    }
    // Running: a client that lost its connection or restarted takes its
    // slot back by its token and catches up from a snapshot.
    slot = who.slot;
  } else if (phase == MatchPhase::kLobby) {
    for (uint32_t p = 0; p < seats_.players() && !slot; ++p) {
      if (!seats_[p].joined) slot = p;
    }
  } else if (phase == MatchPhase::kRunning) {
    // Tokenless: a slot nobody took yet (when the match allows late join),
    // or whose player timed out or left, is free for the next joiner, who
    // catches up from a snapshot. Never-taken slots go first.
    for (uint32_t p = 0; p < seats_.players() && !slot && config_.late_join(); ++p) {
      if (!seats_[p].joined) slot = p;
    }
    for (uint32_t p = 0; p < seats_.players() && !slot; ++p) {
      if (seats_[p].joined && (!seats_[p].connected || seats_[p].left)) slot = p;
    }
  }
  if (!slot)
    return rejected(phase == MatchPhase::kLobby ? "match is full" : "match already running");
  if (phase != MatchPhase::kLobby && phase != MatchPhase::kRunning) {
    return rejected("the match is over");
  }
  Seat& seat = seats_[*slot];
  Decision decision = seated(Decision::Kind::kSeated, *slot);
  decision.rejoin = seat.joined;
  // Whatever the old connection had in flight is void: the newcomer gets a
  // snapshot (its final_seen is before everything held) and final ticks
  // from there.
  if (phase == MatchPhase::kRunning) seat.restart_progress();
  take(seat, request, from, who, now);
  log_line("player " + std::to_string(*slot) +
           (decision.rejoin ? " rejoined from " : " joined from ") + address_text(from) + " (" +
           printable(seat.name) + ")");
  return decision;
}

MatchAdmission::Decision MatchAdmission::seat_spectator(const v1::JoinRequest& request,
                                                        const Endpoint& from, MatchPhase phase,
                                                        const Admission& who, TimePoint now) {
  // A secure server seats a spectator where its token says; a tokenless
  // one in the first seat nobody holds (or whose holder went silent).
  std::optional<uint32_t> seat_id;
  if (phase == MatchPhase::kLobby || phase == MatchPhase::kRunning) {
    if (config_.secure) {
      const uint32_t id = who.slot;
      if (id < seats_.size()) {
        const Seat& held = seats_[id];
        if (!held.joined || !held.connected || held.client_id == who.client_id) seat_id = id;
      }
    } else {
      for (uint32_t id = seats_.players(); id < seats_.size() && !seat_id; ++id) {
        if (!seats_[id].joined || !seats_[id].connected) seat_id = id;
      }
    }
  }
  if (!seat_id) return rejected("no spectator seat is free");
  Seat& seat = seats_[*seat_id];
  seat = Seat{};
  take(seat, request, from, who, now);
  log_line("spectator " + std::to_string(*seat_id - seats_.players()) + " joined from " +
           address_text(from) + " (" + printable(seat.name) + ")");
  return seated(Decision::Kind::kSeated, *seat_id);
}

void MatchAdmission::take(Seat& seat, const v1::JoinRequest& request, const Endpoint& from,
                          const Admission& who, TimePoint now) {
  seat.joined = true;
  seat.connected = true;
  seat.endpoint = from;
  seat.join_nonce = request.nonce();
  seat.client_id = config_.secure ? who.client_id : 0;
  seat.connection.emplace(now, ids_.next());
  seat.last_receive = now;
  seat.name = request.client_name();
}

const std::vector<uint32_t>& MatchAdmission::free_silent_lobby_seats(TimePoint now) {
  freed_.clear();
  for (uint32_t id = 0; id < seats_.size(); ++id) {
    Seat& seat = seats_[id];
    if (!seat.joined) continue;
    const bool silent =
        std::chrono::duration<double>(now - seat.last_receive).count() > config_.peer_timeout_s;
    if (!seat.left && seat.connected && !silent) continue;
    const bool player = seats_.is_player(id);
    log_line(std::string(player ? "player " : "spectator ") +
             std::to_string(player ? id : id - seats_.players()) +
             (seat.left ? " left the lobby" : " went silent in the lobby") + "; its seat is free");
    seat = Seat{};
    freed_.push_back(id);
  }
  return freed_;
}

}  // namespace rwd::server
