// SPDX-License-Identifier: MIT
#include "rewind/server/match_seats.h"

#include <algorithm>

namespace rwd::server {

void Seat::restart_progress() {
  final_seen = kNoTick;
  final_sent = kNoTick;
  resend_cursor = kNoTick;
  standalone_from = 0;
  left = false;
  last_lead = 0;
  late_counted = kNoTick;
  sent_input = false;
}

MatchSeats::MatchSeats(uint32_t players, uint32_t spectators)
    : players_(players), seats_(size_t{players} + spectators) {}

Seat* MatchSeats::find(uint64_t connection_id, uint32_t* id) {
  for (uint32_t s = 0; s < seats_.size(); ++s) {
    Seat& seat = seats_[s];
    if (seat.joined && seat.connection && seat.connection->connection_id() == connection_id) {
      *id = s;
      return &seat;
    }
  }
  return nullptr;
}

std::optional<uint32_t> MatchSeats::held_from(const Endpoint& endpoint) const {
  for (uint32_t s = 0; s < seats_.size(); ++s) {
    const Seat& seat = seats_[s];
    if (seat.joined && seat.connected && seat.endpoint == endpoint) return s;
  }
  return std::nullopt;
}

bool MatchSeats::seated(uint32_t id, const Endpoint& endpoint) const {
  return id < seats_.size() && seats_[id].present() && seats_[id].endpoint == endpoint;
}

uint32_t MatchSeats::players_connected() const {
  uint32_t count = 0;
  for (const Seat& seat : player_seats()) count += (seat.joined && seat.connected) ? 1 : 0;
  return count;
}

uint32_t MatchSeats::players_joined() const {
  const std::span<const Seat> players = player_seats();
  return static_cast<uint32_t>(
      std::count_if(players.begin(), players.end(), [](const Seat& seat) { return seat.joined; }));
}

Tick MatchSeats::acknowledged_by_all(Tick newest) const {
  Tick acked = newest;
  for (const Seat& seat : player_seats()) {
    if (seat.joined && seat.connected) acked = std::min(acked, seat.final_seen);
  }
  return acked;
}

}  // namespace rwd::server
