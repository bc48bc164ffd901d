// SPDX-License-Identifier: MIT
#pragma once
// Our own inputs on their way to the server: each tick's input taken once
// (from the provider, or the held input), kept until the server
// acknowledges it and resent in every input frame until then, and the
// acknowledgement of final ticks that those frames carry back. One concern
// because the frame is the unit: it carries the unacknowledged inputs and
// the newest final tick seen, so an acknowledgement waits for the next
// frame rather than going alone (which would double what a player sends).
//
// It writes the frame; the protocol stamps and sends it. The pending
// inputs live in a deque trimmed from the front, so a steady match
// allocates nothing per tick.
#include <algorithm>
#include <cstddef>
#include <deque>
#include <utility>

#include "rewind/client/client_protocol.h"
#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/net/clock.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::client {

class InputSender {
 public:
  using TimePoint = net::TimePoint;
  /// Redundancy: every unacknowledged input goes in each frame, up to this
  /// many (the newest).
  static constexpr size_t kMaxInputsPerPacket = 64;

  /// Where the acknowledgement of new final ticks stands (ack_wait()).
  enum class AckWait : uint8_t {
    kNone,     ///< nothing new to acknowledge
    kWaiting,  ///< new final ticks, waiting for the next input frame
    kDue,      ///< no frame took it within a tick period: send one now
  };

  void set_provider(ClientProtocol::InputProvider provider) { provider_ = std::move(provider); }
  /// The input for every tick from now on when no provider is set
  /// (checked by take(), as a provider's is).
  void hold(const rwd::PlayerInput& input) { held_input_ = input; }

  /// The first tick whose input is not yet taken.
  Tick next_input_tick() const { return next_input_tick_; }
  bool due(Tick tick) const { return tick >= next_input_tick_; }
  /// Our input for `tick` (due): the provider's or the held one, the neutral
  /// input when `spec` refuses it (the server would, and the other players
  /// would never see it). Kept until acknowledged.
  rwd::PlayerInput take(Tick tick, const InputSpec& spec);
  /// Inputs before `tick` will never be taken (a resync loaded it).
  void skip_to(Tick tick) { next_input_tick_ = std::max(next_input_tick_, tick); }

  /// The server has every input of ours through `tick`.
  void on_ack(Tick tick) { input_ack_ = std::max(input_ack_, tick); }
  /// Pending inputs (neither acknowledged nor trimmed yet).
  size_t unacked() const { return unacked_.size(); }

  /// Fills an input frame for `player`: the unacknowledged inputs (the
  /// acknowledged ones are dropped first) and `last_final_received`, which
  /// counts as acknowledged from now on.
  void write_frame(uint32_t player, Tick last_final_received, v1::InputFrame& frame);
  /// Whether final ticks through `last_final_received` still need
  /// acknowledging, and whether that has waited `period_s` since first seen.
  AckWait ack_wait(Tick last_final_received, TimePoint now, double period_s);
  /// The last final tick a frame carried.
  Tick last_final_acked() const { return last_final_acked_; }

 private:
  ClientProtocol::InputProvider provider_;
  rwd::PlayerInput held_input_;
  Tick next_input_tick_ = 0;
  std::deque<std::pair<Tick, rwd::PlayerInput>> unacked_;
  Tick input_ack_ = kNoTick;
  Tick last_final_acked_ = kNoTick;
  /// Since when an acknowledgement of new final ticks has waited for an
  /// input frame to carry it (meaningful while ack_waiting_).
  TimePoint ack_waiting_since_;
  bool ack_waiting_ = false;
};

}  // namespace rwd::client
