// SPDX-License-Identifier: MIT
// The mesh's tree and ray query.
//
// Build: top down, each range split at its median along the largest axis
// of its triangles' centroid bounds. Triangles are ordered by (centroid
// coordinate, index), a total order, so nth_element's partition (which
// elements fall on each side) is unique whatever the library; within a
// leaf the indices are sorted, so `order` and `nodes` are the same on every
// platform. Children of a node are allocated together (first, first + 1),
// so the tree is one flat array.
#include <algorithm>
#include <cmath>

#include "d3/mesh.h"

namespace rwd::sim::d3 {
namespace mesh_detail {
namespace {

struct Builder {
  TriangleMesh& mesh;
  std::vector<Vec3> centroid;  // sum of the corners (a third of it is the centroid)

  void build(uint32_t node, uint32_t first, uint32_t count) {
    Aabb box = mesh_triangle_box(mesh, mesh.order[first]);
    Vec3 c_lo = centroid[mesh.order[first]];
    Vec3 c_hi = c_lo;
    for (uint32_t i = 1; i < count; ++i) {
      const uint32_t t = mesh.order[first + i];
      const Aabb b = mesh_triangle_box(mesh, t);
      box.lower = min(box.lower, b.lower);
      box.upper = max(box.upper, b.upper);
      c_lo = min(c_lo, centroid[t]);
      c_hi = max(c_hi, centroid[t]);
    }
    mesh.nodes[node].box = box;
    uint32_t* begin = mesh.order.data() + first;
    if (count <= kMeshLeafSize) {
      std::sort(begin, begin + count);
      mesh.nodes[node].first = first;
      mesh.nodes[node].count = count;
      return;
    }
    const Vec3 extent = c_hi - c_lo;
    int axis = 0;
    if (extent.y > extent.x) axis = 1;
    if (extent.z > component(extent, axis)) axis = 2;
    const uint32_t half = count / 2;
    const std::vector<Vec3>& cen = centroid;
    std::nth_element(begin, begin + half, begin + count, [&cen, axis](uint32_t a, uint32_t b) {
      const float ca = component(cen[a], axis);
      const float cb = component(cen[b], axis);
      return ca < cb || (ca == cb && a < b);
    });
    const uint32_t child = static_cast<uint32_t>(mesh.nodes.size());
    mesh.nodes.push_back({});
    mesh.nodes.push_back({});
    mesh.nodes[node].first = child;
    mesh.nodes[node].count = 0;
    build(child, first, half);
    build(child + 1, first + half, count - half);
  }
};

}  // namespace

void build_bvh(TriangleMesh& mesh) {
  const uint32_t n = static_cast<uint32_t>(mesh.triangles.size());
  Builder b{mesh, {}};
  b.centroid.resize(n);
  mesh.order.resize(n);
  for (uint32_t t = 0; t < n; ++t) {
    const MeshTriangle& tri = mesh.triangles[t];
    b.centroid[t] = mesh.vertices[tri.v[0]] + mesh.vertices[tri.v[1]] + mesh.vertices[tri.v[2]];
    mesh.order[t] = t;
  }
  mesh.nodes.clear();
  // A tree over n leaves of up to kMeshLeafSize has fewer than 2n nodes.
  mesh.nodes.reserve(2 * static_cast<size_t>(n));
  mesh.nodes.push_back({});
  b.build(0, 0, n);
}

}  // namespace mesh_detail

bool mesh_raycast(const TriangleMesh& mesh, Vec3 origin, Vec3 dir, float max_t, float& t,
                  Vec3& normal, uint32_t& triangle) {
  if (mesh.nodes.empty() || !(max_t >= 0.0f)) return false;
  const Vec3 big = max(abs(mesh.bounds.lower), abs(mesh.bounds.upper));
  // Node boxes are widened by pad on every side. The widening only adds
  // candidates (every triangle is tested exactly), so rounding in the slab
  // test cannot drop a hit that lies on a node's face.
  const float widen = 1e-5f * (1.0f + std::fmax(big.x, std::fmax(big.y, big.z)));
  const Vec3 pad{widen, widen, widen};
  const SegmentSlabs slabs(origin, dir);
  bool hit = false;
  float best_t = max_t;
  uint32_t best = 0;
  uint32_t stack[2 * kMeshMaxDepth + 2];
  uint32_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = mesh.nodes[stack[--top]];
    // Nodes are pruned against the best hit so far, widened a little: the
    // visiting order then cannot change which of two equal hits wins.
    const float reach = hit ? best_t + 1e-6f * (1.0f + best_t) : best_t;
    if (!slabs.hits({node.box.lower - pad, node.box.upper + pad}, reach < max_t ? reach : max_t)) {
      continue;
    }
    if (node.count == 0) {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
      continue;
    }
    for (uint32_t i = 0; i < node.count; ++i) {
      const uint32_t k = mesh.order[node.first + i];
      const MeshTriangle& tri = mesh.triangles[k];
      float tk = 0.0f;
      if (!ray_triangle(origin, dir, mesh.vertices[tri.v[0]], mesh.vertices[tri.v[1]],
                        mesh.vertices[tri.v[2]], max_t, mesh.one_sided, tk)) {
        continue;
      }
      if (!hit || tk < best_t || (tk == best_t && k < best)) {
        hit = true;
        best_t = tk;
        best = k;
      }
    }
  }
  if (!hit) return false;
  t = best_t;
  triangle = best;
  const Vec3 n = mesh.triangles[best].normal;
  normal = dot(n, dir) > 0.0f ? -n : n;
  return true;
}

}  // namespace rwd::sim::d3
