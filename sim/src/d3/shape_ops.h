// SPDX-License-Identifier: MIT
#pragma once
// What the engine asks of a shape, one table entry per ShapeType, each
// written in that shape's own file (shape_sphere.cpp, shape_box.cpp, ...):
// its rule, its canonical form, mass properties, bounds and ray test. The
// pair routines live in the collide table (collide_table.cpp). A shape
// type the table does not know is refused where shapes enter (the API and
// the snapshot reader), so no stage ever guesses what an unknown shape is.
#include <cstdint>

#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/status.h"

namespace rwd::sim::d3 {

/// Number of shape types; ShapeType values are 0 .. kShapeTypeCount - 1.
inline constexpr uint32_t kShapeTypeCount = 3;

struct ShapeOps {
  const char* name;
  /// The shape's sizes against the state rule (finite, in range).
  Status (*check)(const Shape& shape);
  /// Clears the fields this type does not use, so equal shapes are equal
  /// bits (the fields it uses are quantized by the caller).
  void (*canonical)(Shape& shape);
  /// Largest distance from the body's origin to the surface, m.
  float (*extent)(const Shape& shape);
  /// Volume, m^3.
  float (*volume)(const Shape& shape);
  /// Principal moments of inertia about the centre for a body of `mass` kg,
  /// kg m^2, in the shape's frame.
  Vec3 (*inertia)(const Shape& shape, float mass);
  /// Half size of the world-axis bounds at rotation `axes` (mat3_from_quat).
  Vec3 (*half_bounds)(const Shape& shape, const Mat3& axes);
  /// The first hit along origin + t dir (dir unit), 0 <= t <= max_distance,
  /// of the shape at `position`, `rotation`: t and the outward normal. A
  /// ray starting inside hits at t = 0 with the normal facing back.
  bool (*raycast)(const Shape& shape, Vec3 position, Quat rotation, Vec3 origin, Vec3 dir,
                  float max_distance, float& t, Vec3& normal);
};

inline bool is_known_shape(ShapeType type) {
  return static_cast<uint32_t>(type) < kShapeTypeCount;
}

/// The entry of a known shape type (is_known_shape).
const ShapeOps& shape_ops(ShapeType type);

// Each shape's entry, defined in its own file.
extern const ShapeOps kSphereOps;
extern const ShapeOps kBoxOps;
extern const ShapeOps kCapsuleOps;

/// The ray test of a sphere of `radius` at `center` (dir unit), shared by
/// the shapes made of spheres.
bool ray_sphere(Vec3 origin, Vec3 dir, float max_distance, Vec3 center, float radius, float& t,
                Vec3& normal);

}  // namespace rwd::sim::d3
