// SPDX-License-Identifier: MIT
// Triangle meshes: validation messages, the tree's box query and ray query
// against brute force on random triangle soups, bit-identical rebuilds, the
// active-edge flags of a flat grid, a convex ridge and a concave valley, and
// the signed distance's nearest triangle against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "d3/mesh.h"
#include "d3/triangle_closest.h"
#include "mesh_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using test::GridMesh;
using test::make_grid;

std::string build_error(const std::vector<Vec3>& v, const std::vector<uint32_t>& idx) {
  auto m = build_mesh(v, idx, false);
  EXPECT_FALSE(m.ok());
  if (m.ok()) return "";
  EXPECT_EQ(m.status().code(), ErrorCode::kInvalidArgument);
  return m.status().message();
}

TEST(Mesh, RefusesBadInput) {
  const std::vector<Vec3> tri{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  EXPECT_NE(build_error({{0, 0, 0}, {1, 0, 0}}, {0, 1, 0}).find("vertex count"), std::string::npos);
  EXPECT_NE(build_error(tri, {0, 1}).find("multiple of 3"), std::string::npos);
  EXPECT_NE(build_error(tri, {}).find("triangle count"), std::string::npos);
  EXPECT_NE(build_error(tri, {0, 1, 2, 0, 1, 3}).find("index 5"), std::string::npos);
  EXPECT_NE(build_error(tri, {0, 1, 1}).find("triangle 0"), std::string::npos);
  std::vector<Vec3> bad = tri;
  bad[2].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(build_error(bad, {0, 1, 2}).find("vertex 2"), std::string::npos);
  bad = tri;
  bad[1].x = 1.5e5f;
  EXPECT_NE(build_error(bad, {0, 1, 2}).find("vertex 1"), std::string::npos);
  // Collinear corners: zero area, named by the triangle.
  const std::vector<Vec3> line{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, 2}};
  EXPECT_NE(build_error(line, {0, 1, 2, 0, 1, 3}).find("triangle 1"), std::string::npos);
  // Tiny but above the limit: accepted.
  const std::vector<Vec3> small{{0, 0, 0}, {0, 0, 1e-4f}, {1e-4f, 0, 0}};
  EXPECT_TRUE(build_mesh(small, std::vector<uint32_t>{0, 1, 2}, false).ok());
}

// A soup of n random triangles in a 20 m cube, sizes up to 2 m.
GridMesh random_soup(test::Rng& rng, uint32_t n) {
  GridMesh g;
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3 c{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
    for (int k = 0; k < 3; ++k) {
      g.vertices.push_back(c + Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
      g.indices.push_back(3 * i + k);
    }
  }
  return g;
}

TEST(Mesh, QueryMatchesBruteForce) {
  test::Rng rng{7};
  for (uint32_t n : {1u, 3u, 5u, 17u, 300u, 2000u}) {
    const GridMesh g = random_soup(rng, n);
    const TriangleMesh mesh = test::build_ok(g);
    ASSERT_EQ(mesh.order.size(), n);
    for (const BvhNode& node : mesh.nodes) EXPECT_LE(node.count, kMeshLeafSize);
    for (int q = 0; q < 200; ++q) {
      const Vec3 c{rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(-12, 12)};
      const Vec3 h{rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 3)};
      const Aabb box{c - h, c + h};
      std::vector<uint32_t> got;
      mesh_query(mesh, box, [&](uint32_t t) { got.push_back(t); });
      std::vector<uint32_t> again;
      mesh_query(mesh, box, [&](uint32_t t) { again.push_back(t); });
      EXPECT_EQ(got, again);
      std::vector<uint32_t> want;
      for (uint32_t t = 0; t < n; ++t) {
        if (overlaps(mesh_triangle_box(mesh, t), box)) want.push_back(t);
      }
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want);
    }
  }
}

TEST(Mesh, RebuildIsBitIdentical) {
  test::Rng rng{11};
  const GridMesh g = random_soup(rng, 777);
  const TriangleMesh a = test::build_ok(g);
  const TriangleMesh b = test::build_ok(g);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(0, std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)));
  EXPECT_EQ(a.order, b.order);
  for (size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_EQ(a.triangles[i].normal, b.triangles[i].normal);
    EXPECT_EQ(a.triangles[i].active_edges, b.triangles[i].active_edges);
  }
}

