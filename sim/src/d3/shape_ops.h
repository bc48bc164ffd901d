// SPDX-License-Identifier: MIT
#pragma once
// What the engine asks of a shape, one table entry per ShapeType, each
// written in that shape's own file (shape_sphere.cpp, shape_box.cpp, ...):
// its rule, its canonical form, mass properties, bounds and ray test. The
// pair routines live in the collide table (collide_table.cpp). A shape
// type the table does not know is refused where shapes enter (the API and
// the snapshot reader), so no stage ever guesses what an unknown shape is.
//
// Shapes made of registered geometry (hulls) find it in the world's
// GeometryStore, which every routine that may need it receives; the
// bounds, read for every body every step, come from the shape alone.
#include <cstdint>

#include "d3/gjk.h"
#include "d3/triangle.h"
#include "rewind/core/status.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Number of shape types; ShapeType values are 0 .. kShapeTypeCount - 1.
inline constexpr uint32_t kShapeTypeCount = 7;

/// Room for the core points a shape computes rather than stores.
struct ProxyPoints {
  Vec3 points[8];
};

struct ShapeOps {
  const char* name;
  /// Whether a dynamic body may have it (a closed solid with a volume);
  /// meshes and height fields are surfaces, for static and kinematic bodies.
  bool solid;
  /// The shape's sizes against the state rule (finite, in range), and its
  /// geometry id against the store.
  Status (*check)(const Shape& shape, const GeometryStore& store);
  /// Clears the fields this type does not use and fills those derived from
  /// its geometry, so equal shapes are equal bits (the fields it uses are
  /// quantized by the caller). Only for shapes check() accepts.
  void (*canonical)(Shape& shape, const GeometryStore& store);
  /// Largest distance from the centre of mass to the surface, m.
  float (*extent)(const Shape& shape, const GeometryStore& store);
  /// Volume, m^3.
  float (*volume)(const Shape& shape, const GeometryStore& store);
  /// Principal moments of inertia about the centre of mass for a body of
  /// `mass` kg, kg m^2, in the shape's mass frame.
  Vec3 (*inertia)(const Shape& shape, const GeometryStore& store, float mass);
  /// Half size of the world-axis bounds at rotation `axes` (mat3_from_quat),
  /// from the shape's own fields.
  Vec3 (*half_bounds)(const Shape& shape, const Mat3& axes);
  /// The first hit along origin + t dir (dir unit), 0 <= t <= max_distance,
  /// of the shape with its centre of mass at `position`, mass frame at
  /// `rotation`: t and the outward normal. A ray starting inside hits at
  /// t = 0 with the normal facing back.
  bool (*raycast)(const Shape& shape, const GeometryStore& store, Vec3 position, Quat rotation,
                  Vec3 origin, Vec3 dir, float max_distance, float& t, Vec3& normal);
  /// The shape as GJK sees it (gjk.h): core points in the mass frame and a
  /// radius, with the pose left at the origin for the caller to set. Core
  /// points that are not stored anywhere (a box's corners) are written to
  /// `storage`, which must outlive the proxy.
  ConvexProxy (*proxy)(const Shape& shape, const GeometryStore& store, ProxyPoints& storage);
  /// The first touch of `swept` (a convex proxy, world frame) moved by
  /// fraction * translation, fraction in [0, max_fraction], against this
  /// shape with its mass frame at `position`, `axes` (shape_cast's
  /// conventions: normal from this shape to the swept one).
  ShapeCastOutput (*sweep)(const Shape& shape, const GeometryStore& store, Vec3 position,
                           const Mat3& axes, const ConvexProxy& swept, Vec3 translation,
                           float max_fraction);
  /// The signed distance from `point` to a surface (a mesh, a height
  /// field) with its mass frame at `position`, `axes`: everything in the
  /// world frame; false when there is no surface (a height field of holes
  /// only). nullptr for the solid shapes, whose contact with a point (the
  /// collide table's sphere routines at radius zero) is their signed
  /// distance. A surface's contact cannot be: it meets a point behind a
  /// two-sided surface as one in front of its back face.
  bool (*signed_distance)(const Shape& shape, const GeometryStore& store, Vec3 position,
                          const Mat3& axes, Vec3 point, SurfaceDistance& out);
};

/// ShapeOps::sweep of the convex shapes: their proxy against the swept one.
ShapeCastOutput sweep_convex(const Shape& shape, const GeometryStore& store, Vec3 position,
                             const Mat3& axes, const ConvexProxy& swept, Vec3 translation,
                             float max_fraction);

inline bool is_known_shape(ShapeType type) {
  return static_cast<uint32_t>(type) < kShapeTypeCount;
}

/// The entry of a known shape type (is_known_shape).
const ShapeOps& shape_ops(ShapeType type);

// Each shape's entry, defined in its own file.
extern const ShapeOps kSphereOps;
extern const ShapeOps kBoxOps;
extern const ShapeOps kCapsuleOps;
extern const ShapeOps kHullOps;
extern const ShapeOps kMeshOps;
extern const ShapeOps kHeightFieldOps;
extern const ShapeOps kCompoundOps;

struct ShapePose;
struct Manifold;
/// A mesh or height field (A, mass-frame pose `pose`) against a convex
/// shape (B): one manifold, normal from A to B (shape_mesh.cpp,
/// shape_height_field.cpp).
void collide_mesh_convex(const Shape& mesh, const ShapePose& pose, const Shape& shape,
                         const ShapePose& shape_pose, float speculative_m,
                         const GeometryStore& store, Manifold& out);
void collide_height_field_convex(const Shape& field, const ShapePose& pose, const Shape& shape,
                                 const ShapePose& shape_pose, float speculative_m,
                                 const GeometryStore& store, Manifold& out);
/// A compound (A) against any shape (B): the deepest group of its
/// children's contacts (compound_contact.h) alone (no points when none).
void collide_compound(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                      float speculative_m, const GeometryStore& store, Manifold& out);

/// The ray test of a sphere of `radius` at `center` (dir unit), shared by
/// the shapes made of spheres.
bool ray_sphere(Vec3 origin, Vec3 dir, float max_distance, Vec3 center, float radius, float& t,
                Vec3& normal);

}  // namespace rwd::sim::d3
