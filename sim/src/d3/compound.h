// SPDX-License-Identifier: MIT
#pragma once
// A compound: a rigid group of convex children (spheres, boxes, capsules,
// hulls) registered once in the geometry store (compound_builder.cpp).
// Like a hull it lives in its mass frame: the origin is the centre of mass
// of the whole (uniform density, mass by child volume), the axes its
// principal axes (inertia by the parallel-axis theorem), so the solver
// sees a diagonal inertia and the body turns about its true centre of
// mass; `frame` says where that sits in the frame the children were placed
// in, which is what the game sees.
#include <cstdint>
#include <vector>

#include "d3/hull.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim::d3 {

inline constexpr uint32_t kCompoundMaxChildren = 16;

/// One child, in the compound's mass frame: its own mass frame's pose.
struct CompoundPart {
  Shape shape;  ///< canonical (a hull child's sizes filled from the store)
  Vec3 position;
  Quat rotation;
};

struct Compound {
  std::vector<CompoundPart> parts;
  HullFrame frame;  ///< the mass frame in the authored frame
  float volume = 0.0f;
  Vec3 unit_inertia;    ///< principal moments per kilogram, m^2
  float extent = 0.0f;  ///< largest distance from the centre of mass to the surface
  Vec3 half_size;       ///< half size of the mass-frame bounds about the origin
};

}  // namespace rwd::sim::d3
