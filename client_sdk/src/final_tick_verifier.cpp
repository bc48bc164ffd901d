// SPDX-License-Identifier: MIT
#include "final_tick_verifier.h"

#include <optional>

namespace rwd::client {

void FinalTickVerifier::seat(uint32_t player, uint32_t player_count) {
  player_ = player;
  player_count_ = player_count;
}

void FinalTickVerifier::on_relayed(net::RollbackSession& session, uint32_t player, Tick first_tick,
                                   std::span<const rwd::PlayerInput> inputs) {
  if (player >= player_count_ || player == player_) return;
  for (size_t i = 0; i < inputs.size(); ++i) {
    (void)session.add_input(player, first_tick + static_cast<Tick>(i), inputs[i]);
  }
}

void FinalTickVerifier::on_relayed(net::RollbackSession& session, const v1::RelayedInputs& run) {
  if (proto::relayed_run_inputs(run, relayed_buffer_).ok()) {
    on_relayed(session, run.player(), run.first_tick(), relayed_buffer_);
  }
}

void FinalTickVerifier::on_relayed_runs(net::RollbackSession& session,
                                        const v1::FinalTicks& finals) {
  if (!proto::relayed_runs(finals, relayed_runs_).ok()) return;
  for (const proto::RelayedRun& run : relayed_runs_) {
    on_relayed(session, run.player, run.first_tick, run.inputs);
  }
}

FinalTickVerifier::Applied FinalTickVerifier::apply(net::RollbackSession& session,
                                                    const v1::FinalTicks& finals) {
  Applied failure = Applied::kOk;
  for (const v1::FinalTick& final_tick : finals.ticks()) {
    const Tick tick = final_tick.tick();
    if (tick <= last_final_received_) continue;  // duplicate
    if (tick == last_final_received_ + 1) {
      if (!apply_one(session, final_tick, failure)) return failure;
      // Ticks that arrived ahead of this one can follow now.
      for (auto it = early_finals_.begin();
           it != early_finals_.end() && it->first == last_final_received_ + 1;
           it = early_finals_.erase(it)) {
        if (!apply_one(session, it->second, failure)) return failure;
      }
    } else if (tick <= last_final_received_ + snapshot_ticks_ &&
               early_finals_.size() < static_cast<size_t>(snapshot_ticks_)) {
      early_finals_.emplace(tick, final_tick);  // a gap: keep it for later
    }
  }
  return Applied::kOk;
}

bool FinalTickVerifier::apply_one(net::RollbackSession& session, const v1::FinalTick& final_tick,
                                  Applied& failure) {
  // Packed against the tick before, which is always the one applied last:
  // final ticks are applied in order.
  if (!proto::final_tick_inputs(final_tick, last_final_inputs_, final_inputs_buffer_).ok() ||
      final_inputs_buffer_.size() != player_count_) {
    failure = Applied::kRejected;
    return false;
  }
  const Tick tick = final_tick.tick();
  for (uint32_t p = 0; p < player_count_; ++p) {
    const net::InputResult result = session.add_final_input(p, tick, final_inputs_buffer_[p]);
    if (result == net::InputResult::kTooFar) {
      // Beyond our input window: we cannot apply it, so we cannot verify it.
      failure = Applied::kTooFar;
      return false;
    }
  }
  pending_finals_.emplace_back(tick, final_tick.checksum());
  last_final_received_ = tick;
  last_final_inputs_.swap(final_inputs_buffer_);
  return true;
}

FinalTickVerifier::Check FinalTickVerifier::check_next(net::RollbackSession& session) {
  if (pending_finals_.empty()) return {};
  const auto [tick, server_checksum] = pending_finals_.front();
  if (tick >= session.current_tick()) return {};  // not simulated yet
  std::optional<uint64_t> local;
  if (session.finalize_through(tick)) local = session.checksum_after(tick);
  if (!local) return {Verdict::kLost, tick, 0, server_checksum};  // history we cannot re-simulate
  pending_finals_.pop_front();
  if (*local != server_checksum) return {Verdict::kMismatch, tick, *local, server_checksum};
  agreed_through_ = tick;
  return {Verdict::kAgreed, tick, *local, server_checksum};
}

uint64_t FinalTickVerifier::on_resync_loaded(Tick tick) {
  last_final_received_ = tick - 1;  // the server resends final ticks from here
  last_final_inputs_.clear();       // ... and sends the first one standalone
  pending_finals_.clear();
  early_finals_.clear();
  if (tick - 1 <= agreed_through_) return 0;
  const auto passed_over = static_cast<uint64_t>(tick - 1 - agreed_through_);
  agreed_through_ = tick - 1;
  return passed_over;
}

}  // namespace rwd::client
