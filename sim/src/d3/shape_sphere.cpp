// SPDX-License-Identifier: MIT
// The sphere: a radius about the body's origin.
#include <cmath>

#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

Status check(const Shape& s, const GeometryStore& /*store*/) {
  if (!in_shape_size_range(s.radius)) {
    return Status::Error(ErrorCode::kInvalidArgument, "sphere radius must be in (0, 1000] m");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& /*store*/) {
  s.half_extents = {};
  s.half_height = 0.0f;
  s.geometry = 0;
}

float extent(const Shape& s, const GeometryStore& /*store*/) {
  return s.radius;
}

float volume(const Shape& s, const GeometryStore& /*store*/) {
  const float r = s.radius;
  return (4.0f / 3.0f) * kPi * r * r * r;
}

Vec3 inertia(const Shape& s, const GeometryStore& /*store*/, float mass) {
  const float r = s.radius;
  const float i = 0.4f * mass * r * r;  // solid sphere: 2/5 m r^2
  return {i, i, i};
}

Vec3 half_bounds(const Shape& s, const Mat3&) {
  return {s.radius, s.radius, s.radius};
}

bool raycast(const Shape& s, const GeometryStore& /*store*/, Vec3 center, Quat, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  return ray_sphere(origin, dir, max_distance, center, s.radius, t, normal);
}

ConvexProxy proxy(const Shape& s, const GeometryStore& /*store*/, ProxyPoints& storage) {
  storage.points[0] = {};
  ConvexProxy p;
  p.points = storage.points;
  p.count = 1;
  p.radius = s.radius;
  return p;
}

}  // namespace

bool ray_sphere(Vec3 origin, Vec3 dir, float max_distance, Vec3 center, float radius, float& t,
                Vec3& normal) {
  Vec3 m = origin - center;
  float b = dot(m, dir);
  float c = dot(m, m) - radius * radius;
  if (c <= 0.0f) {  // inside
    t = 0.0f;
    normal = -dir;
    return true;
  }
  if (b > 0.0f) return false;  // outside and pointing away
  float disc = b * b - c;
  if (disc < 0.0f) return false;
  t = -b - std::sqrt(disc);
  if (t < 0.0f) t = 0.0f;
  if (t > max_distance) return false;
  normal = normalize_or_zero(origin + dir * t - center);
  return true;
}

extern const ShapeOps kSphereOps{"sphere", true,        check,   canonical, extent,       volume,
                                 inertia,  half_bounds, raycast, proxy,     sweep_convex, nullptr};

}  // namespace rwd::sim::d3
