// SPDX-License-Identifier: MIT
#include "rewind/net/rollback_session.h"

#include <algorithm>

namespace rwd::net {

RollbackSession::RollbackSession(std::unique_ptr<game::Simulation> sim,
                                 const RollbackConfig& config)
    : sim_(std::move(sim)),
      player_count_(sim_->setup().player_count),
      config_(config),
      ring_(config.snapshot_ticks),
      used_(static_cast<size_t>(ring_.capacity()) * player_count_),
      scratch_inputs_(player_count_) {
  queues_.reserve(player_count_);
  for (uint32_t p = 0; p < player_count_; ++p) {
    queues_.emplace_back(config.input_ticks, sim_->tick(), sim_->game().input_spec().predict);
  }
  final_tick_ = sim_->tick() - 1;
}

InputResult RollbackSession::classify(InputQueue::AddOutcome outcome) const {
  switch (outcome) {
    case InputQueue::AddOutcome::kNew:
      return InputResult::kAccepted;
    case InputQueue::AddOutcome::kDuplicate:
      return InputResult::kDuplicate;
    case InputQueue::AddOutcome::kConflict:
      return InputResult::kConflict;
    case InputQueue::AddOutcome::kOutOfRange:
      return InputResult::kTooFar;
  }
  return InputResult::kTooFar;
}

void RollbackSession::note_changed(Tick tick) {
  if (tick >= current_tick()) return;  // not simulated yet: nothing to redo
  dirty_from_ = dirty_from_ == kNoTick ? tick : std::min(dirty_from_, tick);
}

InputResult RollbackSession::add_input(uint32_t player, Tick tick, const rwd::PlayerInput& input) {
  if (player >= player_count_) return InputResult::kBadPlayer;
  if (!check_input(sim_->game().input_spec(), input).ok()) return InputResult::kBadInput;
  if (tick <= final_tick_) return InputResult::kFinal;
  const InputQueue::AddOutcome outcome = queues_[player].add(tick, input);
  if (outcome == InputQueue::AddOutcome::kNew) note_changed(tick);
  return classify(outcome);
}

InputResult RollbackSession::add_final_input(uint32_t player, Tick tick,
                                             const rwd::PlayerInput& input) {
  if (player >= player_count_) return InputResult::kBadPlayer;
  if (!check_input(sim_->game().input_spec(), input).ok()) return InputResult::kBadInput;
  if (tick <= final_tick_) return InputResult::kFinal;
  const InputQueue::AddOutcome outcome = queues_[player].set_authoritative(tick, input);
  if (outcome == InputQueue::AddOutcome::kNew) note_changed(tick);
  return classify(outcome);
}

rwd::PlayerInput RollbackSession::used_input(uint32_t player, Tick tick) const {
  if (player >= player_count_ || tick < 0 || tick >= current_tick()) return {};
  return used_row(tick)[player];
}

bool RollbackSession::synchronize() {
  if (dirty_from_ == kNoTick) return true;
  const Tick from = std::max(dirty_from_, final_tick_ + 1);
  dirty_from_ = kNoTick;

  // A new input can change the prediction of every later tick too (repeat
  // the last input), so compare each simulated tick's inputs with what the
  // queues say now; the first difference is where history diverged.
  Tick first_bad = kNoTick;
  for (Tick t = from; t < current_tick() && first_bad == kNoTick; ++t) {
    const rwd::PlayerInput* row = used_row(t);
    for (uint32_t p = 0; p < player_count_; ++p) {
      if (!(queues_[p].input_for(t) == row[p])) {
        first_bad = t;
        break;
      }
    }
  }
  if (first_bad == kNoTick) return true;

  const game::SimSnapshot* snapshot = ring_.find(first_bad);
  if (snapshot == nullptr) return false;
  const Tick target = current_tick();
  sim_->restore(*snapshot);
  ++stats_.rollbacks;
  while (current_tick() < target && game_error_.ok()) {
    step_once();
    ++stats_.resimulated_ticks;
  }
  return true;
}

bool RollbackSession::advance() {
  const bool in_sync = synchronize();
  step_once();
  ++stats_.simulated_ticks;
  return in_sync;
}

void RollbackSession::step_once() {
  if (!game_error_.ok()) return;
  const Tick t = current_tick();
  ring_.save(*sim_);
  rwd::PlayerInput* row = used_row(t);
  for (uint32_t p = 0; p < player_count_; ++p) {
    row[p] = scratch_inputs_[p] = queues_[p].input_for(t);
  }
  if (Status status = sim_->step(scratch_inputs_); !status.ok()) {
    game_error_ = std::move(status);
    return;
  }
  if (step_hook_) step_hook_(*sim_, t);
}

std::optional<uint64_t> RollbackSession::checksum_after(Tick t) const {
  if (t < 0 || t >= current_tick()) return std::nullopt;
  if (t + 1 == current_tick()) return sim_->checksum();
  const game::SimSnapshot* snapshot = ring_.find(t + 1);
  if (snapshot == nullptr) return std::nullopt;
  return sim_->checksum_of(*snapshot);
}

std::optional<uint64_t> RollbackSession::checksum_at(Tick tick) const {
  if (tick == current_tick()) return sim_->checksum();
  const game::SimSnapshot* snapshot = ring_.find(tick);
  if (snapshot == nullptr) return std::nullopt;
  return sim_->checksum_of(*snapshot);
}

bool RollbackSession::serialize_state_at(Tick tick, std::vector<uint8_t>& out) {
  if (tick == current_tick()) {
    sim_->serialize(out);
    return true;
  }
  const game::SimSnapshot* snapshot = ring_.find(tick);
  if (snapshot == nullptr) return false;
  // Serialization works on a live simulation: borrow ours and put it back.
  // Resyncs are rare, so the two copies do not matter.
  game::SimSnapshot now;
  sim_->save(now);
  sim_->restore(*snapshot);
  sim_->serialize(out);
  sim_->restore(now);
  return true;
}

bool RollbackSession::finalize_through(Tick t) {
  if (t <= final_tick_) return true;
  const bool in_sync = dirty_from_ == kNoTick || dirty_from_ > t || synchronize();
  final_tick_ = t;
  for (InputQueue& queue : queues_) queue.discard_before(t + 1);
  return in_sync;
}

Result<std::unique_ptr<game::Simulation>> RollbackSession::load_snapshot(
    std::span<const uint8_t> serialized, std::optional<uint64_t> expected_checksum) const {
  auto scratch = game::Simulation::create(sim_->game().name(), sim_->setup());
  if (!scratch.ok()) return scratch.status();
  if (Status status = (*scratch)->deserialize(serialized); !status.ok()) return status;
  if (expected_checksum && (*scratch)->checksum() != *expected_checksum) {
    return Status::Error(ErrorCode::kCorrupt, "snapshot does not reproduce its checksum");
  }
  return std::move(*scratch);
}

Status RollbackSession::reset_from(std::span<const uint8_t> serialized,
                                   std::optional<uint64_t> expected_checksum) {
  auto scratch = load_snapshot(serialized, expected_checksum);
  if (!scratch.ok()) return scratch.status();
  sim_ = std::move(*scratch);
  const Tick t = sim_->tick();
  ring_.clear();
  final_tick_ = t - 1;
  dirty_from_ = kNoTick;
  for (InputQueue& queue : queues_) queue.rebase(t);
  return Status::Ok();
}

}  // namespace rwd::net
