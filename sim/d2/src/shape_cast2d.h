// SPDX-License-Identifier: MIT
#pragma once
// A convex core moved in a straight line through the world until it comes
// within `target` of a body: World2D::shape_cast and the character
// controller's sweeps.
#include <cstdint>

#include "distance2d.h"
#include "rewind/sim2d/query2d.h"
#include "rewind/sim2d/world2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// How close (m) the advancement must come to `target` to call it a hit.
inline constexpr W kCastTolerance = W{1} << 12;  // 2^-20 m

struct CastResult2 {
  uint32_t index = 0;  ///< body slot
  W fraction = 0;      ///< of the translation, [0, 1]
  V2 point;            ///< on the body's surface
  V2 normal;           ///< unit, out of the body toward the moving core
};

/// The first body (filter rules as the queries; ties by lower index) that
/// `core` (world frame, at fraction 0) comes within `target` m (>= 0) of
/// while moving by `translation`. A body already within target counts only
/// when the move heads into it (by more than about 0.2 degrees).
bool cast_core(const World2D& world, const QueryFilter2D& filter, const WPoly& core, V2 translation,
               W target, CastResult2& out);

}  // namespace rwd::sim2d::detail
