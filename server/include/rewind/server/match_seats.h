// SPDX-License-Identifier: MIT
#pragma once
// The seats of a hosted match: one per player slot, then the spectator
// seats (seat id players + s). A seat is who holds it (address, connection,
// token's client id, name), whether it is still heard from, and how far its
// holder has come through the final ticks. What the other parts of the host
// keep per seat (a resync on its way, a desync report being assembled) they
// keep themselves, by seat id.
#include <asio/ip/udp.hpp>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/tick.h"
#include "rewind/net/clock.h"
#include "rewind/net/connection.h"

namespace rwd::server {

using Endpoint = asio::ip::udp::endpoint;
using TimePoint = net::TimePoint;

struct Seat {
  bool joined = false;
  bool connected = false;
  bool left = false;  // sent Disconnect: nothing more is taken from it
  Endpoint endpoint;
  uint64_t join_nonce = 0;
  uint64_t client_id = 0;  // secure mode: the client its token names
  std::optional<net::Connection> connection;
  TimePoint last_receive;
  std::string name;
  Tick final_seen = kNoTick;     // newest final tick the client has acknowledged
  Tick final_sent = kNoTick;     // newest final tick sent at least once
  Tick resend_cursor = kNoTick;  // round-robin position among unacknowledged finals
  // The first final tick the client applies without the one before it
  // (the match's first, or a resync snapshot's): sent standalone; later
  // ticks go packed against the tick before.
  Tick standalone_from = 0;
  int32_t last_lead = 0;        // how far ahead of the server clock its inputs run
  Tick late_counted = kNoTick;  // newest too-late input counted as rejected
  bool sent_input = false;

  /// Held, and neither dropped by the peer timeout nor gone.
  bool present() const { return joined && connected && !left; }
  /// A new connection takes the seat mid-match: its progress through the
  /// final ticks starts over (identity fields are the admission's).
  void restart_progress();
};

class MatchSeats {
 public:
  MatchSeats(uint32_t players, uint32_t spectators);

  /// Player slots, then spectator seats.
  uint32_t size() const { return static_cast<uint32_t>(seats_.size()); }
  uint32_t players() const { return players_; }
  bool is_player(uint32_t id) const { return id < players_; }
  Seat& operator[](uint32_t id) { return seats_[id]; }
  const Seat& operator[](uint32_t id) const { return seats_[id]; }
  std::span<Seat> player_seats() { return {seats_.data(), players_}; }
  std::span<const Seat> player_seats() const { return {seats_.data(), players_}; }
  std::span<Seat> all() { return seats_; }

  /// The joined seat whose connection has `connection_id`, or null.
  Seat* find(uint64_t connection_id, uint32_t* id);
  /// The seat joined and connected from `endpoint`, if any.
  std::optional<uint32_t> held_from(const Endpoint& endpoint) const;
  /// Whether seat `id` is held from `endpoint` now (joined, connected, not gone).
  bool seated(uint32_t id, const Endpoint& endpoint) const;
  uint32_t players_connected() const;
  uint32_t players_joined() const;
  /// Players whose final-tick progress the history must wait for: the
  /// oldest final tick a connected player has not acknowledged, or `newest`.
  Tick acknowledged_by_all(Tick newest) const;

 private:
  uint32_t players_ = 0;
  std::vector<Seat> seats_;
};

}  // namespace rwd::server
