// SPDX-License-Identifier: MIT
#pragma once
// Small builders shared by the triangle mesh, height field and
// triangle-manifold tests: grids of triangles, box and sphere proxies, and
// gathering a source's triangles near a shape.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "d3/gjk.h"
#include "d3/height_field.h"
#include "d3/mesh.h"

namespace rwd::sim::test {

/// A grid of (n + 1) x (n + 1) vertices spaced `cell` apart from `origin`
/// in x and z, height y = height(x, z), split like a HeightField (diagonal
/// from (r, c) to (r + 1, c + 1), normals up).
struct GridMesh {
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
};
inline GridMesh make_grid(uint32_t n, float cell, Vec3 origin,
                          const std::function<float(float, float)>& height) {
  GridMesh g;
  for (uint32_t r = 0; r <= n; ++r) {
    for (uint32_t c = 0; c <= n; ++c) {
      const float x = origin.x + static_cast<float>(c) * cell;
      const float z = origin.z + static_cast<float>(r) * cell;
      g.vertices.push_back({x, origin.y + height(x, z), z});
    }
  }
  for (uint32_t r = 0; r < n; ++r) {
    for (uint32_t c = 0; c < n; ++c) {
      const uint32_t p00 = r * (n + 1) + c;
      const uint32_t p10 = p00 + 1;
      const uint32_t p01 = p00 + n + 1;
      const uint32_t p11 = p01 + 1;
      g.indices.insert(g.indices.end(), {p00, p01, p11, p00, p11, p10});
    }
  }
  return g;
}

inline d3::TriangleMesh build_ok(const GridMesh& g, bool one_sided = false) {
  auto m = d3::build_mesh(g.vertices, g.indices, one_sided);
  EXPECT_TRUE(m.ok()) << m.status().message();
  return std::move(*m);
}

/// A box's eight corners (corner i has +x when bit 0 is set, +y bit 1, +z
/// bit 2, as gjk's tests and BoxHull number them) and its proxy.
struct BoxProxy {
  Vec3 corners[8];
  d3::ConvexProxy proxy;
};
inline void make_box(BoxProxy& b, Vec3 half, Vec3 position, Quat rotation = {}) {
  for (int i = 0; i < 8; ++i) {
    b.corners[i] = {(i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                    (i & 4) ? half.z : -half.z};
  }
  b.proxy.points = b.corners;
  b.proxy.count = 8;
  b.proxy.radius = 0.0f;
  b.proxy.position = position;
  b.proxy.axes = mat3_from_quat(rotation);
}

/// The proxy's world core points' bounds, grown by radius + margin.
inline d3::Aabb proxy_box(const d3::ConvexProxy& p, float margin) {
  d3::Aabb box;
  for (uint32_t i = 0; i < p.count; ++i) {
    const Vec3 w = p.position + p.axes * p.points[i];
    box.lower = i == 0 ? w : min(box.lower, w);
    box.upper = i == 0 ? w : max(box.upper, w);
  }
  const float g = p.radius + margin;
  box.lower = box.lower - Vec3{g, g, g};
  box.upper = box.upper + Vec3{g, g, g};
  return box;
}

inline std::vector<d3::TriangleRef> gather(const d3::TriangleMesh& mesh, const d3::Aabb& box) {
  std::vector<d3::TriangleRef> out;
  d3::mesh_query(mesh, box, [&](uint32_t t) { out.push_back(d3::mesh_triangle(mesh, t)); });
  return out;
}

inline std::vector<d3::TriangleRef> gather(const d3::HeightField& hf, const d3::Aabb& box) {
  std::vector<d3::TriangleRef> out;
  d3::height_field_query(hf, box, [&](const d3::TriangleRef& t) { out.push_back(t); });
  return out;
}

}  // namespace rwd::sim::test