TEST(Mesh, RaycastMatchesBruteForce) {
  test::Rng rng{3};
  for (bool one_sided : {false, true}) {
    const GridMesh g = random_soup(rng, 1500);
    const TriangleMesh mesh = test::build_ok(g, one_sided);
    int hits = 0;
    for (int q = 0; q < 500; ++q) {
      const Vec3 o{rng.uniform(-15, 15), rng.uniform(-15, 15), rng.uniform(-15, 15)};
      // Toward a random point of the soup's cube, so most rays pass through it.
      Vec3 d = Vec3{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)} - o;
      if (q % 10 == 0) d = {0, -1, 0};  // axis-aligned rays too
      const float max_t = rng.uniform(0, 2);
      float t = 0;
      Vec3 n;
      uint32_t tri = 0;
      const bool hit = mesh_raycast(mesh, o, d, max_t, t, n, tri);
      bool want_hit = false;
      float want_t = 0;
      uint32_t want_tri = 0;
      for (uint32_t k = 0; k < mesh.triangles.size(); ++k) {
        const MeshTriangle& mt = mesh.triangles[k];
        float tk = 0;
        if (ray_triangle(o, d, mesh.vertices[mt.v[0]], mesh.vertices[mt.v[1]],
                         mesh.vertices[mt.v[2]], max_t, one_sided, tk) &&
            (!want_hit || tk < want_t)) {
          want_hit = true;
          want_t = tk;
          want_tri = k;
        }
      }
      ASSERT_EQ(hit, want_hit) << q;
      if (!hit) continue;
      ++hits;
      EXPECT_EQ(t, want_t);
      EXPECT_EQ(tri, want_tri);
      EXPECT_LT(dot(n, d), 0.0f);
      if (one_sided) {
        EXPECT_EQ(n, mesh.triangles[tri].normal);
      }
    }
    EXPECT_GT(hits, 80);
  }
}

// The signed distance's magnitude, nearest point and triangle tie-break
// against every triangle of random soups: the tree walk skips no triangle
// that could win, so the answer is the brute force's to the bit.
TEST(Mesh, SignedDistanceMagnitudeMatchesBruteForce) {
  test::Rng rng{5};
  for (uint32_t n : {1u, 17u, 300u, 2000u}) {
    const TriangleMesh mesh = test::build_ok(random_soup(rng, n));
    for (int q = 0; q < 200; ++q) {
      const float r = q % 4 == 0 ? 60.0f : 12.0f;  // some far outside the soup
      const Vec3 at{rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r)};
      const SurfaceDistance got = mesh_signed_distance(mesh, at);
      PointTriangleClosest want;
      for (uint32_t t = 0; t < n; ++t) {
        Vec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = mesh.vertices[mesh.triangles[t].v[k]];
        const PointTriangleClosest c = closest_point_triangle(at, p);
        if (t == 0 || c.distance_sq < want.distance_sq) want = c;
      }
      EXPECT_EQ(std::fabs(got.distance), std::sqrt(want.distance_sq)) << n << " " << q;
      EXPECT_EQ(got.point, want.point) << n << " " << q;
    }
  }
}

TEST(Mesh, OneSidedRayIgnoresBackFaces) {
  const GridMesh g = make_grid(2, 1.0f, {}, [](float, float) { return 0.0f; });
  const TriangleMesh one = test::build_ok(g, true);
  const TriangleMesh two = test::build_ok(g, false);
  float t = 0;
  Vec3 n;
  uint32_t tri = 0;
  EXPECT_TRUE(mesh_raycast(one, {0.3f, 1, 0.6f}, {0, -1, 0}, 5, t, n, tri));
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_EQ(n, (Vec3{0, 1, 0}));
  // Through the diagonal shared by triangles 0 and 1: the lower index.
  ASSERT_TRUE(mesh_raycast(one, {0.5f, 1, 0.5f}, {0, -2, 0}, 5, t, n, tri));
  EXPECT_EQ(tri, 0u);
  EXPECT_EQ(t, 0.5f);
  EXPECT_FALSE(mesh_raycast(one, {0.3f, -1, 0.6f}, {0, 1, 0}, 5, t, n, tri));
  ASSERT_TRUE(mesh_raycast(two, {0.3f, -1, 0.6f}, {0, 1, 0}, 5, t, n, tri));
  EXPECT_EQ(n, (Vec3{0, -1, 0}));
}

