// SPDX-License-Identifier: MIT
#pragma once
// Static triangle meshes: immutable geometry built once (build_mesh) with a
// flat bounding volume hierarchy and per-edge "active" flags, then queried
// by box (mesh_query) and by ray (mesh_raycast). Everything is in the
// mesh's local frame; callers map shapes and rays into it.
//
// Determinism: the build is a pure function of the input bits (median
// splits on a total order, leaves sorted by index), so two builds of the
// same data are identical on every platform, and every query is a pure
// function of the mesh and its arguments.
//
// Vertices are not welded: two triangles share an edge only when they share
// its two vertex indices. An edge between unwelded duplicates counts as a
// boundary (active), so weld before building for smooth sliding.
#include <cstdint>
#include <span>
#include <vector>

#include "d3/aabb_tree.h"
#include "d3/triangle.h"
#include "rewind/core/status.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

inline constexpr uint32_t kMeshMinVertices = 3;
inline constexpr uint32_t kMeshMaxVertices = 1u << 20;
inline constexpr uint32_t kMeshMaxTriangles = 1u << 21;
/// Largest |coordinate| of a vertex, metres.
inline constexpr float kMeshMaxCoordinate = 1e5f;
/// Triangles with a smaller area are refused (m^2).
inline constexpr float kMeshMinTriangleArea = 1e-10f;
/// Leaves hold at most this many triangles.
inline constexpr uint32_t kMeshLeafSize = 4;
/// Depth bound of the tree (median splits of at most 2^21 triangles into
/// leaves of 4 need 20 levels); sizes the query stacks.
inline constexpr uint32_t kMeshMaxDepth = 24;

/// MeshTriangle::across of an edge that is not a fold.
inline constexpr uint32_t kNoVertex = 0xffffffffu;

struct MeshTriangle {
  uint32_t v[3];  ///< vertex indices, counter-clockwise about the normal
  Vec3 normal;    ///< unit
  /// Bit e (e < 3): edge (v[e], v[(e + 1) % 3]) is a boundary or convex
  /// edge and may give edge contacts seen from the front; bit 3 + e: the
  /// same seen from the back (boundary or concave). See triangle.h.
  uint8_t active_edges = 0;
  /// across[e]: the vertex of the neighbour across edge e off the edge
  /// when the edge is a fold (TriangleRef::across), else kNoVertex.
  uint32_t across[3] = {kNoVertex, kNoVertex, kNoVertex};
};

/// A node of the flat tree. Leaf: count > 0 triangles at
/// order[first .. first + count). Inner: count == 0, children at nodes[first]
/// and nodes[first + 1]. The root is nodes[0].
struct BvhNode {
  Aabb box;
  uint32_t first = 0;
  uint32_t count = 0;
};

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
  std::vector<uint32_t> order;  ///< triangle indices, grouped by leaf
  std::vector<BvhNode> nodes;
  bool one_sided = false;  ///< collisions and rays only from the front
  Aabb bounds;
};

/// Validates and builds. Refuses (kInvalidArgument, naming the offending
/// index): vertex count outside 3..2^20, an index count that is not a
/// multiple of 3, a triangle count outside 1..2^21, an index out of range,
/// a non-finite coordinate or one beyond kMeshMaxCoordinate, a triangle with
/// a repeated index or an area below kMeshMinTriangleArea.
Result<TriangleMesh> build_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                                bool one_sided);

/// The bounds of triangle i (exact min and max of its corners).
Aabb mesh_triangle_box(const TriangleMesh& mesh, uint32_t triangle);

/// Triangle i as the narrowphase takes it (id = i).
TriangleRef mesh_triangle(const TriangleMesh& mesh, uint32_t triangle);

/// Calls visit(triangle) for every triangle whose bounds overlap
/// `local_box` (closed boxes, as overlaps() in aabb_tree.h): exactly the
/// set a brute-force test finds. The order is the tree's (depth first, first
/// child first, leaves in ascending index), a pure function of the mesh and
/// the box. No allocation.
template <class Visit>
void mesh_query(const TriangleMesh& mesh, const Aabb& local_box, Visit&& visit) {
  if (mesh.nodes.empty()) return;
  uint32_t stack[2 * kMeshMaxDepth + 2];
  uint32_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = mesh.nodes[stack[--top]];
    if (!overlaps(node.box, local_box)) continue;
    if (node.count == 0) {
      stack[top++] = node.first + 1;  // popped second
      stack[top++] = node.first;
      continue;
    }
    for (uint32_t i = 0; i < node.count; ++i) {
      const uint32_t t = mesh.order[node.first + i];
      if (overlaps(mesh_triangle_box(mesh, t), local_box)) visit(t);
    }
  }
}

/// Closest hit of the ray origin + t * dir, 0 <= t <= max_t (local frame,
/// dir need not be unit). On a hit fills t, the unit face normal facing the
/// ray (for a two-sided mesh the normal is flipped when the ray meets the
/// back) and the triangle index; ties in t go to the lower index. A one-sided
/// mesh ignores triangles met from behind.
bool mesh_raycast(const TriangleMesh& mesh, Vec3 origin, Vec3 dir, float max_t, float& t,
                  Vec3& normal, uint32_t& triangle);

/// The signed distance from q to the mesh's surface (local frame, metres):
/// negative behind it, by the angle-weighted pseudo-normal of the feature
/// (face, edge, vertex) nearest q (mesh_distance.cpp), so negative exactly
/// inside a closed mesh wound counter-clockwise from outside. The same for
/// one- and two-sided meshes. Ties between equally near triangles go to
/// the lower index; a pure function of the mesh and q. No allocation.
SurfaceDistance mesh_signed_distance(const TriangleMesh& mesh, Vec3 q);

namespace mesh_detail {
/// Builds mesh.nodes and mesh.order from mesh.vertices and mesh.triangles
/// (mesh_bvh.cpp).
void build_bvh(TriangleMesh& mesh);
}  // namespace mesh_detail

}  // namespace rwd::sim::d3
