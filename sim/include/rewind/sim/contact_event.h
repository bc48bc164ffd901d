// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/body.h"
#include "rewind/sim/event_mask.h"

namespace rwd::sim {

enum class ContactEventType : uint8_t {
  kEnter = 0,  ///< the pair started touching this tick
  /// the pair touched last tick and still does, and one of its bodies is
  /// awake: a resting pair (both asleep, or asleep on a static body)
  /// reports no stay until one of them wakes
  kStay = 1,
  kExit = 2,  ///< the pair touched last tick and no longer does (or a body was destroyed)
};

/// One contact event from the last step. `a.index < b.index` always; events
/// are ordered by (a.index, b.index, type) so every machine sees the same
/// list.
///
/// Enter and stay events of solid pairs carry where the bodies touch, as of
/// the contact's manifold this tick: the deepest point, the normal, the
/// depth and the impulse the solver pushed them apart with. Sensor events
/// carry the point, normal and depth of the overlap (no impulse); exit
/// events carry none of these (zeros).
struct ContactEvent {
  ContactEventType type = ContactEventType::kEnter;
  BodyId a;
  BodyId b;
  bool sensor = false;  ///< at least one of the bodies is a sensor
  Vec3 point;           ///< world, midway between the surfaces at the deepest point
  Vec3 normal;          ///< unit, from a toward b
  float depth = 0.0f;   ///< metres the shapes overlap there (0 when only touching)
  /// N*s: the normal impulse the solver pushed the pair apart with over the
  /// tick (its substeps' impulses summed).
  float impulse = 0.0f;
};

/// The EventMask bit of an event of `type`, between solid bodies or with a
/// sensor.
constexpr EventMask event_mask_bit(ContactEventType type, bool sensor) {
  const auto bit = static_cast<EventMask>(1u << static_cast<uint8_t>(type));
  return sensor ? static_cast<EventMask>(bit << 3) : bit;
}

}  // namespace rwd::sim
