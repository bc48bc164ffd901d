// SPDX-License-Identifier: MIT
// The box: half extents along the body's axes.
#include <cmath>

#include "d3/shape_ops.h"
#include "d3/slab_interval.h"
#include "d3/state_rules.h"

namespace rwd::sim::d3 {
namespace {

Status check(const Shape& s, const GeometryStore& /*store*/) {
  if (!in_shape_size_range(s.half_extents.x) || !in_shape_size_range(s.half_extents.y) ||
      !in_shape_size_range(s.half_extents.z)) {
    return Status::Error(ErrorCode::kInvalidArgument, "box half extents must be in (0, 1000] m");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& /*store*/) {
  s.radius = 0.0f;
  s.half_height = 0.0f;
  s.geometry = 0;
}

float extent(const Shape& s, const GeometryStore& /*store*/) {
  return length(s.half_extents);
}

float volume(const Shape& s, const GeometryStore& /*store*/) {
  const Vec3 h = s.half_extents;
  return 8.0f * h.x * h.y * h.z;
}

Vec3 inertia(const Shape& s, const GeometryStore& /*store*/, float mass) {
  const Vec3 h = s.half_extents;
  // Solid box: I_x = m/3 (hy^2 + hz^2) with half extents.
  const float k = mass / 3.0f;
  return {k * (h.y * h.y + h.z * h.z), k * (h.x * h.x + h.z * h.z), k * (h.x * h.x + h.y * h.y)};
}

Vec3 half_bounds(const Shape& s, const Mat3& axes) {
  const Vec3 h = s.half_extents;
  // Extent along world axis i = sum_k |R_ik| h_k.
  return abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
}

// Slabs in the box's frame.
bool raycast(const Shape& s, const GeometryStore& /*store*/, Vec3 center, Quat rotation,
             Vec3 origin, Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const Vec3 half = s.half_extents;
  Vec3 o = inv_rotate(rotation, origin - center);
  Vec3 d = inv_rotate(rotation, dir);
  float t_enter = -1.0f;  // below any real entry: origin inside until proven outside
  float t_exit = max_distance;
  int enter_axis = -1;
  float enter_sign = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float oi = component(o, i);
    float di = component(d, i);
    float hi = component(half, i);
    if (std::fabs(di) < 1e-12f) {
      if (oi < -hi || oi > hi) return false;
      continue;
    }
    float inv = 1.0f / di;
    float t1 = (-hi - oi) * inv;
    float t2 = (hi - oi) * inv;
    float sign = -1.0f;  // entering through the -axis face
    if (t1 > t2) {
      float tmp = t1;
      t1 = t2;
      t2 = tmp;
      sign = 1.0f;
    }
    if (t1 > t_enter) {
      t_enter = t1;
      enter_axis = i;
      enter_sign = sign;
    }
    if (t2 < t_exit) t_exit = t2;
    if (t_enter > t_exit) return false;
  }
  if (t_exit < 0.0f) return false;
  if (t_enter <= 0.0f) {  // origin inside the box
    t = 0.0f;
    normal = -dir;
    return true;
  }
  t = t_enter;
  float n[3] = {0.0f, 0.0f, 0.0f};
  n[enter_axis] = enter_sign;
  normal = rotate(rotation, Vec3{n[0], n[1], n[2]});
  return true;
}

// The eight corners, vertex i at +-h with axis k positive when bit k of i
// is set.
ConvexProxy proxy(const Shape& s, const GeometryStore& /*store*/, ProxyPoints& storage) {
  const Vec3 h = s.half_extents;
  for (uint32_t i = 0; i < 8; ++i) {
    storage.points[i] = {(i & 1u) != 0 ? h.x : -h.x, (i & 2u) != 0 ? h.y : -h.y,
                         (i & 4u) != 0 ? h.z : -h.z};
  }
  ConvexProxy p;
  p.points = storage.points;
  p.count = 8;
  return p;
}

// A box swept at: first the segment of the swept shape's centre against the
// box grown by the radius of a ball around the swept shape (in the box's
// frame, slab by slab), which holds every point the shape can touch from;
// most candidates a query's tree gives miss it, and skip the GJK sweep.
ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                      const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  float reach = 0.0f;
  for (uint32_t i = 0; i < swept.count; ++i) {
    const float d = length_squared(swept.points[i]);
    if (d > reach) reach = d;
  }
  // Plus the gap a sweep counts as touching (gjk.h), with room to spare.
  reach = std::sqrt(reach) + swept.radius + 0.01f;
  const Vec3 o = gjk_detail::mul_transpose(axes, swept.position - position);
  const Vec3 d = gjk_detail::mul_transpose(axes, translation);
  float t_lo = 0.0f;
  float t_hi = max_fraction;
  for (int i = 0; i < 3; ++i) {
    const float oi = component(o, i);
    const float di = component(d, i);
    const float hi = component(s.half_extents, i) + reach;
    if (di == 0.0f) {
      if (oi < -hi || oi > hi) return {};
      continue;
    }
    float t0 = 0.0f;
    float t1 = 0.0f;
    slab_interval(oi, di, hi, t0, t1);
    if (t0 > t_lo) t_lo = t0;
    if (t1 < t_hi) t_hi = t1;
    if (t_lo > t_hi) return {};
  }
  return sweep_convex(s, store, position, axes, swept, translation, max_fraction);
}

}  // namespace

extern const ShapeOps kBoxOps{"box",   true,        check,   canonical, extent, volume,
                              inertia, half_bounds, raycast, proxy,     sweep,  nullptr};

}  // namespace rwd::sim::d3
