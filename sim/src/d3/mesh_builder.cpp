// SPDX-License-Identifier: MIT
// build_mesh: validation, face normals and active edges. The tree is built
// in mesh_bvh.cpp.
//
// Adjacency: every edge is keyed by its two vertex indices (lower first)
// and the keys are sorted (a total order, so the result is the same on
// every platform). An edge listed once is a boundary; listed twice by
// triangles that run it in opposite directions (consistent winding) it is
// classified by classify_shared_edge; anything else (three or more
// triangles, or two wound inconsistently) is treated as a boundary, which
// only costs smoothness, never correctness.
#include <algorithm>
#include <cmath>
#include <string>

#include "d3/mesh.h"

namespace rwd::sim::d3 {
namespace {

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

struct EdgeKey {
  uint32_t lo;
  uint32_t hi;
  uint32_t triangle;
  uint32_t edge;  // 0..2, edge (v[e], v[(e + 1) % 3])
};

bool key_less(const EdgeKey& a, const EdgeKey& b) {
  if (a.lo != b.lo) return a.lo < b.lo;
  if (a.hi != b.hi) return a.hi < b.hi;
  if (a.triangle != b.triangle) return a.triangle < b.triangle;
  return a.edge < b.edge;
}

void compute_active_edges(TriangleMesh& mesh) {
  const uint32_t tri_count = static_cast<uint32_t>(mesh.triangles.size());
  std::vector<EdgeKey> keys;
  keys.reserve(static_cast<size_t>(tri_count) * 3);
  for (uint32_t t = 0; t < tri_count; ++t) {
    const MeshTriangle& tri = mesh.triangles[t];
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = tri.v[e];
      const uint32_t b = tri.v[(e + 1) % 3];
      keys.push_back({a < b ? a : b, a < b ? b : a, t, e});
    }
  }
  std::sort(keys.begin(), keys.end(), key_less);
  size_t i = 0;
  while (i < keys.size()) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].lo == keys[i].lo && keys[j].hi == keys[i].hi) ++j;
    bool shared = j - i == 2;
    if (shared) {
      const MeshTriangle& t1 = mesh.triangles[keys[i].triangle];
      const MeshTriangle& t2 = mesh.triangles[keys[i + 1].triangle];
      // Consistent winding: the two run the edge in opposite directions.
      shared = t1.v[keys[i].edge] != t2.v[keys[i + 1].edge];
    }
    for (size_t k = i; k < j; ++k) {
      MeshTriangle& tri = mesh.triangles[keys[k].triangle];
      const uint32_t e = keys[k].edge;
      uint8_t bits = kBoundaryEdgeBits;
      if (shared) {
        const EdgeKey& other_key = keys[k == i ? i + 1 : i];
        const MeshTriangle& other = mesh.triangles[other_key.triangle];
        const uint32_t opposite = other.v[(other_key.edge + 2) % 3];
        bits = classify_shared_edge(tri.normal, other.normal, mesh.vertices[tri.v[e]],
                                    mesh.vertices[opposite]);
        if (bits != 0) tri.across[e] = opposite;
      }
      tri.active_edges = static_cast<uint8_t>(tri.active_edges | (bits << e));
    }
    i = j;
  }
}

}  // namespace

Aabb mesh_triangle_box(const TriangleMesh& mesh, uint32_t triangle) {
  const MeshTriangle& t = mesh.triangles[triangle];
  const Vec3 a = mesh.vertices[t.v[0]];
  const Vec3 b = mesh.vertices[t.v[1]];
  const Vec3 c = mesh.vertices[t.v[2]];
  return {min(min(a, b), c), max(max(a, b), c)};
}

TriangleRef mesh_triangle(const TriangleMesh& mesh, uint32_t triangle) {
  const MeshTriangle& t = mesh.triangles[triangle];
  TriangleRef r;
  r.p[0] = mesh.vertices[t.v[0]];
  r.p[1] = mesh.vertices[t.v[1]];
  r.p[2] = mesh.vertices[t.v[2]];
  r.normal = t.normal;
  r.active_edges = t.active_edges;
  for (uint32_t e = 0; e < 3; ++e) {
    if (t.across[e] != kNoVertex) r.across[e] = mesh.vertices[t.across[e]];
  }
  r.id = triangle;
  return r;
}

Result<TriangleMesh> build_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                                bool one_sided) {
  if (vertices.size() < kMeshMinVertices || vertices.size() > kMeshMaxVertices) {
    return invalid("mesh: vertex count " + std::to_string(vertices.size()) + " outside 3..1048576");
  }
  if (indices.size() % 3 != 0) {
    return invalid("mesh: index count " + std::to_string(indices.size()) +
                   " is not a multiple of 3");
  }
  const size_t tri_count = indices.size() / 3;
  if (tri_count < 1 || tri_count > kMeshMaxTriangles) {
    return invalid("mesh: triangle count " + std::to_string(tri_count) + " outside 1..2097152");
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3 v = vertices[i];
    if (!is_finite(v) || !(std::fabs(v.x) <= kMeshMaxCoordinate) ||
        !(std::fabs(v.y) <= kMeshMaxCoordinate) || !(std::fabs(v.z) <= kMeshMaxCoordinate)) {
      return invalid("mesh: vertex " + std::to_string(i) +
                     " is not finite or beyond 1e5 m from the origin");
    }
  }
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertices.size()) {
      return invalid("mesh: index " + std::to_string(i) + " (" + std::to_string(indices[i]) +
                     ") out of range of " + std::to_string(vertices.size()) + " vertices");
    }
  }

  TriangleMesh mesh;
  mesh.one_sided = one_sided;
  mesh.vertices.assign(vertices.begin(), vertices.end());
  mesh.triangles.resize(tri_count);
  for (size_t t = 0; t < tri_count; ++t) {
    MeshTriangle& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) tri.v[k] = indices[3 * t + k];
    if (tri.v[0] == tri.v[1] || tri.v[1] == tri.v[2] || tri.v[0] == tri.v[2]) {
      return invalid("mesh: triangle " + std::to_string(t) + " repeats a vertex index");
    }
    const Vec3 n =
        triangle_cross(mesh.vertices[tri.v[0]], mesh.vertices[tri.v[1]], mesh.vertices[tri.v[2]]);
    const float twice_area = length(n);
    if (!(twice_area >= 2.0f * kMeshMinTriangleArea)) {
      return invalid("mesh: triangle " + std::to_string(t) +
                     " is degenerate (area below 1e-10 m^2)");
    }
    tri.normal = n * (1.0f / twice_area);
  }
  compute_active_edges(mesh);

  mesh_detail::build_bvh(mesh);
  // The root's box: the bounds of the triangles (unreferenced vertices
  // do not widen it).
  mesh.bounds = mesh.nodes[0].box;
  return mesh;
}

}  // namespace rwd::sim::d3