// Front bits of the edge of triangle t running between vertices a and b.
uint32_t edge_bit(const TriangleMesh& m, uint32_t t, uint32_t a, uint32_t b, int shift) {
  const MeshTriangle& tri = m.triangles[t];
  for (uint32_t e = 0; e < 3; ++e) {
    const uint32_t p = tri.v[e];
    const uint32_t q = tri.v[(e + 1) % 3];
    if ((p == a && q == b) || (p == b && q == a)) return (tri.active_edges >> (e + shift)) & 1u;
  }
  ADD_FAILURE() << "no such edge";
  return 0;
}

TEST(Mesh, FlatGridInternalEdgesInactive) {
  const uint32_t n = 4;
  const GridMesh g = make_grid(n, 0.5f, {-1, 0, -1}, [](float, float) { return 0.0f; });
  const TriangleMesh m = test::build_ok(g);
  for (uint32_t t = 0; t < m.triangles.size(); ++t) {
    const MeshTriangle& tri = m.triangles[t];
    EXPECT_EQ(tri.normal, (Vec3{0, 1, 0}));
    for (uint32_t e = 0; e < 3; ++e) {
      const Vec3 a = m.vertices[tri.v[e]];
      const Vec3 b = m.vertices[tri.v[(e + 1) % 3]];
      // A boundary edge lies on the grid's border along its whole length.
      const bool boundary = (a.x == -1 && b.x == -1) || (a.x == 1 && b.x == 1) ||
                            (a.z == -1 && b.z == -1) || (a.z == 1 && b.z == 1);
      const uint32_t front = (tri.active_edges >> e) & 1u;
      const uint32_t back = (tri.active_edges >> (e + 3)) & 1u;
      EXPECT_EQ(front, boundary ? 1u : 0u) << t << " " << e;
      EXPECT_EQ(back, boundary ? 1u : 0u) << t << " " << e;
    }
  }
}

TEST(Mesh, RidgeActiveValleyInactive) {
  // Two quads meeting along x = 0, folded 20 degrees-ish either way.
  for (float fold : {-0.3f, 0.3f}) {
    const std::vector<Vec3> v{{-1, -fold, 0}, {0, 0, 0}, {1, -fold, 0},
                              {-1, -fold, 1}, {0, 0, 1}, {1, -fold, 1}};
    // Triangles (0,3,4) (0,4,1) on the left, (1,4,5) (1,5,2) on the right.
    const std::vector<uint32_t> idx{0, 3, 4, 0, 4, 1, 1, 4, 5, 1, 5, 2};
    auto m = build_mesh(v, idx, false);
    ASSERT_TRUE(m.ok());
    const bool ridge = fold > 0;  // outer vertices lower: a convex ridge
    // The ridge line is the edge 1-4, shared by triangles 1 and 2.
    EXPECT_EQ(edge_bit(*m, 1, 1, 4, 0), ridge ? 1u : 0u);
    EXPECT_EQ(edge_bit(*m, 2, 1, 4, 0), ridge ? 1u : 0u);
    EXPECT_EQ(edge_bit(*m, 1, 1, 4, 3), ridge ? 0u : 1u);
    EXPECT_EQ(edge_bit(*m, 2, 1, 4, 3), ridge ? 0u : 1u);
    // The diagonals within each flat side stay inactive both ways.
    EXPECT_EQ(edge_bit(*m, 0, 0, 4, 0), 0u);
    EXPECT_EQ(edge_bit(*m, 0, 0, 4, 3), 0u);
  }
  // A fold below kFlatEdgeSin counts as flat.
  const float tiny = 2e-4f;
  const std::vector<Vec3> v{{-1, -tiny, 0}, {0, 0, 0}, {1, -tiny, 0},
                            {-1, -tiny, 1}, {0, 0, 1}, {1, -tiny, 1}};
  auto m = build_mesh(v, std::vector<uint32_t>{0, 3, 4, 0, 4, 1, 1, 4, 5, 1, 5, 2}, false);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(edge_bit(*m, 1, 1, 4, 0), 0u);
}

}  // namespace
}  // namespace rwd::sim::d3
