// SPDX-License-Identifier: MIT
#pragma once
// The inputs a hosted match accepted since its last broadcast, waiting to
// be relayed to every other client in the tick's one datagram to each:
// O(players) datagrams a tick instead of O(players^2). Inputs are gathered
// in runs of consecutive ticks of one player (at most
// proto::kMaxPackedInputs long), each run packed once per broadcast, every
// input against the one before it, and handed to every client but its
// player's.
//
// Allocation: runs, packed strings and their buffers keep their capacity
// from tick to tick; after warm-up a broadcast allocates nothing.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"

namespace rwd::server {

class InputRelay {
 public:
  /// Starts gathering the accepted inputs of one frame from `player`.
  void begin(uint32_t player);
  /// An input of that frame the session accepted for `tick`; a gap in the
  /// ticks or a full run starts a new run.
  void add(Tick tick, const rwd::PlayerInput& input);
  /// Ends the frame; returns how many of its inputs will be relayed.
  size_t end();

  /// Packs every run gathered since the last clear(), stamped with the
  /// server's clock `server_tick`.
  void pack(Tick server_tick);
  /// Appends to `out` the packed runs of players other than `client`, in
  /// the order they came, skipping any that would leave less than `keep`
  /// of `budget`; returns the budget left.
  size_t append_for(uint32_t client, size_t budget, size_t keep, std::string& out) const;
  /// After the broadcast: everything gathered has gone out.
  void clear() { runs_used_ = 0; }

  size_t runs() const { return runs_used_; }

 private:
  struct Run {
    uint32_t player = 0;
    Tick first_tick = 0;
    std::vector<rwd::PlayerInput> inputs;
    std::string packed;
  };
  void close_run();

  std::vector<Run> runs_;  // the first runs_used_ are this broadcast's
  size_t runs_used_ = 0;
  uint32_t player_ = 0;
  Tick run_first_ = kNoTick;
  Tick run_next_ = kNoTick;
  std::vector<rwd::PlayerInput> run_;  // the run being gathered
  size_t frame_count_ = 0;
};

}  // namespace rwd::server
