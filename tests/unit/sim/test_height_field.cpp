// SPDX-License-Identifier: MIT
// Height fields: validation, the triangles against a mesh built from the
// same grid (corners, normals and active edges), the box query and the ray
// walk against brute force, holes, the signed distance against brute force,
// and a sphere on a slope at the analytic distance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "d3/height_field.h"
#include "d3/manifold_triangles.h"
#include "d3/triangle_closest.h"
#include "mesh_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

std::string build_error(uint32_t rows, uint32_t cols, Vec3 scale, const std::vector<float>& h,
                        const std::vector<uint8_t>& holes = {}) {
  auto hf = build_height_field(rows, cols, scale, h, holes);
  EXPECT_FALSE(hf.ok());
  if (hf.ok()) return "";
  EXPECT_EQ(hf.status().code(), ErrorCode::kInvalidArgument);
  return hf.status().message();
}

TEST(HeightField, RefusesBadInput) {
  const std::vector<float> h4(4, 0.0f);
  EXPECT_NE(build_error(1, 4, {1, 1, 1}, h4).find("2..4096"), std::string::npos);
  EXPECT_NE(build_error(2, 4097, {1, 1, 1}, h4).find("2..4096"), std::string::npos);
  EXPECT_NE(build_error(2, 3, {1, 1, 1}, h4).find("4 heights"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {0, 1, 1}, h4).find("scale"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {1, -1, 1}, h4).find("scale"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {1, 1, INFINITY}, h4).find("scale"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {2e5f, 1, 1}, h4).find("extent"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {1, 1, 1}, h4, {0, 0}).find("hole flags"), std::string::npos);
  EXPECT_NE(build_error(2, 2, {1, 1, 1}, h4, {2}).find("cell 0"), std::string::npos);
  std::vector<float> bad = h4;
  bad[3] = NAN;
  EXPECT_NE(build_error(2, 2, {1, 1, 1}, bad).find("sample 3"), std::string::npos);
  bad[3] = 2e4f;
  EXPECT_NE(build_error(2, 2, {1, 10, 1}, bad).find("sample 3"), std::string::npos);
  EXPECT_TRUE(build_height_field(2, 2, {1, 10, 1}, h4, {}).ok());
}

// A bumpy field of n x n samples with some holes.
HeightField bumpy(uint32_t n, Vec3 scale, bool with_holes, uint64_t seed) {
  test::Rng rng{seed};
  std::vector<float> h(n * n);
  for (float& v : h) v = rng.uniform(-1.0f, 1.0f);
  std::vector<uint8_t> holes;
  if (with_holes) {
    holes.resize((n - 1) * (n - 1));
    for (uint8_t& c : holes) c = rng.next() % 7 == 0 ? 1 : 0;
  }
  auto hf = build_height_field(n, n, scale, h, holes);
  EXPECT_TRUE(hf.ok());
  return std::move(*hf);
}

TEST(HeightField, TrianglesMatchEquivalentMesh) {
  // The mesh of the same grid (no holes): same corners, normals, and the
  // same active edges and neighbours' corners computed the mesh's way.
  const uint32_t n = 9;
  const HeightField hf = bumpy(n, {0.5f, 0.3f, 0.7f}, false, 5);
  std::vector<Vec3> v;
  for (uint32_t r = 0; r < n; ++r) {
    for (uint32_t c = 0; c < n; ++c) v.push_back(height_field_point(hf, r, c));
  }
  std::vector<uint32_t> idx;
  for (uint32_t r = 0; r + 1 < n; ++r) {
    for (uint32_t c = 0; c + 1 < n; ++c) {
      const uint32_t p00 = r * n + c;
      idx.insert(idx.end(), {p00, p00 + n, p00 + n + 1, p00, p00 + n + 1, p00 + 1});
    }
  }
  auto mesh = build_mesh(v, idx, false);
  ASSERT_TRUE(mesh.ok());
  for (uint32_t id = 0; id < mesh->triangles.size(); ++id) {
    const TriangleRef a = height_field_triangle(hf, id);
    const TriangleRef b = mesh_triangle(*mesh, id);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.p[k], b.p[k]);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.active_edges, b.active_edges) << id;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.across[k], b.across[k]) << id;
    EXPECT_GT(a.normal.y, 0.0f);
  }
}

