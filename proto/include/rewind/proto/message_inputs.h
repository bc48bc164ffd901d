// SPDX-License-Identifier: MIT
#pragma once
// The inputs carried by the messages that may pack them (final ticks and
// relayed runs), read one way for the envelope codec's checks and for the
// client: packed bytes when present, the repeated Input fields otherwise.
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/v1/input.pb.h"

namespace rwd::proto {

/// Checks the inputs of every final tick of `finals`: standalone ones
/// (packed or repeated) fully, `delta` ones (packed against the inputs of
/// the tick before, which only the receiver holds) for their form.
/// kCorrupt naming the tick otherwise.
Status check_final_tick_inputs(const v1::FinalTicks& finals);

/// One final tick's inputs into `out`: a `delta` tick against `previous`
/// (the final inputs of the tick before, as the receiver applied them;
/// kCorrupt when it has none), a standalone one on its own. kCorrupt for
/// bad packing or an axis outside [-1000, 1000].
Status final_tick_inputs(const v1::FinalTick& tick, std::span<const rwd::PlayerInput> previous,
                         std::vector<rwd::PlayerInput>& out);

/// One run of a player's inputs from a FinalTicks message's `relayed`.
struct RelayedRun {
  uint32_t player = 0;
  int32_t first_tick = 0;
  std::vector<rwd::PlayerInput> inputs;
};

/// Appends a run (at most kMaxPackedInputs inputs) to a FinalTicks
/// message's `relayed` bytes, its first tick relative to `server_tick`.
void append_relayed_run(uint32_t player, int32_t first_tick, int32_t server_tick,
                        std::span<const rwd::PlayerInput> inputs, std::string& out);

/// The runs of `finals.relayed()`: kCorrupt for bad packing, a player past
/// the slot limit, a tick outside [0, 2^31) or more than 256 runs.
Status relayed_runs(const v1::FinalTicks& finals, std::vector<RelayedRun>& out);

/// A relayed run's inputs, packed or repeated (not both).
Status relayed_run_inputs(const v1::RelayedInputs& run, std::vector<rwd::PlayerInput>& out);

}  // namespace rwd::proto
