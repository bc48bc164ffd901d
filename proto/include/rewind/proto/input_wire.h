// SPDX-License-Identifier: MIT
#pragma once
// The one conversion between a PlayerInput and its wire form
// (rwd.v1.Input), shared by the server, the client SDK and replay files.
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/v1/common.pb.h"

namespace rwd::proto {

/// Wire form of one input: its bytes, trailing zeros left out.
v1::Input to_wire(const rwd::PlayerInput& input);

/// Reads one input: its bytes, or the stick fields of replay formats 1 and
/// 2 as a StickInput. kCorrupt for more than kInputCapacity bytes, bytes
/// ending in a zero (not the form to_wire() writes), bytes and stick fields
/// together, or an axis beyond 16 bits. What the game
/// accepts (its InputSpec) is checked where inputs reach a game: the
/// rollback session, the replay verifier.
Result<rwd::PlayerInput> from_wire(const v1::Input& input);

}  // namespace rwd::proto
