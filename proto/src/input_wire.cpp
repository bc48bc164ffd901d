// SPDX-License-Identifier: MIT
#include "rewind/proto/input_wire.h"

#include <limits>
#include <string>

#include "rewind/core/stick_input.h"

namespace rwd::proto {

v1::Input to_wire(const rwd::PlayerInput& input) {
  size_t used = input.bytes.size();
  while (used > 0 && input.bytes[used - 1] == 0) --used;
  v1::Input out;
  if (used > 0) out.set_data(input.bytes.data(), used);
  return out;
}

Result<rwd::PlayerInput> from_wire(const v1::Input& input) {
  const bool legacy = input.axis_x() != 0 || input.axis_y() != 0 || input.buttons() != 0;
  if (!legacy) {
    if (input.data().size() > rwd::kInputCapacity) {
      return Status::Error(ErrorCode::kCorrupt,
                           "an input of " + std::to_string(input.data().size()) +
                               " bytes, more than " + std::to_string(rwd::kInputCapacity));
    }
    if (!input.data().empty() && input.data().back() == '\0') {
      // One form per input: to_wire() leaves trailing zeros out.
      return Status::Error(ErrorCode::kCorrupt, "an input whose bytes end in a zero");
    }
    rwd::PlayerInput out;
    for (size_t i = 0; i < input.data().size(); ++i) {
      out.bytes[i] = static_cast<uint8_t>(input.data()[i]);
    }
    return out;
  }
  if (!input.data().empty()) {
    return Status::Error(ErrorCode::kCorrupt, "an input with both bytes and stick fields");
  }
  constexpr int32_t lo = std::numeric_limits<int16_t>::min();
  constexpr int32_t hi = std::numeric_limits<int16_t>::max();
  if (input.axis_x() < lo || input.axis_x() > hi || input.axis_y() < lo || input.axis_y() > hi) {
    return Status::Error(ErrorCode::kCorrupt, "input axis (" + std::to_string(input.axis_x()) +
                                                  ", " + std::to_string(input.axis_y()) +
                                                  ") does not fit 16 bits");
  }
  rwd::StickInput stick;
  stick.axis_x = static_cast<int16_t>(input.axis_x());
  stick.axis_y = static_cast<int16_t>(input.axis_y());
  stick.buttons = input.buttons();
  return rwd::PlayerInput::of(stick);
}

}  // namespace rwd::proto
