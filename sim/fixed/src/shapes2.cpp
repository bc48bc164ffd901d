// SPDX-License-Identifier: MIT
// Validating constructors of Aabb2 and Circle.
#include <string>

#include "rewind/fixed/aabb2.h"
#include "rewind/fixed/circle.h"

namespace rwd::fixed {
namespace {

std::string raw_pair(Vec2 v) {
  return "(" + std::to_string(v.x.raw()) + ", " + std::to_string(v.y.raw()) + ")";
}

}  // namespace

Result<Aabb2> Aabb2::make(Vec2 lower, Vec2 upper) {
  if (upper.x < lower.x || upper.y < lower.y) {
    return Status::Error(ErrorCode::kInvalidArgument, "aabb lower corner raw " + raw_pair(lower) +
                                                          " exceeds upper corner raw " +
                                                          raw_pair(upper));
  }
  return Aabb2{lower, upper};
}

Result<Aabb2> Aabb2::from_center(Vec2 center, Vec2 half_extents) {
  if (half_extents.x.raw() < 0 || half_extents.y.raw() < 0) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "aabb half extents must not be negative, got raw " + raw_pair(half_extents));
  }
  return Aabb2{center - half_extents, center + half_extents};
}

Result<Circle> Circle::make(Vec2 center, Fx radius) {
  if (radius.raw() < 0) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "circle radius must not be negative, got raw " + std::to_string(radius.raw()));
  }
  return Circle{center, radius};
}

}  // namespace rwd::fixed
