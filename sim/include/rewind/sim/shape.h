// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/geometry_id.h"
#include "rewind/sim/math.h"

namespace rwd::sim {

enum class ShapeType : uint8_t {
  kSphere = 0,
  kBox = 1,
  /// A segment along the body's local y axis, from -half_height to
  /// +half_height, swept by a sphere of `radius`.
  kCapsule = 2,
  /// A convex hull registered in the world's GeometryStore (geometry.h),
  /// referred to by id.
  kHull = 3,
  /// A triangle mesh registered in the store (static and kinematic bodies).
  kMesh = 4,
  /// A height field registered in the store (static and kinematic bodies).
  kHeightField = 5,
  /// A compound of convex children registered in the store.
  kCompound = 6,
};

/// A collision shape on its body's origin. Plain data, trivially copyable,
/// part of world state. Sizes are in metres, each in (0, 1000]. Shapes
/// made of registered geometry (hulls) hold its id, never the data.
struct Shape {
  ShapeType type = ShapeType::kBox;
  float radius = 0.0f;  ///< sphere and capsule radius, m
  /// Box half sizes, m. For a hull, filled by the world when the body is
  /// made: half the size of the hull's bounds in its mass frame.
  Vec3 half_extents;
  float half_height = 0.0f;  ///< capsule: half the distance between its cap centres, m
  uint32_t geometry = 0;     ///< hull, mesh, height field: its GeometryId in the world's store

  static Shape make_sphere(float radius_m) {
    Shape s;
    s.type = ShapeType::kSphere;
    s.radius = radius_m;
    return s;
  }
  static Shape make_box(Vec3 half_extents_m) {
    Shape s;
    s.type = ShapeType::kBox;
    s.half_extents = half_extents_m;
    return s;
  }
  /// A capsule standing along local y: total height 2 (half_height_m +
  /// radius_m).
  static Shape make_capsule(float radius_m, float half_height_m) {
    Shape s;
    s.type = ShapeType::kCapsule;
    s.radius = radius_m;
    s.half_height = half_height_m;
    return s;
  }
  /// A registered convex hull (GeometryStore::add_hull). The body turns
  /// about the hull's centre of mass; its position is the origin of the
  /// frame the hull's points were given in.
  static Shape make_hull(GeometryId id) {
    Shape s;
    s.type = ShapeType::kHull;
    s.geometry = id.value;
    return s;
  }
  /// A registered triangle mesh (GeometryStore::add_mesh), for static and
  /// kinematic bodies; its position is the origin of its vertices' frame.
  static Shape make_mesh(GeometryId id) {
    Shape s;
    s.type = ShapeType::kMesh;
    s.geometry = id.value;
    return s;
  }
  /// A registered height field (GeometryStore::add_height_field), for
  /// static and kinematic bodies; its position is where sample (0, 0) sits
  /// at height 0.
  static Shape make_height_field(GeometryId id) {
    Shape s;
    s.type = ShapeType::kHeightField;
    s.geometry = id.value;
    return s;
  }
  /// A registered compound (GeometryStore::add_compound). The body turns
  /// about the compound's centre of mass; its position is the origin of
  /// the frame its children were placed in.
  static Shape make_compound(GeometryId id) {
    Shape s;
    s.type = ShapeType::kCompound;
    s.geometry = id.value;
    return s;
  }
  /// Whether the shape refers to registered geometry.
  bool uses_geometry() const {
    return type == ShapeType::kHull || type == ShapeType::kMesh ||
           type == ShapeType::kHeightField || type == ShapeType::kCompound;
  }
};

}  // namespace rwd::sim
