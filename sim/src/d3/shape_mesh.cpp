// SPDX-License-Identifier: MIT
// The triangle mesh: registered geometry (mesh.h) for static and kinematic
// bodies, found in the world's GeometryStore by the shape's id. The body's
// mass frame is the centre of the mesh's bounds (mass_frame.h), so the
// shape's half extents are half the size of those bounds and the
// broadphase bounds it like a box. Convex shapes meet it triangle by
// triangle (triangle_source.h); two meshes never collide.
#include <string>

#include "d3/mesh.h"
#include "d3/shape_ops.h"
#include "d3/triangle_source.h"

namespace rwd::sim::d3 {
namespace {

const TriangleMesh& mesh_of(const Shape& s, const GeometryStore& store) {
  return *store.mesh(s.geometry);
}

Status check(const Shape& s, const GeometryStore& store) {
  return check_surface(store.mesh(s.geometry) != nullptr, "mesh", s.geometry);
}

void canonical(Shape& s, const GeometryStore& store) {
  surface_canonical(s, mesh_of(s, store).bounds);
}

bool raycast(const Shape& s, const GeometryStore& store, Vec3 position, Quat rotation, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const TriangleMesh& m = mesh_of(s, store);
  const SourceFrame f = source_frame(position, mat3_from_quat(rotation), bounds_center(m.bounds));
  return raycast_source(f, origin, dir, max_distance, t, normal,
                        [&m](Vec3 o, Vec3 d, float max_t, float& hit_t, Vec3& n) {
                          uint32_t triangle = 0;
                          return mesh_raycast(m, o, d, max_t, hit_t, n, triangle);
                        });
}

auto triangles_of(const TriangleMesh& m) {
  return [&m](const Aabb& box, auto&& visit) {
    mesh_query(m, box, [&](uint32_t t) { visit(mesh_triangle(m, t)); });
  };
}

ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                      const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  const TriangleMesh& m = mesh_of(s, store);
  return sweep_source(source_frame(position, axes, bounds_center(m.bounds)), m.one_sided,
                      triangles_of(m), swept, translation, max_fraction);
}

bool signed_distance(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                     Vec3 point, SurfaceDistance& out) {
  const TriangleMesh& m = mesh_of(s, store);
  return signed_distance_source(source_frame(position, axes, bounds_center(m.bounds)), point, out,
                                [&m](Vec3 q, SurfaceDistance& d) {
                                  d = mesh_signed_distance(m, q);
                                  return true;
                                });
}

}  // namespace

void collide_mesh_convex(const Shape& mesh, const ShapePose& pose, const Shape& shape,
                         const ShapePose& shape_pose, float speculative_m,
                         const GeometryStore& store, Manifold& out) {
  const TriangleMesh& m = mesh_of(mesh, store);
  collide_source_convex(source_frame(pose.position, pose.axes, bounds_center(m.bounds)),
                        m.one_sided, triangles_of(m), shape, shape_pose, store, speculative_m, out);
}

extern const ShapeOps kMeshOps{"mesh",         false,          check,           canonical,
                               surface_extent, surface_volume, surface_inertia, surface_half_bounds,
                               raycast,        nullptr,        sweep,           signed_distance};

}  // namespace rwd::sim::d3
