// SPDX-License-Identifier: MIT
#pragma once
// Rewrites one recorded input and re-frames the file with correct hashes: a
// consistent forgery that only re-simulation can catch. Used by tests and by
// `rewind-replay tamper` to prove the verifier does its job.
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"

namespace rwd::replay {

/// One field of the game's input (a name from its InputSpec) and its new value.
struct InputFieldEdit {
  std::string name;
  int64_t value = 0;
};

/// The fields of one input to replace; the others keep their value.
struct InputEdit {
  Tick tick = 0;
  uint32_t player = 0;
  std::vector<InputFieldEdit> fields;  ///< at least one
};

/// The input before and after the edit, and both as describe_input() writes them.
struct InputRewrite {
  rwd::PlayerInput before;
  rwd::PlayerInput after;
  std::string before_text;
  std::string after_text;
};

/// Copies the replay at `in_path` to `out_path` with `edit` applied. `spec`
/// is the replay's game's input (Game::input_spec()): each field must be
/// one of its fields and the value within the field's range
/// (kInvalidArgument names the fields there are). The input must read cleanly to its end and
/// contain edit.tick; `out_path` is refused if it exists non-empty unless `overwrite`, and removed
/// again on failure.
Result<InputRewrite> rewrite_replay_input(const std::string& in_path, const std::string& out_path,
                                          const InputEdit& edit, const InputSpec& spec,
                                          bool overwrite);

}  // namespace rwd::replay
