// SPDX-License-Identifier: MIT
#include "d3/body_storage.h"

#include "d3/shape_ops.h"

#include <cmath>

namespace rwd::sim::d3 {

BodyMass compute_mass(BodyKind kind, const Shape& shape, const GeometryStore& store,
                      float density) {
  const ShapeOps& ops = shape_ops(shape.type);
  BodyMass m;
  m.extent = ops.extent(shape, store);
  if (kind != BodyKind::kDynamic) return m;
  m.mass = density * ops.volume(shape, store);
  const Vec3 i = ops.inertia(shape, store, m.mass);
  m.inv_inertia_local = {1.0f / i.x, 1.0f / i.y, 1.0f / i.z};
  m.inv_mass = 1.0f / m.mass;
  return m;
}

Aabb shape_aabb(const Shape& shape, Vec3 position, const Mat3& axes) {
  const Vec3 e = shape_ops(shape.type).half_bounds(shape, axes);
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
