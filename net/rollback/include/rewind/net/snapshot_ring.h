// SPDX-License-Identifier: MIT
#pragma once
// Saved simulation states by tick. Slot buffers are reused, so once every
// slot has been written, saving allocates nothing.
#include <cstdint>
#include <vector>

#include "rewind/game/simulation.h"

namespace rwd::net {

class SnapshotRing {
 public:
  /// Holds the states of the last `capacity` ticks.
  explicit SnapshotRing(int32_t capacity);

  /// Saves `sim` as the state at the start of sim.tick().
  void save(const game::Simulation& sim);
  /// The state at the start of `tick`, or nullptr if not held.
  const game::SimSnapshot* find(Tick tick) const;
  /// Forgets everything (after a resync).
  void clear();
  int32_t capacity() const { return static_cast<int32_t>(slots_.size()); }

 private:
  struct Slot {
    bool used = false;
    game::SimSnapshot snapshot;
  };
  std::vector<Slot> slots_;
};

}  // namespace rwd::net
