// SPDX-License-Identifier: MIT
#include "rewind/server/input_relay.h"

#include "rewind/proto/input_packing.h"
#include "rewind/proto/message_inputs.h"

namespace rwd::server {

void InputRelay::begin(uint32_t player) {
  player_ = player;
  run_first_ = kNoTick;
  run_next_ = kNoTick;
  run_.clear();
  frame_count_ = 0;
}

void InputRelay::add(Tick tick, const rwd::PlayerInput& input) {
  if (run_next_ != tick || run_.size() == proto::kMaxPackedInputs) {
    close_run();
    run_first_ = tick;
  }
  run_.push_back(input);
  run_next_ = tick + 1;
}

size_t InputRelay::end() {
  close_run();
  return frame_count_;
}

void InputRelay::close_run() {
  if (run_.empty()) return;
  if (runs_used_ == runs_.size()) runs_.emplace_back();
  Run& run = runs_[runs_used_++];
  run.player = player_;
  run.first_tick = run_first_;
  run.inputs.assign(run_.begin(), run_.end());  // keeps the run's capacity
  frame_count_ += run_.size();
  run_.clear();
}

void InputRelay::pack(Tick server_tick) {
  for (size_t r = 0; r < runs_used_; ++r) {
    Run& run = runs_[r];
    run.packed.clear();
    proto::append_relayed_run(run.player, run.first_tick, server_tick, run.inputs, run.packed);
  }
}

size_t InputRelay::append_for(uint32_t client, size_t budget, size_t keep, std::string& out) const {
  for (size_t r = 0; r < runs_used_; ++r) {
    const Run& run = runs_[r];
    if (run.player == client || budget < keep || run.packed.size() > budget - keep) continue;
    budget -= run.packed.size();
    out += run.packed;
  }
  return budget;
}

}  // namespace rwd::server
