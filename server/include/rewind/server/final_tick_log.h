// SPDX-License-Identifier: MIT
#pragma once
// The final ticks a match still holds for its clients, oldest first, and
// how they go into each client's datagram: new ticks first, then ticks a
// round trip has passed without acknowledging, round-robin; each tick's
// inputs packed against the tick before (the client applies final ticks in
// order, so it holds that one), or standalone for the first tick a client
// applies after the start or a snapshot.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/v1/input.pb.h"

namespace rwd::server {

class FinalTickLog {
 public:
  /// Where one client stands: what it acknowledged and was sent, where
  /// the resend walk is, and the first tick it applies without the one
  /// before.
  struct Cursor {
    Tick seen = kNoTick;
    Tick sent = kNoTick;
    Tick resend = kNoTick;
    Tick standalone_from = 0;
  };

  /// Appends the next final tick (`tick` follows the last one appended),
  /// made at server tick `made_at`.
  void append(Tick tick, std::span<const rwd::PlayerInput> inputs, uint64_t substituted,
              uint64_t checksum, Tick made_at);
  /// Drops the ticks every client has (through `acked_by_all`) and, past
  /// `max_held` ticks, the oldest.
  void trim(Tick acked_by_all, size_t max_held);

  bool empty() const { return ticks_.empty(); }
  /// The oldest tick held, or the next to be appended when none is.
  Tick oldest() const { return ticks_.empty() ? next_ : ticks_.front().tick(); }
  Tick newest() const { return next_ - 1; }
  const std::deque<v1::FinalTick>& ticks() const { return ticks_; }

  /// Adds ticks for a client at `cursor` to `out`, within `budget` encoded
  /// bytes and the per-message tick limit, and moves the cursor. `now` is
  /// the server's tick, `rtt_ticks` the client's round trip in ticks.
  void add_to(v1::FinalTicks& out, size_t budget, Cursor& cursor, Tick now, double rtt_ticks) const;

 private:
  struct Held {
    uint32_t size = 0;        // encoded size, standalone
    std::string delta;        // the inputs packed against the tick before
    uint32_t delta_size = 0;  // encoded size sent that way
    Tick made_at = 0;
  };
  std::deque<v1::FinalTick> ticks_;  // standalone, as appended
  std::deque<Held> held_;            // in step with ticks_
  std::vector<rwd::PlayerInput> previous_inputs_;
  Tick next_ = 0;
};

}  // namespace rwd::server
