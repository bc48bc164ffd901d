// SPDX-License-Identifier: MIT
#pragma once
// Rewrites one recorded input and re-frames the file with correct hashes: a
// consistent forgery that only re-simulation can catch. Used by tests and by
// `rewind-replay tamper` to prove the verifier does its job.
#include <cstdint>
#include <optional>
#include <string>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"

namespace rwd::replay {

/// The fields of one input to replace; unset fields keep their value.
struct InputEdit {
  Tick tick = 0;
  uint32_t player = 0;
  std::optional<int16_t> axis_x;
  std::optional<int16_t> axis_y;
  std::optional<uint32_t> buttons;
};

/// Copies the replay at `in_path` to `out_path` with `edit` applied and
/// returns the input as it was before the edit. The input must read cleanly
/// to its end and contain edit.tick; `out_path` is refused if it exists
/// non-empty unless `overwrite`, and removed again on failure.
Result<rwd::PlayerInput> rewrite_replay_input(const std::string& in_path,
                                              const std::string& out_path, const InputEdit& edit,
                                              bool overwrite);

}  // namespace rwd::replay
