// SPDX-License-Identifier: MIT
#pragma once
#include <span>

#include "d3/compound.h"
#include "rewind/core/status.h"
#include "rewind/sim/geometry.h"

namespace rwd::sim::d3 {

/// Validates the children (1 to kCompoundMaxChildren spheres, boxes,
/// capsules or hulls of `store`, sizes in range, finite poses within 1000 m)
/// and builds the compound: the children's poses in its mass frame, its
/// volume, centre of mass and principal inertia. kInvalidArgument naming
/// the child otherwise.
Result<Compound> build_compound(std::span<const CompoundChild> children,
                                const GeometryStore& store);

}  // namespace rwd::sim::d3
