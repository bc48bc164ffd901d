// SPDX-License-Identifier: MIT
// The convex hull: registered geometry (hull.h) in its mass frame, found in
// the world's GeometryStore by the shape's id. The shape itself carries
// the half size of the hull's mass-frame bounds, so the broadphase bounds
// every hull without reading its vertices.
#include <string>

#include "d3/hull.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

Status check(const Shape& s, const GeometryStore& store) {
  if (store.hull(s.geometry) == nullptr) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "hull shape refers to geometry " + std::to_string(s.geometry) +
                             ", which is not a hull in this world's geometry store");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& store) {
  s.radius = 0.0f;
  s.half_height = 0.0f;
  s.half_extents = store.hull(s.geometry)->half_size;
}

float extent(const Shape& s, const GeometryStore& store) {
  return store.hull(s.geometry)->extent;
}

float volume(const Shape& s, const GeometryStore& store) {
  return store.hull(s.geometry)->volume;
}

Vec3 inertia(const Shape& s, const GeometryStore& store, float mass) {
  return store.hull(s.geometry)->unit_inertia * mass;
}

Vec3 half_bounds(const Shape& s, const Mat3& axes) {
  // The mass-frame bounds turned with the body: loose for a hull that is
  // far from box-like, exact for one that is a box.
  const Vec3 h = s.half_extents;
  return abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
}

// The ray clipped by every face plane in the mass frame: it enters through
// the last plane it crosses inward and leaves through the first it crosses
// outward.
bool raycast(const Shape& s, const GeometryStore& store, Vec3 center, Quat rotation, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const Hull& hull = *store.hull(s.geometry);
  const Vec3 o = inv_rotate(rotation, origin - center);
  const Vec3 d = inv_rotate(rotation, dir);
  float t_enter = 0.0f;
  float t_exit = max_distance;
  int enter_face = -1;
  for (uint32_t i = 0; i < hull.faces.size(); ++i) {
    const HullFace& f = hull.faces[i];
    const float gap = f.offset - dot(f.normal, o);  // >= 0: origin behind the plane
    const float speed = dot(f.normal, d);
    if (speed == 0.0f) {
      if (gap < 0.0f) return false;  // parallel and outside
      continue;
    }
    const float at = gap / speed;
    if (speed < 0.0f) {
      if (at > t_enter) {
        t_enter = at;
        enter_face = static_cast<int>(i);
      }
    } else if (at < t_exit) {
      t_exit = at;
    }
    if (t_enter > t_exit) return false;
  }
  if (enter_face < 0) {
    // No plane crossed inward ahead of the origin: it starts inside.
    t = 0.0f;
    normal = -dir;
    return true;
  }
  t = t_enter;
  normal = rotate(rotation, hull.faces[static_cast<uint32_t>(enter_face)].normal);
  return true;
}

// The hull's own vertices.
ConvexProxy proxy(const Shape& s, const GeometryStore& store, ProxyPoints& /*storage*/) {
  const Hull& hull = *store.hull(s.geometry);
  ConvexProxy p;
  p.points = hull.vertices.data();
  p.count = static_cast<uint32_t>(hull.vertices.size());
  return p;
}

}  // namespace

extern const ShapeOps kHullOps{"hull",  true,        check,   canonical, extent,       volume,
                               inertia, half_bounds, raycast, proxy,     sweep_convex, nullptr};

}  // namespace rwd::sim::d3
