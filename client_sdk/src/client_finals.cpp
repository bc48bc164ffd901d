// SPDX-License-Identifier: MIT
// The client protocol's authoritative inputs: other players' inputs as the
// server relays them, and final ticks applied strictly in order (each one's
// inputs may be packed against the tick before, which is then always the
// one applied last), with ticks that arrive ahead of a gap held back.
#include "client_protocol_impl.h"
#include "rewind/proto/message_inputs.h"

namespace rwd::client {

void ClientProtocol::Impl::on_relayed(uint32_t player, Tick first_tick,
                                      std::span<const rwd::PlayerInput> inputs) {
  if (player >= player_count_ || player == player_) return;
  for (size_t i = 0; i < inputs.size(); ++i) {
    (void)session_->add_input(player, first_tick + static_cast<Tick>(i), inputs[i]);
  }
}

void ClientProtocol::Impl::on_final_ticks(const v1::FinalTicks& finals, TimePoint now) {
  server_tick_ = std::max(server_tick_, finals.server_tick());
  input_ack_ = std::max(input_ack_, finals.input_ack_tick());
  if (next_input_tick_ > 0) time_sync_.on_lead_report(finals.input_lead_ticks());
  // While desynced, final ticks are neither applied nor acknowledged: the
  // server resends them from the resync snapshot's tick on.
  if (awaiting_resync_) return;
  for (const v1::FinalTick& final_tick : finals.ticks()) {
    const Tick tick = final_tick.tick();
    if (tick <= last_final_received_) continue;  // duplicate
    if (tick == last_final_received_ + 1) {
      if (!apply_final_tick(final_tick, now)) return;
      // Ticks that arrived ahead of this one can follow now.
      for (auto it = early_finals_.begin();
           it != early_finals_.end() && it->first == last_final_received_ + 1;
           it = early_finals_.erase(it)) {
        if (!apply_final_tick(it->second, now)) return;
      }
    } else if (tick <= last_final_received_ + config_.snapshot_ticks &&
               early_finals_.size() < static_cast<size_t>(config_.snapshot_ticks)) {
      early_finals_.emplace(tick, final_tick);  // a gap: keep it for later
    }
  }
}

bool ClientProtocol::Impl::apply_final_tick(const v1::FinalTick& final_tick, TimePoint now) {
  // Packed against the tick before, which is always the one applied last:
  // final ticks are applied in order.
  if (!proto::final_tick_inputs(final_tick, last_final_inputs_, final_inputs_buffer_).ok() ||
      final_inputs_buffer_.size() != player_count_) {
    ++stats_.packets_rejected;
    return false;
  }
  const Tick tick = final_tick.tick();
  for (uint32_t p = 0; p < player_count_; ++p) {
    const net::InputResult result = session_->add_final_input(p, tick, final_inputs_buffer_[p]);
    if (result == net::InputResult::kTooFar) {
      // Beyond our input window: we cannot apply it, so we cannot verify it.
      request_resync(now);
      return false;
    }
  }
  pending_finals_.emplace_back(tick, final_tick.checksum());
  last_final_received_ = tick;
  last_final_inputs_.swap(final_inputs_buffer_);
  return true;
}

}  // namespace rwd::client
