// SPDX-License-Identifier: MIT
// The triangle mesh: registered geometry (mesh.h) for static and kinematic
// bodies, found in the world's GeometryStore by the shape's id. The body's
// mass frame is the centre of the mesh's bounds (mass_frame.h), so the
// shape's half extents are half the size of those bounds and the
// broadphase bounds it like a box. Convex shapes meet it triangle by
// triangle (triangle_source.h, whose SurfaceShape writes the table entries
// from what is said here); two meshes never collide.
#include "d3/mesh.h"
#include "d3/shape_ops.h"
#include "d3/triangle_source.h"

namespace rwd::sim::d3 {
namespace {

struct MeshSource {
  using Data = TriangleMesh;
  static constexpr const char* kName = "mesh";

  static const TriangleMesh* find(const GeometryStore& store, uint32_t geometry) {
    return store.mesh(geometry);
  }
  static bool one_sided(const TriangleMesh& m) { return m.one_sided; }
  static bool raycast(const TriangleMesh& m, Vec3 origin, Vec3 dir, float max_t, float& t,
                      Vec3& normal) {
    uint32_t triangle = 0;
    return mesh_raycast(m, origin, dir, max_t, t, normal, triangle);
  }
  template <class Visit>
  static void query(const TriangleMesh& m, const Aabb& box, Visit&& visit) {
    mesh_query(m, box, [&](uint32_t t) { visit(mesh_triangle(m, t)); });
  }
  static bool signed_distance(const TriangleMesh& m, Vec3 q, SurfaceDistance& out) {
    out = mesh_signed_distance(m, q);
    return true;
  }
};

using MeshShape = SurfaceShape<MeshSource>;

}  // namespace

void collide_mesh_convex(const Shape& mesh, const ShapePose& pose, const Shape& shape,
                         const ShapePose& shape_pose, float speculative_m,
                         const GeometryStore& store, Manifold& out) {
  MeshShape::collide_convex(mesh, pose, shape, shape_pose, speculative_m, store, out);
}

// Constant-initialized: the shape table reads it before main.
extern constinit const ShapeOps kMeshOps = MeshShape::ops();

}  // namespace rwd::sim::d3
