// SPDX-License-Identifier: MIT
// The height field: registered geometry (height_field.h) for static and
// kinematic bodies, found in the world's GeometryStore by the shape's id.
// Like a mesh (shape_mesh.cpp): its mass frame is the centre of its bounds,
// convex shapes meet it triangle by triangle (triangle_source.h, whose
// SurfaceShape writes the table entries from what is said here), and it
// never collides with a mesh or another height field. It is seen from both
// sides, like a two-sided mesh.
#include "d3/height_field.h"
#include "d3/shape_ops.h"
#include "d3/triangle_source.h"

namespace rwd::sim::d3 {
namespace {

struct HeightFieldSource {
  using Data = HeightField;
  static constexpr const char* kName = "height field";

  static const HeightField* find(const GeometryStore& store, uint32_t geometry) {
    return store.height_field(geometry);
  }
  static bool one_sided(const HeightField& /*h*/) { return false; }
  static bool raycast(const HeightField& h, Vec3 origin, Vec3 dir, float max_t, float& t,
                      Vec3& normal) {
    uint32_t id = 0;
    return height_field_raycast(h, origin, dir, max_t, t, normal, id);
  }
  template <class Visit>
  static void query(const HeightField& h, const Aabb& box, Visit&& visit) {
    height_field_query(h, box, visit);
  }
  static bool signed_distance(const HeightField& h, Vec3 q, SurfaceDistance& out) {
    return height_field_signed_distance(h, q, out);
  }
};

using HeightFieldShape = SurfaceShape<HeightFieldSource>;

}  // namespace

void collide_height_field_convex(const Shape& field, const ShapePose& pose, const Shape& shape,
                                 const ShapePose& shape_pose, float speculative_m,
                                 const GeometryStore& store, Manifold& out) {
  HeightFieldShape::collide_convex(field, pose, shape, shape_pose, speculative_m, store, out);
}

// Constant-initialized: the shape table reads it before main.
extern constinit const ShapeOps kHeightFieldOps = HeightFieldShape::ops();

}  // namespace rwd::sim::d3
