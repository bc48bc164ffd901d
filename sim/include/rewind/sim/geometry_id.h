// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd::sim {

/// Handle of a piece of geometry registered in a GeometryStore
/// (geometry.h): its index there, in registration order, so two stores that
/// registered the same geometry in the same order agree on every id.
struct GeometryId {
  uint32_t value = 0;
};

}  // namespace rwd::sim
