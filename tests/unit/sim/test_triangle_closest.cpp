// SPDX-License-Identifier: MIT
// The closed-form closest points of a point or a segment and a triangle
// (d3/triangle_closest.h): hand-computed cases, and random ones against
// GJK on the same cores (distances within 1e-4 of the larger of 1 and the
// distance; both report an overlap for a segment through the triangle); and
// the nearest point of a triangle with its feature against the point core.
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "d3/gjk.h"
#include "d3/triangle_closest.h"
#include "gjk_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace gjk_test;

const Vec3 kTri[3] = {{0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f}};
const Vec3 kDown{0.0f, -1.0f, 0.0f};  // (p1 - p0) x (p2 - p0) points down

TEST(TriangleClosest, PointAboveTheFace) {
  const Vec3 p{0.5f, 1.5f, 0.5f};
  const CoreTriangleClosest c = closest_core_triangle(&p, 1, kTri, kDown);
  EXPECT_FALSE(c.overlap);
  EXPECT_NEAR(c.distance, 1.5f, kTol);
  expect_vec(c.on_tri, {0.5f, 0.0f, 0.5f}, kTol);
  expect_vec(c.normal, {0.0f, 1.0f, 0.0f}, kTol);
}

TEST(TriangleClosest, SegmentPastAnEdgeMeetsTheEdge) {
  // A segment parallel to the hypotenuse, 1 m beyond it and 1 m up.
  const Vec3 s[2] = {{2.5f, 1.0f, 0.5f}, {0.5f, 1.0f, 2.5f}};
  const CoreTriangleClosest c = closest_core_triangle(s, 2, kTri, kDown);
  EXPECT_FALSE(c.overlap);
  const float beyond = std::sqrt(0.5f);  // (1.5,_,1.5) is sqrt(0.5) past x + z = 2
  EXPECT_NEAR(c.distance, std::sqrt(1.0f + beyond * beyond), kTol);
  EXPECT_NEAR(c.on_tri.x + c.on_tri.z, 2.0f, kTol);
  EXPECT_NEAR(c.on_tri.y, 0.0f, kTol);
}

TEST(TriangleClosest, SegmentThroughTheFaceOverlaps) {
  const Vec3 s[2] = {{0.5f, 1.0f, 0.5f}, {0.6f, -1.0f, 0.4f}};
  EXPECT_TRUE(closest_core_triangle(s, 2, kTri, kDown).overlap);
  // The same segment beside the triangle does not.
  const Vec3 t[2] = {{3.5f, 1.0f, 0.5f}, {3.6f, -1.0f, 0.4f}};
  const CoreTriangleClosest c = closest_core_triangle(t, 2, kTri, kDown);
  EXPECT_FALSE(c.overlap);
  EXPECT_GT(c.distance, 1.0f);
}

TEST(TriangleClosest, RandomCoresAgreeWithGjk) {
  uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next = [&state]() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<float>(state >> 40) / static_cast<float>(1u << 24) * 4.0f - 2.0f;
  };
  int overlaps = 0;
  for (int i = 0; i < 4000; ++i) {
    Vec3 tri[3];
    for (Vec3& v : tri) v = {next(), next() * 0.5f, next()};
    const Vec3 n = normalize_or_zero(cross(tri[1] - tri[0], tri[2] - tri[0]));
    if (n == Vec3{}) continue;
    const uint32_t count = i % 3 == 0 ? 1u : 2u;
    const Vec3 core[2] = {{next(), next(), next()}, {next(), next(), next()}};
    const CoreTriangleClosest c = closest_core_triangle(core, count, tri, n);
    const Vec3 zero{};
    const GjkOutput g = gjk_distance(proxy(tri, 3, zero), proxy(core, count, zero));
    if (g.overlap || c.overlap) {
      // Both see it, or the cores are within GJK's tolerance of touching.
      EXPECT_TRUE((g.overlap && c.overlap) || std::fmax(g.distance, c.distance) < 1e-3f)
          << "case " << i << ": gjk " << g.overlap << " " << g.distance << ", closed form "
          << c.overlap << " " << c.distance;
      overlaps += c.overlap ? 1 : 0;
      continue;
    }
    EXPECT_NEAR(c.distance, g.distance, 1e-4f * std::fmax(1.0f, g.distance)) << "case " << i;
    EXPECT_NEAR(length(c.on_core - c.on_tri), c.distance, 1e-5f) << "case " << i;
  }
  EXPECT_GT(overlaps, 50) << "the random cases should cross some triangles";
}

// The nearest point of a triangle to a point, with its feature, against
// the core routine's (a one-point core): the same distance, and a point
// on the feature named (a vertex exactly, an edge within rounding, the
// face in the plane and inside every edge).
TEST(TriangleClosest, PointFeatureAgreesWithTheCoreRoutine) {
  test::Rng rng{9};
  int seen[3] = {0, 0, 0};
  for (int i = 0; i < 4000; ++i) {
    Vec3 tri[3];
    for (Vec3& v : tri) v = {rng.uniform(-2, 2), rng.uniform(-1, 1), rng.uniform(-2, 2)};
    const Vec3 n = normalize_or_zero(cross(tri[1] - tri[0], tri[2] - tri[0]));
    if (n == Vec3{}) continue;
    const Vec3 q{rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)};
    const PointTriangleClosest c = closest_point_triangle(q, tri);
    const CoreTriangleClosest want = closest_core_triangle(&q, 1, tri, n);
    EXPECT_NEAR(std::sqrt(c.distance_sq), want.distance, 1e-5f) << "case " << i;
    EXPECT_NEAR(length(c.point - want.on_tri), 0.0f, 1e-5f) << "case " << i;
    ++seen[static_cast<int>(c.feature)];
    if (c.feature == TriangleFeature::kVertex) {
      EXPECT_EQ(c.point, tri[c.index]) << "case " << i;
    } else if (c.feature == TriangleFeature::kEdge) {
      const Vec3 a = tri[c.index];
      const Vec3 e = tri[(c.index + 1) % 3] - a;
      EXPECT_LT(length(cross(c.point - a, e)), 1e-5f * length(e)) << "case " << i;
    } else {
      EXPECT_NEAR(dot(c.point - tri[0], n), 0.0f, 1e-5f) << "case " << i;
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(dot(cross(tri[(k + 1) % 3] - tri[k], c.point - tri[k]), n), -1e-5f)
            << "case " << i;
      }
    }
  }
  for (int f = 0; f < 3; ++f) EXPECT_GT(seen[f], 200) << "feature " << f;
}

}  // namespace
}  // namespace rwd::sim::d3
