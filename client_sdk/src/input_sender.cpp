// SPDX-License-Identifier: MIT
#include "input_sender.h"

#include <algorithm>
#include <chrono>

#include "rewind/proto/input_wire.h"

namespace rwd::client {

rwd::PlayerInput InputSender::take(Tick tick, const InputSpec& spec) {
  rwd::PlayerInput input = provider_ ? provider_(tick) : held_input_;
  if (!check_input(spec, input).ok()) input = {};
  unacked_.emplace_back(tick, input);
  next_input_tick_ = tick + 1;
  return input;
}

void InputSender::write_frame(uint32_t player, Tick last_final_received, v1::InputFrame& frame) {
  while (!unacked_.empty() &&
         (unacked_.front().first <= input_ack_ || unacked_.size() > kMaxInputsPerPacket)) {
    unacked_.pop_front();
  }
  frame.set_player(player);
  frame.set_first_tick(unacked_.empty() ? std::max<Tick>(next_input_tick_, 0)
                                        : unacked_.front().first);
  frame.set_last_final_tick_seen(last_final_received);
  last_final_acked_ = last_final_received;
  ack_waiting_ = false;
  for (const auto& [tick, input] : unacked_) *frame.add_inputs() = proto::to_wire(input);
}

InputSender::AckWait InputSender::ack_wait(Tick last_final_received, TimePoint now,
                                           double period_s) {
  if (last_final_received <= last_final_acked_) return AckWait::kNone;
  if (!ack_waiting_) {
    ack_waiting_ = true;
    ack_waiting_since_ = now;
  }
  return std::chrono::duration<double>(now - ack_waiting_since_).count() >= period_s
             ? AckWait::kDue
             : AckWait::kWaiting;
}

}  // namespace rwd::client
