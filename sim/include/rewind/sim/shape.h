// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/math.h"

namespace rwd::sim {

enum class ShapeType : uint8_t {
  kSphere = 0,
  kBox = 1,
};

/// A collision shape centred on its body's origin. Plain data, trivially
/// copyable, part of world state.
struct Shape {
  ShapeType type = ShapeType::kBox;
  float radius = 0.0f;  ///< sphere radius in metres, > 0
  Vec3 half_extents;    ///< box half sizes in metres, each > 0

  static Shape make_sphere(float radius_m) {
    Shape s;
    s.type = ShapeType::kSphere;
    s.radius = radius_m;
    return s;
  }
  static Shape make_box(Vec3 half_extents_m) {
    Shape s;
    s.type = ShapeType::kBox;
    s.half_extents = half_extents_m;
    return s;
  }
};

}  // namespace rwd::sim
