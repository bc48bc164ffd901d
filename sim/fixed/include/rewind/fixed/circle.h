// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/core/status.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"

namespace rwd::fixed {

/// A closed disc. Invariant: radius >= 0 (make() refuses a negative one; a
/// zero radius is a point).
struct Circle {
  Vec2 center;
  Fx radius;

  /// The circle, or kInvalidArgument for a negative radius.
  static Result<Circle> make(Vec2 center, Fx radius);

  friend constexpr bool operator==(Circle a, Circle b) = default;
};

}  // namespace rwd::fixed
