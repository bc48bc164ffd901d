// SPDX-License-Identifier: MIT
#pragma once
// The one conversion between the game's PlayerInput and its wire form
// (rwd.v1.Input), shared by the server, the client SDK and replay files.
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/v1/common.pb.h"

namespace rwd::proto {

/// Wire form of one input.
v1::Input to_wire(const rwd::PlayerInput& input);

/// Reads one input; kCorrupt when an axis does not fit PlayerInput's 16 bits.
/// The tighter game range ([-1000, 1000]) is enforced where inputs enter:
/// decode_envelope for datagrams, PlayerInput users for everything else.
Result<rwd::PlayerInput> from_wire(const v1::Input& input);

}  // namespace rwd::proto
