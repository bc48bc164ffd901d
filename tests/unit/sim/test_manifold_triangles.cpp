// SPDX-License-Identifier: MIT
// Convex shapes against triangles: a box resting on a quad, on a grid
// mesh, on a height field and on a grid finer than the contact cap (four
// corners, face normal, the box-on-plane depth); sliding across internal
// edges (the normal stays the face normal); deep overlap (EPA and the
// segment test); spheres on convex ridges (edge normal) and in valleys;
// one-sided meshes; capsules lying flat (two points); sweeps onto a floor
// at the analytic fraction; and bit-identical, order-free results.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "d3/manifold_triangles.h"
#include "mesh_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using test::BoxProxy;
using test::make_box;
using test::make_grid;

constexpr float kSpec = 0.02f;

Quat yaw(float half_angle_sin, float half_angle_cos) {
  return normalize(Quat{0.0f, half_angle_sin, 0.0f, half_angle_cos});
}

template <class Source>
Manifold collide(const Source& source, const ConvexProxy& shape, bool one_sided,
                 float spec = kSpec) {
  const auto tris = test::gather(source, test::proxy_box(shape, spec));
  Manifold m;
  collide_convex_triangles(shape, tris, one_sided, spec, m);
  return m;
}

// The manifold holds exactly the box's four lowest corners (any order),
// each with the expected separation and midway between the surfaces of a
// floor at y = floor_y.
void expect_bottom_corners(const Manifold& m, const BoxProxy& box, float floor_y, float sep,
                           float tol = 2e-5f) {
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.x, 0.0f, 1e-6f);
  EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(m.normal.z, 0.0f, 1e-6f);
  bool used[4] = {false, false, false, false};
  for (int i = 0; i < 8; ++i) {
    if (box.corners[i].y > 0) continue;
    const Vec3 w = box.proxy.position + box.proxy.axes * box.corners[i];
    bool found = false;
    for (uint32_t k = 0; k < 4 && !found; ++k) {
      const Vec3 p = m.points[k].point;
      if (!used[k] && std::fabs(p.x - w.x) < tol && std::fabs(p.z - w.z) < tol) {
        used[k] = true;
        found = true;
        EXPECT_NEAR(m.points[k].separation, sep, 1e-5f);
        EXPECT_NEAR(p.y, floor_y + 0.5f * sep, 1e-5f);
      }
    }
    EXPECT_TRUE(found) << "corner " << i << " at " << w.x << " " << w.z;
  }
}

TEST(ManifoldTriangles, BoxOnQuad) {
  const std::vector<Vec3> v{{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}};
  auto mesh = build_mesh(v, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, true);
  ASSERT_TRUE(mesh.ok());
  for (float depth : {0.01f, 0.0f, -0.015f}) {
    for (float s : {0.0f, 0.2f, 0.5f}) {
      BoxProxy box;
      make_box(box, {0.5f, 0.4f, 0.3f}, {0.3f, 0.4f - depth, -0.2f}, yaw(s, 1.0f));
      const Manifold m = collide(*mesh, box.proxy, true);
      expect_bottom_corners(m, box, 0.0f, -depth);
    }
  }
  // Beyond the speculative distance: nothing.
  BoxProxy box;
  make_box(box, {0.5f, 0.4f, 0.3f}, {0.3f, 0.4f + 0.03f, -0.2f});
  EXPECT_EQ(collide(*mesh, box.proxy, true).point_count, 0u);
}

