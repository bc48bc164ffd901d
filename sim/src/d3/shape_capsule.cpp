// SPDX-License-Identifier: MIT
// The capsule: the segment from -half_height to +half_height along the
// body's local y axis, swept by a sphere of `radius` (a cylinder with two
// hemispherical caps).
#include <cmath>

#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

Status check(const Shape& s, const GeometryStore& /*store*/) {
  if (!in_shape_size_range(s.radius) || !in_shape_size_range(s.half_height)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "capsule radius and half height must be in (0, 1000] m");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& /*store*/) {
  s.half_extents = {};
  s.geometry = 0;
}

float extent(const Shape& s, const GeometryStore& /*store*/) {
  return s.half_height + s.radius;
}

float cylinder_volume(const Shape& s) {
  return kPi * s.radius * s.radius * (2.0f * s.half_height);
}

float caps_volume(const Shape& s) {
  const float r = s.radius;
  return (4.0f / 3.0f) * kPi * r * r * r;
}

float volume(const Shape& s, const GeometryStore& /*store*/) {
  return cylinder_volume(s) + caps_volume(s);
}

// The cylinder (length 2h) and the two hemispheres share the mass by
// volume. About the long axis: m_c r^2 / 2 + 2/5 m_s r^2. Across it: the
// cylinder's m_c (r^2 / 4 + h^2 / 3), and each hemisphere's 2/5 (m_s / 2)
// r^2 about its flat face moved out to the centre: its own centre of mass
// sits 3r/8 from that face, so the parallel-axis theorem adds
// (m_s / 2)(h^2 + 3 h r / 4) per cap.
Vec3 inertia(const Shape& s, const GeometryStore& /*store*/, float mass) {
  const float r = s.radius;
  const float h = s.half_height;
  const float v_c = cylinder_volume(s);
  const float v_s = caps_volume(s);
  const float m_c = mass * (v_c / (v_c + v_s));
  const float m_s = mass - m_c;
  const float axial = m_c * r * r * 0.5f + m_s * r * r * 0.4f;
  const float across =
      m_c * (r * r * 0.25f + h * h / 3.0f) + m_s * (r * r * 0.4f + h * h + 0.75f * h * r);
  return {across, axial, across};
}

Vec3 half_bounds(const Shape& s, const Mat3& axes) {
  // The segment's half along each world axis, plus the radius.
  return abs(axes.c1) * s.half_height + Vec3{s.radius, s.radius, s.radius};
}

// In the capsule's frame: the side (an infinite cylinder about y, hits
// with |y| <= h) and the two cap spheres; the nearest hit wins.
bool raycast(const Shape& s, const GeometryStore& /*store*/, Vec3 center, Quat rotation,
             Vec3 origin, Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const float r = s.radius;
  const float h = s.half_height;
  const Vec3 o = inv_rotate(rotation, origin - center);
  const Vec3 d = inv_rotate(rotation, dir);
  // Inside: the origin within r of the segment.
  const float clamped_y = o.y < -h ? -h : (o.y > h ? h : o.y);
  const Vec3 from_axis = o - Vec3{0.0f, clamped_y, 0.0f};
  if (length_squared(from_axis) <= r * r) {
    t = 0.0f;
    normal = -dir;
    return true;
  }
  bool hit = false;
  float best = max_distance;
  Vec3 best_normal;
  // The side: |(o + t d) projected off y| = r.
  const float a = d.x * d.x + d.z * d.z;
  if (a > 1e-12f) {
    const float b = o.x * d.x + o.z * d.z;
    const float c = o.x * o.x + o.z * o.z - r * r;
    const float disc = b * b - a * c;
    if (disc >= 0.0f) {
      const float side_t = (-b - std::sqrt(disc)) / a;
      const float y = o.y + side_t * d.y;
      if (side_t >= 0.0f && side_t <= best && y >= -h && y <= h) {
        hit = true;
        best = side_t;
        best_normal = normalize_or_zero(Vec3{o.x + side_t * d.x, 0.0f, o.z + side_t * d.z});
      }
    }
  }
  // The caps: the nearest sphere hit, if nearer than the side's.
  for (float cap : {-h, h}) {
    float cap_t = 0.0f;
    Vec3 cap_normal;
    if (ray_sphere(o, d, best, Vec3{0.0f, cap, 0.0f}, r, cap_t, cap_normal) &&
        (!hit || cap_t < best)) {
      hit = true;
      best = cap_t;
      best_normal = cap_normal;
    }
  }
  if (!hit) return false;
  t = best;
  normal = rotate(rotation, best_normal);
  return true;
}

// The segment between the cap centres, rounded by the radius.
ConvexProxy proxy(const Shape& s, const GeometryStore& /*store*/, ProxyPoints& storage) {
  storage.points[0] = {0.0f, -s.half_height, 0.0f};
  storage.points[1] = {0.0f, s.half_height, 0.0f};
  ConvexProxy p;
  p.points = storage.points;
  p.count = 2;
  p.radius = s.radius;
  return p;
}

}  // namespace

extern const ShapeOps kCapsuleOps{"capsule", true,   check,        canonical,
                                  extent,    volume, inertia,      half_bounds,
                                  raycast,   proxy,  sweep_convex, nullptr};

}  // namespace rwd::sim::d3
