// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/body2d.h"

namespace rwd::sim2d {

enum class ContactEventType2D : uint8_t {
  kEnter = 0,  ///< the pair started touching this step
  kStay = 1,   ///< the pair touched last step and still does (while either body is awake)
  kExit = 2,   ///< the pair touched last step and no longer does (or a body went away)
};

/// One contact event of the last step. a.index < b.index; the list is
/// ordered by (a.index, b.index), the same on every machine.
///
/// Two solid bodies touch while their surfaces are closer than the world's
/// linear_slop; a sensor touches while it overlaps. Enter and stay events
/// carry the deepest point (midway between the surfaces), the normal from a
/// to b and the depth (>= 0; 0 when only touching); exit events carry zeros.
struct ContactEvent2D {
  ContactEventType2D type = ContactEventType2D::kEnter;
  BodyId2D a;
  BodyId2D b;
  bool sensor = false;   ///< at least one of the two is a sensor
  bool trigger = false;  ///< at least one of the two is a trigger
  fixed::Vec2 point;
  fixed::Vec2 normal;
  fixed::Fx depth;
};

}  // namespace rwd::sim2d
