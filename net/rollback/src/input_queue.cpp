// SPDX-License-Identifier: MIT
#include "rewind/net/input_queue.h"

#include <algorithm>

namespace rwd::net {

InputQueue::InputQueue(int32_t capacity, Tick base, InputPredictor predict)
    : capacity_(std::max<int32_t>(capacity, 1)),
      base_(std::max<Tick>(base, 0)),
      contiguous_(base_ - 1),
      predict_(predict),
      slots_(static_cast<size_t>(capacity_)) {}

InputQueue::AddOutcome InputQueue::add(Tick tick, const rwd::PlayerInput& input) {
  if (!in_range(tick)) return AddOutcome::kOutOfRange;
  Slot& s = slot(tick);
  if (s.tick == tick) return s.input == input ? AddOutcome::kDuplicate : AddOutcome::kConflict;
  s.tick = tick;
  s.input = input;
  newest_ = std::max(newest_, tick);
  advance_contiguous();
  return AddOutcome::kNew;
}

InputQueue::AddOutcome InputQueue::set_authoritative(Tick tick, const rwd::PlayerInput& input) {
  if (!in_range(tick)) return AddOutcome::kOutOfRange;
  Slot& s = slot(tick);
  if (s.tick == tick && s.input == input) return AddOutcome::kDuplicate;
  s.tick = tick;
  s.input = input;
  newest_ = std::max(newest_, tick);
  advance_contiguous();
  return AddOutcome::kNew;
}

bool InputQueue::is_confirmed(Tick tick) const {
  return in_range(tick) && slot(tick).tick == tick;
}

rwd::PlayerInput InputQueue::input_for(Tick tick) const {
  if (is_confirmed(tick)) return slot(tick).input;
  const rwd::PlayerInput newest = newest_at_or_before(tick);
  return predict_ != nullptr ? predict_(newest) : newest;
}

rwd::PlayerInput InputQueue::newest_at_or_before(Tick tick) const {
  // Walk back to the newest confirmed input. The walk is bounded by the
  // capacity; games keep it to the rollback window.
  const Tick t = std::min(tick, base_ + capacity_ - 1);
  for (Tick u = std::min(t, newest_); u >= base_; --u) {
    if (slot(u).tick == u) return slot(u).input;
  }
  return carried_;
}

void InputQueue::discard_before(Tick tick) {
  if (tick <= base_) return;
  const Tick new_base = tick;
  // Keep the newest input before the new base as the prediction seed.
  for (Tick u = std::min(new_base - 1, newest_); u >= base_; --u) {
    if (slot(u).tick == u) {
      carried_ = slot(u).input;
      break;
    }
  }
  for (Tick u = base_; u < new_base && u < base_ + capacity_; ++u) {
    if (slot(u).tick == u) slot(u).tick = kNoTick;
  }
  base_ = new_base;
  if (contiguous_ < base_ - 1) contiguous_ = base_ - 1;
  advance_contiguous();
}

void InputQueue::rebase(Tick base) {
  base = std::max<Tick>(base, 0);
  if (base >= base_) {
    discard_before(base);
    return;
  }
  // Moving back: older slots are gone, so restart from what is still held.
  InputQueue fresh(capacity_, base, predict_);
  fresh.carried_ = newest_at_or_before(base - 1);
  for (Tick u = base_; u <= newest_ && u < base_ + capacity_; ++u) {
    if (slot(u).tick == u) (void)fresh.add(u, slot(u).input);
  }
  *this = fresh;
}

void InputQueue::advance_contiguous() {
  while (contiguous_ + 1 < base_ + capacity_ && slot(contiguous_ + 1).tick == contiguous_ + 1) {
    ++contiguous_;
  }
}

}  // namespace rwd::net
