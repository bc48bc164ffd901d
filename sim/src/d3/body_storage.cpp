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

Aabb shape_aabb(const Shape& shape, Vec3 position, Quat rotation) {
  Vec3 e;
  if (shape.type == ShapeType::kSphere) {
    e = {shape.radius, shape.radius, shape.radius};
  } else {
    Mat3 r = mat3_from_quat(rotation);
    Vec3 h = shape.half_extents;
    // Extent along world axis i = sum_k |R_ik| h_k.
    e = abs(r.c0) * h.x + abs(r.c1) * h.y + abs(r.c2) * h.z;
  }
  return {position - e, position + e};
}

Mat3 world_inverse_inertia(const BodyMass& mass, Quat rotation) {
  return rotate_diagonal(mat3_from_quat(rotation), mass.inv_inertia_local);
}

}  // namespace rwd::sim::d3
