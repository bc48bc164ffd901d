// SPDX-License-Identifier: MIT
#pragma once
// One player's input stream: confirmed inputs in a ring indexed by tick, and
// the prediction for ticks not yet confirmed: the game's predictor applied
// to the newest earlier confirmed input (neutral before any); without a
// predictor, that input repeated.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"

namespace rwd::net {

class InputQueue {
 public:
  enum class AddOutcome : uint8_t {
    kNew,         ///< stored
    kDuplicate,   ///< the same input was already stored for that tick
    kConflict,    ///< a different input is already stored; kept the old one
    kOutOfRange,  ///< before the queue's base or beyond its capacity
  };

  /// `capacity` ticks starting at `base` can be held; base only moves
  /// forward. `predict` (nullptr: repeat) guesses unconfirmed ticks.
  explicit InputQueue(int32_t capacity = 256, Tick base = 0, InputPredictor predict = nullptr);

  /// Stores a confirmed input. First writer wins (an input, once sent, never
  /// changes); use set_authoritative() for the server's final word.
  AddOutcome add(Tick tick, const rwd::PlayerInput& input);
  /// Stores an input that overrides anything stored (the server's final input).
  AddOutcome set_authoritative(Tick tick, const rwd::PlayerInput& input);

  bool is_confirmed(Tick tick) const;
  /// The confirmed input, or the prediction for an unconfirmed tick.
  rwd::PlayerInput input_for(Tick tick) const;
  /// Highest tick such that every tick in [base, it] is confirmed (base - 1 if none).
  Tick contiguous_through() const { return contiguous_; }
  /// Newest confirmed tick (kNoTick if none).
  Tick newest() const { return newest_; }
  Tick base() const { return base_; }
  int32_t capacity() const { return capacity_; }

  /// Forgets ticks before `tick`, remembering the newest forgotten input as
  /// the prediction seed.
  void discard_before(Tick tick);
  /// Empties the queue and restarts it at `base`, keeping confirmed inputs
  /// at or after `base` (a resync moved the simulation to `base`).
  void rebase(Tick base);

 private:
  struct Slot {
    Tick tick = kNoTick;
    rwd::PlayerInput input;
  };
  bool in_range(Tick tick) const { return tick >= base_ && tick < base_ + capacity_; }
  Slot& slot(Tick tick) { return slots_[static_cast<size_t>(tick % capacity_)]; }
  const Slot& slot(Tick tick) const { return slots_[static_cast<size_t>(tick % capacity_)]; }
  void advance_contiguous();
  // The newest confirmed input at or before `tick` (carried_ before base_).
  rwd::PlayerInput newest_at_or_before(Tick tick) const;

  int32_t capacity_;
  Tick base_;
  Tick contiguous_;
  Tick newest_ = kNoTick;
  InputPredictor predict_;
  rwd::PlayerInput carried_;  // newest input before base_, the prediction seed
  std::vector<Slot> slots_;
};

}  // namespace rwd::net
