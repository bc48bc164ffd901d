// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/body.h"

namespace rwd::sim {

enum class ContactEventType : uint8_t {
  kEnter = 0,  ///< the pair started touching this tick
  kStay = 1,   ///< the pair touched last tick and still does
  kExit = 2,   ///< the pair touched last tick and no longer does (or a body was destroyed)
};

/// One contact event from the last step. `a.index < b.index` always; events
/// are ordered by (a.index, b.index, type) so every machine sees the same
/// list.
struct ContactEvent {
  ContactEventType type = ContactEventType::kEnter;
  BodyId a;
  BodyId b;
  bool sensor = false;  ///< at least one of the bodies is a sensor
};

}  // namespace rwd::sim
