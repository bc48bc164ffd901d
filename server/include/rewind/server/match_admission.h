// SPDX-License-Identifier: MIT
#pragma once
// Who takes which seat of a hosted match. A join request is answered again
// when it repeats one already seated, refused with a reason, or seated: a
// secure server seats the slot the sender's connect token names (taking it
// back from a holder who is gone, never from one still playing); a
// tokenless one the first free slot in the lobby, or mid-match a slot
// nobody took yet (late join) or whose player timed out or left. In the
// lobby, a seat whose holder left or went silent is free again, so nobody
// can squat a seat until the start.
//
// It decides and fills in the seat's holder; the host answers the client,
// counts, and resets what it keeps per seat.
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/net/connection_id.h"
#include "rewind/server/match_config.h"
#include "rewind/server/match_phase.h"
#include "rewind/server/match_seats.h"
#include "rewind/server/secure_gateway.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

class MatchAdmission {
 public:
  /// `config` and `seats` outlive this.
  MatchAdmission(const MatchConfig& config, MatchSeats& seats);

  struct Decision {
    enum class Kind : uint8_t {
      kAnswerAgain,  // the sender holds `seat` by this very request: our answer was lost
      kSeated,       // the sender now holds `seat`
      kRejected,     // `reason` says why
    };
    Kind kind = Kind::kRejected;
    uint32_t seat = 0;
    bool rejoin = false;  // kSeated on a player slot that was held before
    std::string reason;
  };

  /// Decides on a join request from `from` (`who`: what its token names, or
  /// on a tokenless server that it answered a cookie; never null). Seated:
  /// the seat's holder fields are the sender's, with a new connection; on
  /// a player slot mid-match its progress has restarted.
  Decision admit(const v1::JoinRequest& request, const Endpoint& from, MatchPhase phase,
                 const Admission& who, TimePoint now);

  /// In the lobby: frees every seat whose holder left or was silent for
  /// the peer timeout; returns the seats freed (valid until the next call).
  const std::vector<uint32_t>& free_silent_lobby_seats(TimePoint now);

 private:
  Decision seat_player(const v1::JoinRequest& request, const Endpoint& from, MatchPhase phase,
                       const Admission& who, TimePoint now);
  Decision seat_spectator(const v1::JoinRequest& request, const Endpoint& from, MatchPhase phase,
                          const Admission& who, TimePoint now);
  void take(Seat& seat, const v1::JoinRequest& request, const Endpoint& from, const Admission& who,
            TimePoint now);

  const MatchConfig& config_;
  MatchSeats& seats_;
  net::ConnectionIdGenerator ids_;  // unguessable by other clients
  std::vector<uint32_t> freed_;
};

}  // namespace rwd::server
