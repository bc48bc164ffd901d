// SPDX-License-Identifier: MIT
#include "rewind/sim/rotation.h"

#include <cmath>

#include "rewind/core/det_math.h"

namespace rwd::sim {
namespace {

constexpr Quat kIdentity{};

// The quaternion of the rotation matrix with columns x, y, z (orthonormal,
// right-handed), by the largest of its four candidates for stability.
Quat from_columns(Vec3 x, Vec3 y, Vec3 z) {
  const float trace = x.x + y.y + z.z;
  Quat q;
  if (trace > 0.0f) {
    const float s = std::sqrt(trace + 1.0f) * 2.0f;
    q = {(y.z - z.y) / s, (z.x - x.z) / s, (x.y - y.x) / s, 0.25f * s};
  } else if (x.x > y.y && x.x > z.z) {
    const float s = std::sqrt(1.0f + x.x - y.y - z.z) * 2.0f;
    q = {0.25f * s, (y.x + x.y) / s, (z.x + x.z) / s, (y.z - z.y) / s};
  } else if (y.y > z.z) {
    const float s = std::sqrt(1.0f + y.y - x.x - z.z) * 2.0f;
    q = {(y.x + x.y) / s, 0.25f * s, (z.y + y.z) / s, (z.x - x.z) / s};
  } else {
    const float s = std::sqrt(1.0f + z.z - x.x - y.y) * 2.0f;
    q = {(z.x + x.z) / s, (z.y + y.z) / s, 0.25f * s, (x.y - y.x) / s};
  }
  return normalize(q);
}

}  // namespace

Quat axis_angle(Vec3 axis, float angle) {
  const Vec3 n = normalize_or_zero(axis);
  if (!is_finite(n) || n == Vec3{} || !is_finite(angle)) return kIdentity;
  const float s = det_sin(0.5f * angle);
  return normalize(Quat{n.x * s, n.y * s, n.z * s, det_cos(0.5f * angle)});
}

Quat look_at(Vec3 forward, Vec3 up) {
  const Vec3 z = normalize_or_zero(forward);
  if (!is_finite(z) || z == Vec3{}) return kIdentity;
  Vec3 x = is_finite(up) ? normalize_or_zero(cross(up, z)) : Vec3{};
  if (x == Vec3{}) {
    // up is zero or along forward: any perpendicular does, chosen the same
    // way everywhere.
    const Vec3 fallback = std::fabs(z.y) < 0.9f ? Vec3{0.0f, 1.0f, 0.0f} : Vec3{1.0f, 0.0f, 0.0f};
    x = normalize_or_zero(cross(fallback, z));
  }
  const Vec3 y = cross(z, x);
  return from_columns(x, y, z);
}

}  // namespace rwd::sim
