// SPDX-License-Identifier: MIT
#pragma once
// How a game declares its input (Game::input_spec()): how many bytes it
// uses, what each field means and which values are allowed, and how to
// predict a player's next input when it has not arrived. The server refuses
// inputs the spec does not allow before they reach the rules; the bots,
// rewind-replay and the viewer read and write inputs through the fields.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"

namespace rwd {

/// The integer type of one field, stored little-endian.
enum class InputFieldType : uint8_t { kI8, kU8, kI16, kU16, kI32, kU32 };

/// Bytes a field of `type` takes (1, 2 or 4).
size_t input_field_bytes(InputFieldType type);

/// One named field of a game's input.
struct InputField {
  std::string_view name;  ///< letters, digits and '_', e.g. "throttle"
  InputFieldType type = InputFieldType::kU8;
  uint8_t offset = 0;  ///< byte offset in the input (offsetof in the game's struct)
  int64_t min = 0;     ///< smallest value the server accepts (inclusive)
  int64_t max = 0;     ///< largest value the server accepts (inclusive)
};

/// A player's next input, guessed from the newest one the server or client
/// has, while the real one is on its way. Must be a pure function, and
/// return an input the spec allows (a step refuses any other).
using InputPredictor = PlayerInput (*)(const PlayerInput& newest);

/// What a game's input is. The spec and what it points to must outlive
/// every Simulation of the game (static storage in practice).
struct InputSpec {
  std::string_view name;  ///< names the layout in tools' output, e.g. "stick"
  uint8_t size = 0;       ///< bytes the game uses, [1, kInputCapacity]; the rest stay 0
  /// The fields, in any order; they must lie within `size` and not overlap.
  /// Empty: the bytes are opaque to tools, and any value is accepted.
  std::span<const InputField> fields;
  /// nullptr: repeat the newest input (what most games want).
  InputPredictor predict = nullptr;
};

/// kInvalidArgument naming the problem when `spec` is malformed: a size
/// outside [1, kInputCapacity], a field past the size, overlapping or
/// unnamed or duplicate fields, a range empty or beyond the field's type.
Status check_input_spec(const InputSpec& spec);

/// kInvalidArgument naming the field when `input` sets a byte past the
/// spec's size or a field outside its range.
Status check_input(const InputSpec& spec, const PlayerInput& input);

/// The spec's prediction from the newest input (the newest itself when the
/// spec has no predictor).
PlayerInput predict_input(const InputSpec& spec, const PlayerInput& newest);

/// The field of `spec` named `name`, or nullptr.
const InputField* find_input_field(const InputSpec& spec, std::string_view name);

/// A field's value in `input`.
int64_t read_input_field(const PlayerInput& input, const InputField& field);
/// Stores `value`, truncated to the field's bytes, into `input`.
void write_input_field(PlayerInput& input, const InputField& field, int64_t value);

/// "axis_x=120 axis_y=-40 buttons=1" for a spec with fields; the used bytes
/// in hex ("0a00ff...") for one without.
std::string describe_input(const InputSpec& spec, const PlayerInput& input);

/// An input whose every field is drawn uniformly from its range by
/// `bits` (hashed per field), for bots that know nothing of the game; an
/// opaque spec gets random bytes. A pure function of its arguments.
PlayerInput random_input(const InputSpec& spec, uint64_t bits);

}  // namespace rwd
