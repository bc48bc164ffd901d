// SPDX-License-Identifier: MIT
#pragma once
// Inputs packed against a reference, for the datagrams that carry many of
// them (final ticks, relayed runs). Consecutive inputs of a player, and a
// player's input on consecutive ticks, are mostly equal, so each input is
// sent as its XOR with a reference input: a mask naming the bytes that
// differ (bit i for byte i of the input, as a base-128 varint of up to 5
// bytes), then those bytes. An unchanged input costs one byte; a change in
// the first 7 bytes costs one byte plus the bytes changed (a stick that
// moved: three).
//
// A packed list is a count byte (0 to 64) followed by the inputs; the
// references are the caller's (the neutral input, the previous input of a
// run, or the same players on the previous tick).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"

namespace rwd::proto {

/// Largest number of inputs in one packed list (the player slot limit).
inline constexpr size_t kMaxPackedInputs = 64;

/// Appends `values` packed against `references` (same size, or empty for
/// the neutral input) to `out`. At most kMaxPackedInputs values.
void pack_inputs(std::span<const rwd::PlayerInput> values,
                 std::span<const rwd::PlayerInput> references, std::string& out);

/// Appends a run of one player's inputs, each packed against the one
/// before it (the first against the neutral input).
void pack_run(std::span<const rwd::PlayerInput> run, std::string& out);

/// Reads a packed list against `references` (empty: the neutral input;
/// else as many as the list holds) into `out` (replaced). kCorrupt for a
/// truncated list, trailing bytes, a count above kMaxPackedInputs, a
/// reference count that does not match, or a mask longer than the input.
Status unpack_inputs(std::string_view bytes, std::span<const rwd::PlayerInput> references,
                     std::vector<rwd::PlayerInput>& out);

/// Checks that `bytes` is a well-formed packed list (count, masks and
/// bytes agree, nothing trailing) without its references: the values are
/// known only to a receiver holding them.
Status check_packed_inputs(std::string_view bytes);

/// Reads a run packed by pack_run.
Status unpack_run(std::string_view bytes, std::vector<rwd::PlayerInput>& out);

}  // namespace rwd::proto