TEST(HeightField, FlatInteriorEdgesInactiveHolesAreBoundaries) {
  const uint32_t n = 5;
  std::vector<float> h(n * n, 2.0f);
  std::vector<uint8_t> holes((n - 1) * (n - 1), 0);
  holes[1 * (n - 1) + 1] = 1;  // cell (1, 1)
  auto hf = build_height_field(n, n, {1, 1, 1}, h, holes);
  ASSERT_TRUE(hf.ok());
  // Cell (2, 2) is interior and not next to the hole: nothing active.
  const uint32_t cell = 2 * (n - 1) + 2;
  EXPECT_EQ(height_field_triangle(*hf, cell * 2).active_edges, 0);
  EXPECT_EQ(height_field_triangle(*hf, cell * 2 + 1).active_edges, 0);
  // Cell (1, 2), right of the hole: its half 0's left edge (edge 0) borders it.
  const uint32_t right = 1 * (n - 1) + 2;
  EXPECT_EQ(height_field_triangle(*hf, right * 2).active_edges, kBoundaryEdgeBits);
  // Cell (0, 0): half 1's bottom edge (edge 2) and half 0's left edge are
  // the border.
  EXPECT_EQ(height_field_triangle(*hf, 1).active_edges, kBoundaryEdgeBits << 2);
  EXPECT_EQ(height_field_triangle(*hf, 0).active_edges, kBoundaryEdgeBits);
  // The query skips the hole.
  std::vector<uint32_t> ids;
  height_field_query(*hf, {{1.2f, 0, 1.2f}, {1.8f, 5, 1.8f}},
                     [&](const TriangleRef& t) { ids.push_back(t.id); });
  EXPECT_TRUE(ids.empty());
}

TEST(HeightField, RidgeActiveValleyInactive) {
  // Three samples across x: middle up (ridge) or down (valley); the edge
  // x = 1 between cell columns 0 and 1.
  for (float mid : {0.5f, -0.5f}) {
    const std::vector<float> h{0, mid, 0, 0, mid, 0};
    auto hf = build_height_field(2, 3, {1, 1, 1}, h, {});
    ASSERT_TRUE(hf.ok());
    // Cell 0 half 1 edge 1 (right) and cell 1 half 0 edge 0 (left).
    const uint8_t a = height_field_triangle(*hf, 1).active_edges;
    const uint8_t b = height_field_triangle(*hf, 2).active_edges;
    const bool ridge = mid > 0;
    EXPECT_EQ((a >> 1) & 1, ridge ? 1 : 0);
    EXPECT_EQ((b >> 0) & 1, ridge ? 1 : 0);
    EXPECT_EQ((a >> 4) & 1, ridge ? 0 : 1);
    EXPECT_EQ((b >> 3) & 1, ridge ? 0 : 1);
  }
}

TEST(HeightField, QueryMatchesBruteForce) {
  const HeightField hf = bumpy(33, {0.5f, 2.0f, 0.25f}, true, 9);
  test::Rng rng{1};
  const uint32_t tri_count = 2 * 32 * 32;
  for (int q = 0; q < 300; ++q) {
    const Vec3 c{rng.uniform(-2, 18), rng.uniform(-3, 3), rng.uniform(-2, 10)};
    const Vec3 e{rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(0, 2)};
    const Aabb box{c - e, c + e};
    std::vector<uint32_t> got;
    height_field_query(hf, box, [&](const TriangleRef& t) { got.push_back(t.id); });
    std::vector<uint32_t> want;
    for (uint32_t id = 0; id < tri_count; ++id) {
      if (height_field_is_hole(hf, id >> 1)) continue;
      Vec3 p[3];
      height_field_corners(hf, id, p);
      if (overlaps({min(min(p[0], p[1]), p[2]), max(max(p[0], p[1]), p[2])}, box)) {
        want.push_back(id);
      }
    }
    EXPECT_EQ(got, want);  // ascending id
  }
}

TEST(HeightField, RaycastMatchesBruteForce) {
  const HeightField hf = bumpy(41, {0.5f, 1.5f, 0.75f}, true, 21);
  test::Rng rng{2};
  const uint32_t tri_count = 2 * 40 * 40;
  int hits = 0;
  for (int q = 0; q < 1500; ++q) {
    const Vec3 o{rng.uniform(-5, 25), rng.uniform(-3, 6), rng.uniform(-5, 35)};
    const Vec3 target{rng.uniform(0, 20), rng.uniform(-1.5f, 1.5f), rng.uniform(0, 30)};
    Vec3 d = target - o;
    if (q % 7 == 0) d = {0, -1, 0};
    if (q % 11 == 0) d.z = 0;
    if (q % 13 == 0) d.x = 0;
    const float max_t = q % 5 == 0 ? 1e30f : rng.uniform(0, 2);
    float t = 0;
    Vec3 n;
    uint32_t id = 0;
    const bool hit = height_field_raycast(hf, o, d, max_t, t, n, id);
    bool want_hit = false;
    float want_t = 0;
    uint32_t want_id = 0;
    for (uint32_t k = 0; k < tri_count; ++k) {
      if (height_field_is_hole(hf, k >> 1)) continue;
      Vec3 p[3];
      height_field_corners(hf, k, p);
      float tk = 0;
      if (ray_triangle(o, d, p[0], p[1], p[2], max_t, false, tk) && (!want_hit || tk < want_t)) {
        want_hit = true;
        want_t = tk;
        want_id = k;
      }
    }
    ASSERT_EQ(hit, want_hit) << q;
    if (!hit) continue;
    ++hits;
    EXPECT_EQ(t, want_t) << q;
    EXPECT_EQ(id, want_id) << q;
    EXPECT_LE(dot(n, d), 0.0f);
  }
  EXPECT_GT(hits, 300);
}

