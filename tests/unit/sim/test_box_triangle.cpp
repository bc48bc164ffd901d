// SPDX-License-Identifier: MIT
// A box against a triangle by separating axes (d3/box_triangle.h), checked
// against GJK and EPA over random poses: the same overlap, the same depth
// (EPA's is exact for two polytopes), a gap never beyond GJK's distance and
// often equal to it, and witness points that lie on the shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "d3/box_triangle.h"
#include "mesh_test_shapes.h"

namespace rwd::sim::d3 {
namespace {

using test::BoxProxy;
using test::make_box;

Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return normalize(Quat{n(rng), n(rng), n(rng), n(rng)});
}

TriangleRef make_triangle(Vec3 a, Vec3 b, Vec3 c) {
  TriangleRef t;
  t.p[0] = a;
  t.p[1] = b;
  t.p[2] = c;
  t.normal = normalize_or_zero(cross(b - a, c - a));
  return t;
}

BoxFrame frame_of(const BoxProxy& box, Vec3 half) {
  return {box.proxy.position, {box.proxy.axes.c0, box.proxy.axes.c1, box.proxy.axes.c2}, half};
}

// Distance from p to the box (0 inside).
float box_distance(const BoxFrame& f, Vec3 p) {
  const Vec3 d = p - f.center;
  const float h[3] = {f.half.x, f.half.y, f.half.z};
  float sq = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float over = std::fabs(dot(d, f.axes[k])) - h[k];
    if (over > 0.0f) sq += over * over;
  }
  return std::sqrt(sq);
}

TEST(BoxTriangle, AgreesWithGjkAndEpaOverRandomPoses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_real_distribution<float> size(0.05f, 0.6f);
  int overlapping = 0;
  int apart = 0;
  int exact = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Vec3 half{size(rng), size(rng), size(rng)};
    BoxProxy box;
    make_box(box, half, {u(rng) * 0.8f, u(rng) * 0.8f, u(rng) * 0.8f}, random_rotation(rng));
    const TriangleRef tri =
        make_triangle({u(rng), u(rng) * 0.3f, u(rng)}, {u(rng), u(rng) * 0.3f, u(rng)},
                      {u(rng), u(rng) * 0.3f, u(rng)});
    if (!(length(cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0])) > 1e-3f)) continue;
    const BoxFrame f = frame_of(box, half);
    const BoxTriangleFeatures bt = box_triangle_features(f, tri, 1000.0f);
    ConvexProxy t;
    t.points = tri.p;
    t.count = 3;
    const GjkOutput g = gjk_distance(t, box.proxy);
    if (g.overlap) {
      const EpaOutput e = epa_penetration(t, box.proxy, g.simplex);
      if (!e.converged || e.depth < 1e-4f) continue;  // touching: either answer
      ASSERT_TRUE(bt.overlap) << trial;
      EXPECT_NEAR(-bt.separation, e.depth, 2e-4f + 1e-3f * e.depth) << trial;
      ++overlapping;
    } else {
      if (g.distance < 1e-4f) continue;
      ASSERT_FALSE(bt.overlap) << trial;
      EXPECT_LE(bt.separation, g.distance + 1e-5f) << trial;
      EXPECT_GE(bt.separation, 0.0f) << trial;
      // The witnesses lie on the shapes, at least the gap apart.
      EXPECT_LT(box_distance(f, bt.on_box), 1e-4f) << trial;
      EXPECT_NEAR(dot(bt.on_triangle - tri.p[0], tri.normal), 0.0f, 1e-4f) << trial;
      EXPECT_GE(length(bt.on_box - bt.on_triangle), bt.separation - 1e-4f) << trial;
      // A face axis whose witness lands inside the other shape's face
      // measures the true distance.
      if (std::fabs(bt.separation - g.distance) < 1e-5f) ++exact;
      ++apart;
    }
    EXPECT_NEAR(length(bt.normal), 1.0f, 1e-5f) << trial;
  }
  // Enough of each kind to mean something.
  EXPECT_GT(overlapping, 300);
  EXPECT_GT(apart, 300);
  EXPECT_GT(exact, apart / 3);
}

TEST(BoxTriangle, FlatBoxOnTriangleGetsItsNormal) {
  BoxProxy box;
  const Vec3 half{0.2f, 0.2f, 0.2f};
  make_box(box, half, {0.0f, 0.19f, 0.0f});
  const TriangleRef tri = make_triangle({-1, 0, -1}, {0, 0, 1}, {1, 0, -1});
  const BoxTriangleFeatures bt = box_triangle_features(frame_of(box, half), tri, 1.0f);
  EXPECT_TRUE(bt.overlap);
  EXPECT_NEAR(bt.separation, -0.01f, 1e-6f);
  EXPECT_NEAR(bt.normal.y, 1.0f, 1e-6f);
  // Far apart: the search stops at the first axis beyond reach.
  make_box(box, half, {0.0f, 5.0f, 0.0f});
  const BoxTriangleFeatures far = box_triangle_features(frame_of(box, half), tri, 0.02f);
  EXPECT_FALSE(far.overlap);
  EXPECT_GT(far.separation, 0.02f);
}

}  // namespace
}  // namespace rwd::sim::d3
