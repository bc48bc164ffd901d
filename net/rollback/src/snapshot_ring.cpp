// SPDX-License-Identifier: MIT
#include "rewind/net/snapshot_ring.h"

#include <algorithm>

namespace rwd::net {

SnapshotRing::SnapshotRing(int32_t capacity)
    : slots_(static_cast<size_t>(std::max<int32_t>(capacity, 2))) {}

void SnapshotRing::save(const game::Simulation& sim) {
  Slot& slot = slots_[static_cast<size_t>(sim.tick()) % slots_.size()];
  sim.save(slot.snapshot);
  slot.used = true;
}

const game::SimSnapshot* SnapshotRing::find(Tick tick) const {
  if (tick < 0) return nullptr;
  const Slot& slot = slots_[static_cast<size_t>(tick) % slots_.size()];
  return slot.used && slot.snapshot.tick == tick ? &slot.snapshot : nullptr;
}

void SnapshotRing::clear() {
  for (Slot& slot : slots_) slot.used = false;
}

}  // namespace rwd::net
