// SPDX-License-Identifier: MIT
#pragma once
// The inputs carried by the messages that may pack them (final ticks and
// relayed runs), read one way for the envelope codec's checks and for the
// client: packed bytes when present, the repeated Input fields otherwise.
#include <vector>

#include "rewind/game/player_input.h"
#include "rewind/sim/status.h"
#include "rewind/v1/input.pb.h"

namespace rwd::proto {

/// The inputs of each final tick of `finals`, in order, into `out`: a
/// `delta` tick against the previous tick of the message, which must be
/// the tick before it. kCorrupt (naming the tick) otherwise, or for bad
/// packing or an axis outside [-1000, 1000].
Status final_tick_inputs(const v1::FinalTicks& finals,
                         std::vector<std::vector<game::PlayerInput>>& out);

/// A relayed run's inputs, packed or repeated (not both).
Status relayed_run_inputs(const v1::RelayedInputs& run, std::vector<game::PlayerInput>& out);

}  // namespace rwd::proto
