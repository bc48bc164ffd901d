// SPDX-License-Identifier: MIT
#include "d3/body_storage.h"
#include "rewind/sim/det_math.h"

#include <cmath>

namespace rwd::sim::d3 {

BodyMass compute_mass(BodyKind kind, const Shape& shape, float density) {
  BodyMass m;
  if (shape.type == ShapeType::kSphere) {
    m.extent = shape.radius;
  } else {
    m.extent = length(shape.half_extents);
  }
  if (kind != BodyKind::kDynamic) return m;
  if (shape.type == ShapeType::kSphere) {
    float r = shape.radius;
    float volume = (4.0f / 3.0f) * kPi * r * r * r;
    m.mass = density * volume;
    float i = 0.4f * m.mass * r * r;  // solid sphere: 2/5 m r^2
    m.inv_inertia_local = {1.0f / i, 1.0f / i, 1.0f / i};
  } else {
    Vec3 h = shape.half_extents;
    float volume = 8.0f * h.x * h.y * h.z;
    m.mass = density * volume;
    // Solid box: I_x = m/3 (hy^2 + hz^2) with half extents.
    float k = m.mass / 3.0f;
    m.inv_inertia_local = {1.0f / (k * (h.y * h.y + h.z * h.z)),
                           1.0f / (k * (h.x * h.x + h.z * h.z)),
                           1.0f / (k * (h.x * h.x + h.y * h.y))};
  }
  m.inv_mass = 1.0f / m.mass;
  return m;
}

Aabb shape_aabb(const Shape& shape, Vec3 position, const Mat3& axes) {
  Vec3 e;
  if (shape.type == ShapeType::kSphere) {
    e = {shape.radius, shape.radius, shape.radius};
  } else {
    Vec3 h = shape.half_extents;
    // Extent along world axis i = sum_k |R_ik| h_k.
    e = abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
  }
  return {position - e, position + e};
}

Aabb shape_aabb(const Shape& shape, Vec3 position, Quat rotation) {
  if (shape.type == ShapeType::kSphere) return shape_aabb(shape, position, Mat3{});
  return shape_aabb(shape, position, mat3_from_quat(rotation));
}

Mat3 world_inverse_inertia(const BodyMass& mass, const Mat3& axes) {
  return rotate_diagonal(axes, mass.inv_inertia_local);
}

Mat3 world_inverse_inertia(const BodyMass& mass, Quat rotation) {
  return world_inverse_inertia(mass, mat3_from_quat(rotation));
}

}  // namespace rwd::sim::d3
