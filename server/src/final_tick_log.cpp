// SPDX-License-Identifier: MIT
#include "rewind/server/final_tick_log.h"

#include <algorithm>
#include <cmath>

#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_packing.h"

namespace rwd::server {

void FinalTickLog::append(Tick tick, std::span<const rwd::PlayerInput> inputs, uint64_t substituted,
                          uint64_t checksum, Tick made_at) {
  v1::FinalTick& final_tick = ticks_.emplace_back();
  final_tick.set_tick(tick);
  proto::pack_inputs(inputs, {}, *final_tick.mutable_packed_inputs());
  final_tick.set_substituted_mask(substituted);
  final_tick.set_checksum(checksum);
  Held& held = held_.emplace_back();
  held.size = static_cast<uint32_t>(final_tick.ByteSizeLong());
  held.made_at = made_at;
  // The same tick packed against the one before: a byte per unchanged input.
  if (previous_inputs_.size() == inputs.size()) {
    proto::pack_inputs(inputs, previous_inputs_, held.delta);
    v1::FinalTick as_delta = final_tick;
    as_delta.set_packed_inputs(held.delta);
    as_delta.set_delta(true);
    held.delta_size = static_cast<uint32_t>(as_delta.ByteSizeLong());
  }
  previous_inputs_.assign(inputs.begin(), inputs.end());
  next_ = tick + 1;
}

void FinalTickLog::trim(Tick acked_by_all, size_t max_held) {
  while (!ticks_.empty() && (ticks_.front().tick() <= acked_by_all || ticks_.size() > max_held)) {
    ticks_.pop_front();
    held_.pop_front();
  }
}

void FinalTickLog::add_to(v1::FinalTicks& out, size_t budget, Cursor& cursor, Tick now,
                          double rtt_ticks) const {
  if (ticks_.empty()) return;
  const Tick oldest_held = ticks_.front().tick();
  auto add = [&](Tick t) {
    const size_t index = static_cast<size_t>(t - oldest_held);
    const Held& held = held_[index];
    const bool as_delta = t > cursor.standalone_from && !held.delta.empty();
    const size_t size = (as_delta ? held.delta_size : held.size) + 3;  // tag + length prefix
    if (size > budget || out.ticks_size() >= static_cast<int>(net::kMaxFinalTicksPerPacket)) {
      return false;
    }
    budget -= size;
    v1::FinalTick* added = out.add_ticks();
    *added = ticks_[index];
    if (as_delta) {
      added->set_packed_inputs(held.delta);
      added->set_delta(true);
    }
    return true;
  };
  // New ticks first, so a round trip never limits how fast finals flow;
  // then the oldest unacknowledged ones again, for loss. Clients accept
  // them in any order.
  const Tick first_new = std::max({cursor.sent + 1, cursor.seen + 1, oldest_held});
  Tick t = first_new;
  while (t <= newest() && add(t)) ++t;
  cursor.sent = std::max(cursor.sent, t - 1);
  // Ticks sent less than a round trip (and two ticks) ago are not resent:
  // their acknowledgement cannot be back yet. The resend cursor walks
  // round-robin through the overdue range, so after a loss burst every
  // missing tick comes back within a few packets instead of the oldest few
  // being resent over and over.
  const Tick lowest = std::max(cursor.seen + 1, oldest_held);
  const Tick due_before = now - static_cast<Tick>(std::ceil(rtt_ticks)) - 2;
  Tick overdue_end = lowest;
  while (overdue_end < first_new &&
         held_[static_cast<size_t>(overdue_end - oldest_held)].made_at <= due_before) {
    ++overdue_end;
  }
  if (lowest >= overdue_end) return;
  Tick r = std::clamp(cursor.resend, lowest, overdue_end - 1);
  for (Tick sent = 0; sent < overdue_end - lowest && add(r); ++sent) {
    r = r + 1 < overdue_end ? r + 1 : lowest;
  }
  cursor.resend = r;
}

}  // namespace rwd::server
