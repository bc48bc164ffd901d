// SPDX-License-Identifier: MIT
#include "d3/body_storage.h"
#include "rewind/sim/det_math.h"

#include <cmath>

namespace rwd::sim::d3 {
namespace {

bool in_size_range(float v) {
  return std::isfinite(v) && v > 0.0f && v <= kMaxShapeSize;
}
bool in_coordinate_range(Vec3 v) {
  return is_finite(v) && std::fabs(v.x) < kMaxCoordinate && std::fabs(v.y) < kMaxCoordinate &&
         std::fabs(v.z) < kMaxCoordinate;
}
bool in_speed_range(Vec3 v) {
  return is_finite(v) && std::fabs(v.x) <= kMaxSpeed && std::fabs(v.y) <= kMaxSpeed &&
         std::fabs(v.z) <= kMaxSpeed;
}
Status invalid(const char* what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

}  // namespace

Status validate_shape(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kSphere:
      if (!in_size_range(shape.radius)) return invalid("sphere radius must be in (0, 1000] m");
      return Status::Ok();
    case ShapeType::kBox:
      if (!in_size_range(shape.half_extents.x) || !in_size_range(shape.half_extents.y) ||
          !in_size_range(shape.half_extents.z)) {
        return invalid("box half extents must be in (0, 1000] m");
      }
      return Status::Ok();
  }
  return invalid("unknown shape type");
}

Status validate_body_def(const BodyDef& def) {
  if (def.kind != BodyKind::kStatic && def.kind != BodyKind::kKinematic &&
      def.kind != BodyKind::kDynamic) {
    return invalid("unknown body kind");
  }
  Status s = validate_shape(def.shape);
  if (!s.ok()) return s;
  if (!in_coordinate_range(def.position)) return invalid("position must be finite, |x| < 1e5 m");
  if (!is_finite(def.rotation) || length_squared(def.rotation) < 1e-6f) {
    return invalid("rotation must be a finite, non-zero quaternion");
  }
  if (!in_speed_range(def.linear_velocity) || !in_speed_range(def.angular_velocity)) {
    return invalid("velocities must be finite and at most 1e4");
  }
  if (!(std::isfinite(def.density) && def.density > 0.0f && def.density <= 1e9f)) {
    return invalid("density must be in (0, 1e9] kg/m^3");
  }
  if (!(std::isfinite(def.linear_damping) && def.linear_damping >= 0.0f &&
        def.linear_damping <= 1e4f) ||
      !(std::isfinite(def.angular_damping) && def.angular_damping >= 0.0f &&
        def.angular_damping <= 1e4f)) {
    return invalid("damping must be in [0, 1e4] 1/s");
  }
  if (!(std::isfinite(def.gravity_scale) && std::fabs(def.gravity_scale) <= 1e3f)) {
    return invalid("gravity_scale must be finite, |g| <= 1000");
  }
  if (!(std::isfinite(def.material.friction) && def.material.friction >= 0.0f &&
        def.material.friction <= 10.0f)) {
    return invalid("friction must be in [0, 10]");
  }
  if (!(std::isfinite(def.material.restitution) && def.material.restitution >= 0.0f &&
        def.material.restitution <= 1.0f)) {
    return invalid("restitution must be in [0, 1]");
  }
  if (def.kind == BodyKind::kStatic &&
      (!(def.linear_velocity == Vec3{}) || !(def.angular_velocity == Vec3{}))) {
    return invalid("static bodies cannot have a velocity");
  }
  return Status::Ok();
}

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
