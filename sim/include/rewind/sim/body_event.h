// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/body.h"
#include "rewind/sim/math.h"

namespace rwd::sim {

enum class BodyEventType : uint8_t {
  /// The body's centre left WorldConfig's bounds during the step. The body
  /// is now disabled: clamped onto the bounds where it crossed, velocities
  /// zero, out of the broadphase, contacts and queries. The game decides
  /// what happens next: move it back (set_transform) and set_enabled(true),
  /// or destroy_body(). Until then it stays frozen and costs nothing.
  kLeftBounds = 0,
};

/// One body event from the last step, ordered by body index, so every
/// machine sees the same list.
struct BodyEvent {
  BodyEventType type = BodyEventType::kLeftBounds;
  BodyId body;
  Vec3 position;  ///< metres: where the body now stands (on the bounds)
};

}  // namespace rwd::sim