// The signed distance against every triangle (magnitude and nearest point
// to the bit: the ring walk skips no cell that could win) and its sign
// against a ray straight down from above the field: under the surface
// exactly when the ray meets it above the point. Points range from under
// the field to well beside and above it.
TEST(HeightField, SignedDistanceMatchesBruteForce) {
  const HeightField hf = bumpy(25, {0.5f, 1.5f, 0.75f}, true, 31);
  test::Rng rng{4};
  const uint32_t tri_count = 2 * 24 * 24;
  int under = 0;
  for (int q = 0; q < 1000; ++q) {
    const float far = q % 5 == 0 ? 40.0f : 2.0f;
    const Vec3 at{rng.uniform(-far, 12.0f + far), rng.uniform(-4.0f, 4.0f) * (far / 2.0f),
                  rng.uniform(-far, 18.0f + far)};
    SurfaceDistance got;
    ASSERT_TRUE(height_field_signed_distance(hf, at, got));
    PointTriangleClosest want;
    bool any = false;
    for (uint32_t k = 0; k < tri_count; ++k) {
      if (height_field_is_hole(hf, k >> 1)) continue;
      Vec3 p[3];
      height_field_corners(hf, k, p);
      const PointTriangleClosest c = closest_point_triangle(at, p);
      if (!any || c.distance_sq < want.distance_sq) want = c;
      any = true;
    }
    EXPECT_EQ(std::fabs(got.distance), std::sqrt(want.distance_sq)) << q;
    EXPECT_EQ(got.point, want.point) << q;
    if (std::fabs(got.distance) < 1e-4f) continue;  // on the surface: either sign
    const Vec3 top{at.x, hf.bounds.upper.y + 1.0f, at.z};
    float t = 0;
    Vec3 n;
    uint32_t id = 0;
    const bool below =
        height_field_raycast(hf, top, {0, -1, 0}, 1e30f, t, n, id) && top.y - t > at.y;
    EXPECT_EQ(got.distance < 0.0f, below) << q << ": " << got.distance;
    under += below ? 1 : 0;
  }
  EXPECT_GT(under, 150);
  // A field of holes only has no surface.
  const std::vector<float> h(4, 0.0f);
  const std::vector<uint8_t> holes = {1};
  const HeightField none = *build_height_field(2, 2, {1, 1, 1}, h, holes);
  SurfaceDistance d;
  EXPECT_FALSE(height_field_signed_distance(none, {0.5f, 0.0f, 0.5f}, d));
}

TEST(HeightField, SphereOnSlopeAtAnalyticDistance) {
  // The plane y = 0.5 x (scale.y = 1): unit normal (-0.5, 1, 0) / |.|.
  const uint32_t n = 11;
  std::vector<float> h(n * n);
  for (uint32_t r = 0; r < n; ++r) {
    for (uint32_t c = 0; c < n; ++c) h[r * n + c] = 0.5f * static_cast<float>(c);
  }
  auto hf = build_height_field(n, n, {1, 1, 1}, h, {});
  ASSERT_TRUE(hf.ok());
  const Vec3 normal = normalize_or_zero(Vec3{-0.5f, 1, 0});
  const float radius = 0.5f;
  for (float gap : {-0.05f, 0.0f, 0.01f}) {
    const Vec3 foot{4.3f, 0.5f * 4.3f, 5.6f};
    const Vec3 center = foot + normal * (radius + gap);
    const Vec3 core{};
    ConvexProxy sphere;
    sphere.points = &core;
    sphere.count = 1;
    sphere.radius = radius;
    sphere.position = center;
    const auto tris = test::gather(*hf, test::proxy_box(sphere, 0.02f));
    Manifold m;
    collide_convex_triangles(sphere, tris, false, 0.02f, m);
    ASSERT_EQ(m.point_count, 1u) << gap;
    EXPECT_NEAR(m.normal.x, normal.x, 1e-6f);
    EXPECT_NEAR(m.normal.y, normal.y, 1e-6f);
    EXPECT_NEAR(m.normal.z, 0.0f, 1e-6f);
    EXPECT_NEAR(m.points[0].separation, gap, 1e-5f);
    const Vec3 mid = foot + normal * (0.5f * gap);
    EXPECT_NEAR(m.points[0].point.x, mid.x, 1e-5f);
    EXPECT_NEAR(m.points[0].point.y, mid.y, 1e-5f);
    EXPECT_NEAR(m.points[0].point.z, mid.z, 1e-5f);
  }
}

}  // namespace
}  // namespace rwd::sim::d3
