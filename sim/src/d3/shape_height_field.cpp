// SPDX-License-Identifier: MIT
// The height field: registered geometry (height_field.h) for static and
// kinematic bodies, found in the world's GeometryStore by the shape's id.
// Like a mesh (shape_mesh.cpp): its mass frame is the centre of its bounds,
// convex shapes meet it triangle by triangle (triangle_source.h), and it
// never collides with a mesh or another height field.
#include <string>

#include "d3/height_field.h"
#include "d3/shape_ops.h"
#include "d3/triangle_source.h"

namespace rwd::sim::d3 {
namespace {

const HeightField& field_of(const Shape& s, const GeometryStore& store) {
  return *store.height_field(s.geometry);
}

Status check(const Shape& s, const GeometryStore& store) {
  return check_surface(store.height_field(s.geometry) != nullptr, "height field", s.geometry);
}

void canonical(Shape& s, const GeometryStore& store) {
  surface_canonical(s, field_of(s, store).bounds);
}

bool raycast(const Shape& s, const GeometryStore& store, Vec3 position, Quat rotation, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const HeightField& h = field_of(s, store);
  const SourceFrame f = source_frame(position, mat3_from_quat(rotation), bounds_center(h.bounds));
  return raycast_source(f, origin, dir, max_distance, t, normal,
                        [&h](Vec3 o, Vec3 d, float max_t, float& hit_t, Vec3& n) {
                          uint32_t id = 0;
                          return height_field_raycast(h, o, d, max_t, hit_t, n, id);
                        });
}

auto triangles_of(const HeightField& h) {
  return [&h](const Aabb& box, auto&& visit) { height_field_query(h, box, visit); };
}

ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                      const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  const HeightField& h = field_of(s, store);
  return sweep_source(source_frame(position, axes, bounds_center(h.bounds)), false, triangles_of(h),
                      swept, translation, max_fraction);
}

bool signed_distance(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                     Vec3 point, SurfaceDistance& out) {
  const HeightField& h = field_of(s, store);
  return signed_distance_source(
      source_frame(position, axes, bounds_center(h.bounds)), point, out,
      [&h](Vec3 q, SurfaceDistance& d) { return height_field_signed_distance(h, q, d); });
}

}  // namespace

void collide_height_field_convex(const Shape& field, const ShapePose& pose, const Shape& shape,
                                 const ShapePose& shape_pose, float speculative_m,
                                 const GeometryStore& store, Manifold& out) {
  const HeightField& h = field_of(field, store);
  collide_source_convex(source_frame(pose.position, pose.axes, bounds_center(h.bounds)), false,
                        triangles_of(h), shape, shape_pose, store, speculative_m, out);
}

extern const ShapeOps kHeightFieldOps{
    "height field", false,          check,           canonical,
    surface_extent, surface_volume, surface_inertia, surface_half_bounds,
    raycast,        nullptr,        sweep,           signed_distance};

}  // namespace rwd::sim::d3
