// SPDX-License-Identifier: MIT
#pragma once
// Which bodies a query may find (QueryFilter2D's rules), shared by every
// query and the character controller.
#include <cstdint>

#include "rewind/sim2d/query2d.h"
#include "rewind/sim2d/world2d_state.h"

namespace rwd::sim2d::detail {

inline bool passes_filter(const BodyRecord2D& body, uint32_t index, const QueryFilter2D& filter) {
  if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled)) return false;
  if ((body.layer & filter.layer_mask) == 0) return false;
  if ((body.flags & kBodySensor) && !filter.include_sensors) return false;
  if ((body.flags & kBodyTrigger) && !filter.include_triggers) return false;
  switch (body.kind) {
    case BodyKind2D::kStatic:
      if (!filter.include_static) return false;
      break;
    case BodyKind2D::kKinematic:
      if (!filter.include_kinematic) return false;
      break;
    case BodyKind2D::kDynamic:
      if (!filter.include_dynamic) return false;
      break;
  }
  return filter.ignore.is_null() || filter.ignore.index != index ||
         filter.ignore.generation != body.generation;
}

}  // namespace rwd::sim2d::detail