TEST(ManifoldTriangles, BoxOnGridMeshAndHeightField) {
  // 10 x 10 cells of 0.7 m at y = 1 (mesh) and y = 1 (height field).
  const auto g = make_grid(10, 0.7f, {0, 1, 0}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  std::vector<float> h(11 * 11, 2.0f);
  auto hf = build_height_field(11, 11, {0.7f, 0.5f, 0.7f}, h, {});
  ASSERT_TRUE(hf.ok());
  test::Rng rng{17};
  for (int i = 0; i < 60; ++i) {
    // Drawn one per statement: the order of function arguments is unspecified.
    const float depth = rng.uniform(-0.015f, 0.05f);
    const Vec3 at{rng.uniform(1.5f, 5.5f), 1.3f - depth, rng.uniform(1.5f, 5.5f)};
    const Quat turn = yaw(rng.uniform(-1, 1), 1.0f);
    BoxProxy box;
    make_box(box, {0.6f, 0.3f, 0.45f}, at, turn);
    expect_bottom_corners(collide(mesh, box.proxy, false), box, 1.0f, -depth);
    expect_bottom_corners(collide(*hf, box.proxy, false), box, 1.0f, -depth);
  }
}

TEST(ManifoldTriangles, BoxOnGridFinerThanTheCap) {
  // A 3 m box on 0.1 m cells: about 1800 triangles touch, far beyond
  // kMaxContactTriangles; the corners still come through.
  const auto g = make_grid(50, 0.1f, {0, 0, 0}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  std::vector<float> h(51 * 51, 0.0f);
  auto hf = build_height_field(51, 51, {0.1f, 1.0f, 0.1f}, h, {});
  ASSERT_TRUE(hf.ok());
  test::Rng rng{5};
  for (int i = 0; i < 10; ++i) {
    BoxProxy box;
    const Vec3 at{rng.uniform(2.4f, 2.6f), 0.49f, rng.uniform(2.4f, 2.6f)};
    make_box(box, {1.5f, 0.5f, 1.5f}, at, yaw(rng.uniform(-0.2f, 0.2f), 1.0f));
    const auto tris = test::gather(mesh, test::proxy_box(box.proxy, kSpec));
    EXPECT_GT(tris.size(), 1000u);
    expect_bottom_corners(collide(mesh, box.proxy, false), box, 0.0f, -0.01f);
    expect_bottom_corners(collide(*hf, box.proxy, false), box, 0.0f, -0.01f);
  }
}

TEST(ManifoldTriangles, HullPrismOnItsCap) {
  // A hexagonal prism (12 core points) standing on a grid: its cap's
  // outline is clipped per triangle and reduced to four of its corners.
  Vec3 pts[12];
  for (int i = 0; i < 6; ++i) {
    const float c[6] = {1.0f, 0.5f, -0.5f, -1.0f, -0.5f, 0.5f};
    const float s[6] = {0.0f, 0.8660254f, 0.8660254f, 0.0f, -0.8660254f, -0.8660254f};
    pts[i] = {0.6f * c[i], -0.3f, 0.6f * s[i]};
    pts[i + 6] = {0.6f * c[i], 0.3f, 0.6f * s[i]};
  }
  ConvexProxy hull;
  hull.points = pts;
  hull.count = 12;
  hull.position = {0.37f, 0.295f, -0.21f};
  const auto g = make_grid(8, 0.5f, {-2, 0, -2}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  const Manifold m = collide(mesh, hull, false);
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_EQ(m.normal, (Vec3{0, 1, 0}));
  for (uint32_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(m.points[k].separation, -0.005f, 1e-6f);
    EXPECT_LT(m.points[k].feature_id & 31u, 6u);  // a bottom corner
    const Vec3 d = m.points[k].point - hull.position;
    EXPECT_NEAR(d.x * d.x + d.z * d.z, 0.36f, 1e-5f);
  }
}

TEST(ManifoldTriangles, SlidingAcrossInternalEdgesKeepsFaceNormal) {
  const auto g = make_grid(10, 1.0f, {-5, 0, -5}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  // Upright and turned boxes, slightly sunk, some tipped a little (one
  // edge deeper), swept across cell edges and diagonals.
  const Quat tips[] = {Quat{}, yaw(0.3f, 1.0f), normalize(Quat{0.0f, 0.2f, 0.03f, 1.0f}),
                       normalize(Quat{0.02f, 0.0f, 0.0f, 1.0f})};
  int checked = 0;
  for (const Quat& q : tips) {
    for (float x = -1.0f; x <= 1.0f; x += 0.0131f) {
      BoxProxy box;
      make_box(box, {0.5f, 0.5f, 0.5f}, {x, 0.5f - 0.004f, 0.37f * x + 0.02f}, q);
      // Sink the lowest corner 4 mm.
      float low = 1e9f;
      for (const Vec3& c : box.corners) low = std::fmin(low, (box.proxy.axes * c).y);
      box.proxy.position.y = -low - 0.004f;
      const Manifold m = collide(mesh, box.proxy, false);
      ASSERT_GE(m.point_count, 1u) << x;
      ASSERT_EQ(m.normal, (Vec3{0, 1, 0})) << x;
      if (q.x == 0.0f && q.z == 0.0f) {  // upright: all four corners
        EXPECT_EQ(m.point_count, 4u) << x;
      }
      for (uint32_t k = 0; k < m.point_count; ++k) EXPECT_GE(m.points[k].separation, -0.0041f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 400);
  // A sphere rolling across: one point, right under it.
  for (float x = -1.0f; x <= 1.0f; x += 0.0173f) {
    const Vec3 core{};
    ConvexProxy sphere;
    sphere.points = &core;
    sphere.count = 1;
    sphere.radius = 0.3f;
    sphere.position = {x, 0.299f, 0.5f * x};
    const Manifold m = collide(mesh, sphere, false);
    ASSERT_EQ(m.point_count, 1u) << x;
    ASSERT_EQ(m.normal, (Vec3{0, 1, 0}));
    EXPECT_NEAR(m.points[0].separation, -0.001f, 1e-6f);
    EXPECT_NEAR(m.points[0].point.x, x, 1e-6f);
  }
}

TEST(ManifoldTriangles, DeepOverlapPushesOutThroughTheFace) {
  const auto g = make_grid(6, 1.0f, {-3, 0, -3}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  // EPA per triangle: a box sunk 0.2 m.
  BoxProxy box;
  make_box(box, {0.5f, 0.5f, 0.5f}, {0.1f, 0.3f, -0.2f}, yaw(0.4f, 1.0f));
  expect_bottom_corners(collide(mesh, box.proxy, false), box, 0.0f, -0.2f);
  // The segment test: an upright capsule through the floor.
  const Vec3 ends[2] = {{0, -0.5f, 0}, {0, 0.5f, 0}};
  ConvexProxy capsule;
  capsule.points = ends;
  capsule.count = 2;
  capsule.radius = 0.25f;
  capsule.position = {0.3f, 0.2f, 0.45f};
  const Manifold m = collide(mesh, capsule, false);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.normal, (Vec3{0, 1, 0}));
  EXPECT_NEAR(m.points[0].separation, -0.55f, 1e-5f);
  // A sphere whose centre lies in the floor.
  const Vec3 core{};
  ConvexProxy sphere;
  sphere.points = &core;
  sphere.count = 1;
  sphere.radius = 0.25f;
  sphere.position = {0.3f, 0.0f, 0.45f};
  const Manifold s = collide(mesh, sphere, true);
  ASSERT_EQ(s.point_count, 1u);
  EXPECT_EQ(s.normal, (Vec3{0, 1, 0}));
  EXPECT_NEAR(s.points[0].separation, -0.25f, 1e-6f);
}

TEST(ManifoldTriangles, CapsuleLyingFlatGetsBothEnds) {
  const auto g = make_grid(6, 1.0f, {-3, 0, -3}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  const Vec3 ends[2] = {{-0.8f, 0, 0}, {0.8f, 0, 0}};
  ConvexProxy capsule;
  capsule.points = ends;
  capsule.count = 2;
  capsule.radius = 0.2f;
  capsule.position = {0.15f, 0.19f, 0.33f};
  capsule.axes = mat3_from_quat(yaw(0.3f, 1.0f));
  const Manifold m = collide(mesh, capsule, false);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_EQ(m.normal, (Vec3{0, 1, 0}));
  for (uint32_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.points[k].separation, -0.01f, 1e-6f);
    // Each end: core point 0 or 1 of the triangle under it.
    EXPECT_LE(m.points[k].feature_id & 31u, 1u);
  }
  const Vec3 a = capsule.position + capsule.axes * ends[0];
  const Vec3 b = capsule.position + capsule.axes * ends[1];
  const Vec3 p = m.points[0].point;
  const Vec3 q = m.points[1].point;
  const bool direct = std::fabs(p.x - a.x) < 1e-5f && std::fabs(q.x - b.x) < 1e-5f;
  const bool swapped = std::fabs(p.x - b.x) < 1e-5f && std::fabs(q.x - a.x) < 1e-5f;
  EXPECT_TRUE(direct || swapped);
}

// Two planes meeting along the z axis at x = 0, y = 0, sloping by `fold`
// (down on both sides: a convex ridge; up: a concave valley).
TriangleMesh roof(float fold) {
  const std::vector<Vec3> v{{-2, -2 * fold, -2}, {0, 0, -2}, {2, -2 * fold, -2},
                            {-2, -2 * fold, 2},  {0, 0, 2},  {2, -2 * fold, 2}};
  auto m = build_mesh(v, std::vector<uint32_t>{0, 3, 4, 0, 4, 1, 1, 4, 5, 1, 5, 2}, false);
  EXPECT_TRUE(m.ok());
  return std::move(*m);
}

TEST(ManifoldTriangles, RidgeGivesEdgeNormalValleyGivesFaceNormals) {
  const Vec3 core{};
  ConvexProxy sphere;
  sphere.points = &core;
  sphere.count = 1;
  sphere.radius = 0.5f;
  // Over a convex ridge the edge (active) is the closest feature: the
  // normal points from the edge to the centre.
  const TriangleMesh ridge = roof(0.4f);
  sphere.position = {0.0f, 0.49f, 0.3f};
  Manifold m = collide(ridge, sphere, false);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(m.points[0].separation, -0.01f, 1e-6f);
  sphere.position = {0.1f, 0.45f, 0.3f};  // past the ridge, off both faces' prisms
  m = collide(ridge, sphere, false);
  ASSERT_EQ(m.point_count, 1u);
  const Vec3 to_center = normalize_or_zero(Vec3{0.1f, 0.45f, 0.0f});
  EXPECT_NEAR(m.normal.x, to_center.x, 1e-5f);
  EXPECT_NEAR(m.normal.y, to_center.y, 1e-5f);
  EXPECT_NEAR(m.points[0].separation, length(Vec3{0.1f, 0.45f, 0}) - 0.5f, 1e-5f);
  // In a concave valley each face pushes along its own normal; the deeper
  // one wins and the other (33 degrees away) does not join.
  const TriangleMesh valley = roof(-0.3f);
  const Vec3 n_left = normalize_or_zero(Vec3{0.3f, 1.0f, 0.0f});
  sphere.position = Vec3{-0.3f, 0.09f, 0.1f} + n_left * 0.49f;
  m = collide(valley, sphere, false);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.x, n_left.x, 1e-6f);
  EXPECT_NEAR(m.normal.y, n_left.y, 1e-6f);
  EXPECT_NEAR(m.points[0].separation, -0.01f, 1e-5f);
}

TEST(ManifoldTriangles, OneSidedIgnoresShapesBehind) {
  const auto g = make_grid(4, 1.0f, {-2, 0, -2}, [](float, float) { return 0.0f; });
  const TriangleMesh one = test::build_ok(g, true);
  const TriangleMesh two = test::build_ok(g, false);
  const Vec3 core{};
  ConvexProxy sphere;
  sphere.points = &core;
  sphere.count = 1;
  sphere.radius = 0.5f;
  sphere.position = {0.2f, -0.49f, 0.1f};
  EXPECT_EQ(collide(one, sphere, true).point_count, 0u);
  const Manifold m = collide(two, sphere, false);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.normal, (Vec3{0, -1, 0}));
  EXPECT_NEAR(m.points[0].separation, -0.01f, 1e-6f);
  // The same sphere above is seen by both.
  sphere.position.y = 0.49f;
  EXPECT_EQ(collide(one, sphere, true).point_count, 1u);
}

TEST(ManifoldTriangles, SweepOntoFloorAtAnalyticFraction) {
  const auto g = make_grid(8, 0.5f, {-2, 0, -2}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g, true);
  const Vec3 core{};
  ConvexProxy sphere;
  sphere.points = &core;
  sphere.count = 1;
  sphere.radius = 0.5f;
  sphere.position = {0.25f, 3.0f, -0.75f};  // over a shared vertex
  const Vec3 move{0.4f, -4.0f, 0.2f};
  Aabb sweep = test::proxy_box(sphere, 0.0f);
  sweep.lower = sweep.lower + move;
  const auto tris = test::gather(mesh, sweep);
  const TriangleCastOutput c = shape_cast_triangles(sphere, move, tris, true);
  ASSERT_TRUE(c.hit);
  EXPECT_FALSE(c.initially_overlapping);
  EXPECT_NEAR(c.fraction, 2.5f / 4.0f, 1e-5f);
  EXPECT_NEAR(c.normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(c.point.y, 0.0f, 1e-5f);
  EXPECT_NEAR(c.point.x, 0.25f + 0.4f * 0.625f, 1e-4f);
  // The same from below a one-sided floor: no hit; two-sided: the fraction.
  sphere.position.y = -3.0f;
  const Vec3 up{0.4f, 4.0f, 0.2f};
  EXPECT_FALSE(shape_cast_triangles(sphere, up, tris, true).hit);
  const TriangleCastOutput u = shape_cast_triangles(sphere, up, tris, false);
  ASSERT_TRUE(u.hit);
  EXPECT_NEAR(u.fraction, 0.625f, 1e-5f);
  EXPECT_NEAR(u.normal.y, -1.0f, 1e-6f);
  // A box falling flat.
  BoxProxy box;
  make_box(box, {0.3f, 0.3f, 0.3f}, {0.1f, 2.3f, 0.2f});
  const TriangleCastOutput b = shape_cast_triangles(box.proxy, {0, -4, 0}, tris, true);
  ASSERT_TRUE(b.hit);
  EXPECT_NEAR(b.fraction, 0.5f, 1e-5f);
  EXPECT_NEAR(b.normal.y, 1.0f, 1e-5f);
}

bool same_bits(const Manifold& a, const Manifold& b) {
  if (a.point_count != b.point_count || !(a.normal == b.normal)) return false;
  for (uint32_t i = 0; i < a.point_count; ++i) {
    if (std::memcmp(&a.points[i], &b.points[i], sizeof(ManifoldPoint)) != 0) return false;
  }
  return true;
}

TEST(ManifoldTriangles, DeterministicAndOrderFree) {
  const auto g = make_grid(12, 0.4f, {-2.4f, 0, -2.4f}, [](float x, float z) {
    return 0.1f * x * x - 0.05f * z + 0.02f * x * z;
  });
  const TriangleMesh mesh = test::build_ok(g);
  test::Rng rng{99};
  int touching = 0;
  for (int i = 0; i < 200; ++i) {
    BoxProxy box;
    const float x = rng.uniform(-1.5f, 1.5f);
    const float z = rng.uniform(-1.5f, 1.5f);
    const Vec3 half{rng.uniform(0.1f, 0.5f), rng.uniform(0.1f, 0.5f), rng.uniform(0.1f, 0.5f)};
    const float lift = rng.uniform(0.0f, 0.5f);
    const Quat turn = rng.rotation();
    make_box(box, half, {x, 0.1f * x * x - 0.05f * z + 0.02f * x * z + lift, z}, turn);
    auto tris = test::gather(mesh, test::proxy_box(box.proxy, kSpec));
    Manifold a;
    Manifold b;
    Manifold c;
    collide_convex_triangles(box.proxy, tris, false, kSpec, a);
    collide_convex_triangles(box.proxy, tris, false, kSpec, b);
    ASSERT_LE(tris.size(), kMaxContactTriangles);
    std::reverse(tris.begin(), tris.end());
    collide_convex_triangles(box.proxy, tris, false, kSpec, c);
    EXPECT_TRUE(same_bits(a, b));
    EXPECT_TRUE(same_bits(a, c)) << i;
    touching += a.point_count > 0 ? 1 : 0;
    for (uint32_t k = 0; k < a.point_count; ++k) EXPECT_LE(a.points[k].separation, kSpec);
    EXPECT_NEAR(length(a.normal), a.point_count > 0 ? 1.0f : 0.0f, 1e-5f);
  }
  EXPECT_GT(touching, 50);
}

// A box tilted across a terrain fold: it stands on three points (two
// opposite corners of its base and where the base crosses the fold), its
// other two corners lifted a few millimetres. The four points kept must
// include all three it stands on: with only two (the two lifted corners
// taking the other slots) it rests on a line, rocks about it and never
// comes to rest.
TEST(ManifoldTriangles, ReductionKeepsThePointsABodyStandsOn) {
  const TrianglePoint points[] = {
      {{5.2f, 0.0f, 2.8f}, -0.0045f, 1},  // corner, touching
      {{4.8f, 0.0f, 2.4f}, -0.0040f, 2},  // opposite corner, touching
      {{5.2f, 0.0f, 2.7f}, -0.0060f, 3},  // the base's edge over the fold, deepest
      {{4.8f, 0.0f, 2.8f}, 0.0060f, 4},   // lifted corner
      {{5.2f, 0.0f, 2.4f}, 0.0100f, 5},   // lifted corner
      {{5.0f, 0.0f, 2.6f}, 0.0070f, 6},   // inside the base, lifted
  };
  uint32_t chosen[4];
  const uint32_t n = reduce_triangle_points(points, 6, {0.0f, 1.0f, 0.0f}, chosen);
  ASSERT_EQ(n, 4u);
  int touching = 0;
  for (uint32_t k = 0; k < n; ++k) touching += points[chosen[k]].separation <= 0.0f ? 1 : 0;
  EXPECT_EQ(touching, 3);
}

TEST(ManifoldTriangles, FeatureIdsPersistWhileResting) {
  const auto g = make_grid(10, 1.0f, {-5, 0, -5}, [](float, float) { return 0.0f; });
  const TriangleMesh mesh = test::build_ok(g);
  BoxProxy box;
  make_box(box, {0.4f, 0.4f, 0.4f}, {0.3f, 0.395f, 0.2f}, yaw(0.2f, 1.0f));
  const Manifold a = collide(mesh, box.proxy, false);
  box.proxy.position.x += 0.01f;  // a small slide within the same triangles
  box.proxy.position.y += 0.002f;
  const Manifold b = collide(mesh, box.proxy, false);
  ASSERT_EQ(a.point_count, 4u);
  ASSERT_EQ(b.point_count, 4u);
  std::vector<uint32_t> ia, ib;
  for (uint32_t k = 0; k < 4; ++k) {
    ia.push_back(a.points[k].feature_id);
    ib.push_back(b.points[k].feature_id);
    EXPECT_LT(a.points[k].feature_id & 31u, 8u);  // box corners
  }
  std::sort(ia.begin(), ia.end());
  std::sort(ib.begin(), ib.end());
  EXPECT_EQ(ia, ib);
}

}  // namespace
}  // namespace rwd::sim::d3
