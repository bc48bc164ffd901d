// SPDX-License-Identifier: MIT
#include "rewind/proto/input_wire.h"

#include <limits>
#include <string>

namespace rwd::proto {

v1::Input to_wire(const rwd::PlayerInput& input) {
  v1::Input out;
  out.set_axis_x(input.axis_x);
  out.set_axis_y(input.axis_y);
  out.set_buttons(input.buttons);
  return out;
}

Result<rwd::PlayerInput> from_wire(const v1::Input& input) {
  constexpr int32_t lo = std::numeric_limits<int16_t>::min();
  constexpr int32_t hi = std::numeric_limits<int16_t>::max();
  if (input.axis_x() < lo || input.axis_x() > hi || input.axis_y() < lo || input.axis_y() > hi) {
    return Status::Error(ErrorCode::kCorrupt, "input axis (" + std::to_string(input.axis_x()) +
                                                  ", " + std::to_string(input.axis_y()) +
                                                  ") does not fit 16 bits");
  }
  rwd::PlayerInput out;
  out.axis_x = static_cast<int16_t>(input.axis_x());
  out.axis_y = static_cast<int16_t>(input.axis_y());
  out.buttons = input.buttons();
  return out;
}

}  // namespace rwd::proto
