// SPDX-License-Identifier: MIT
#pragma once
// Which bodies a query may report (QueryFilter), shared by every query.
#include "d3/body_storage.h"
#include "rewind/sim/query.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Whether a query with `filter` may report body i (simulated, on a layer
/// the filter takes, of a kind it takes, not the body it ignores, a sensor
/// only when the filter asks for sensors).
inline bool query_accepts(const WorldState& state, const QueryFilter& filter, uint32_t i) {
  const BodyInfo& info = state.infos[i];
  if (!is_simulated(info) || (info.layer & filter.layer_mask) == 0) return false;
  if (info.sensor != 0 && !filter.include_sensors) return false;
  if (filter.ignore.index == i && filter.ignore.generation == info.generation &&
      !filter.ignore.is_null()) {
    return false;
  }
  switch (info.kind) {
    case BodyKind::kStatic:
      return filter.include_static;
    case BodyKind::kKinematic:
      return filter.include_kinematic;
    case BodyKind::kDynamic:
      return filter.include_dynamic;
  }
  return false;
}

}  // namespace rwd::sim::d3
