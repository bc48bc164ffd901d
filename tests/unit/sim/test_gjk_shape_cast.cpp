// SPDX-License-Identifier: MIT
// Shape casts (conservative advancement on GJK) against analytic times of impact.
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>
#include "d3/gjk.h"
#include "gjk_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace gjk_test;

// ---- Shape cast ------------------------------------------------------------

TEST(ShapeCast, SphereAtABoxFace) {
  const BoxCorners box = corners({1.0f, 1.0f, 1.0f});
  const Vec3 zero{};
  const ConvexProxy a = proxy(box.p, 8, {});
  const ConvexProxy b = proxy(&zero, 1, {-5.0f, 0.3f, 0.2f}, {}, 0.5f);
  // The centre reaches x = -1.5 after 3.5 of 10 m.
  const ShapeCastOutput c = shape_cast(a, b, {10.0f, 0.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_FALSE(c.initially_overlapping);
  EXPECT_NEAR(c.fraction, 0.35f, 1e-5f);
  expect_vec(c.normal, {-1.0f, 0.0f, 0.0f}, kTol);
  expect_vec(c.point, {-1.0f, 0.3f, 0.2f}, kTol);
}

TEST(ShapeCast, SphereAtABoxCorner) {
  // Along the diagonal toward the corner (1, 1, 1): the centre stops at
  // distance r from it.
  const BoxCorners box = corners({1.0f, 1.0f, 1.0f});
  const Vec3 zero{};
  const float r = 0.5f;
  const ConvexProxy a = proxy(box.p, 8, {});
  const ConvexProxy b = proxy(&zero, 1, {4.0f, 4.0f, 4.0f}, {}, r);
  const ShapeCastOutput c = shape_cast(a, b, {-4.0f, -4.0f, -4.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  const float s3 = std::sqrt(3.0f);
  const float travel = (3.0f * s3 - r) / (4.0f * s3);  // fraction of the 4 sqrt3 path
  EXPECT_NEAR(c.fraction, travel, 1e-5f);
  expect_vec(c.normal, Vec3{1.0f, 1.0f, 1.0f} * (1.0f / s3), 1e-4f);
  expect_vec(c.point, {1.0f, 1.0f, 1.0f}, 1e-4f);
}

TEST(ShapeCast, BoxAtABox) {
  const BoxCorners big = corners({1.0f, 1.0f, 1.0f});
  const BoxCorners small = corners({0.5f, 0.5f, 0.5f});
  const ConvexProxy a = proxy(big.p, 8, {});
  // Face down: bottom at y = 1 when the centre is at 1.5.
  ShapeCastOutput c =
      shape_cast(a, proxy(small.p, 8, {0.2f, 5.0f, 0.1f}), {0.0f, -10.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.fraction, 0.35f, 1e-5f);
  expect_vec(c.normal, {0.0f, 1.0f, 0.0f}, kTol);
  EXPECT_NEAR(c.point.y, 1.0f, kTol);
  // Edge down (turned 45 degrees about z): the edge is reach below the centre.
  const float reach = 0.5f * std::sqrt(2.0f);
  c = shape_cast(a, proxy(small.p, 8, {0.2f, 5.0f, 0.1f}, kZ45), {0.0f, -10.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.fraction, (4.0f - reach) / 10.0f, 1e-5f);
  expect_vec(c.normal, {0.0f, 1.0f, 0.0f}, 1e-4f);
  EXPECT_NEAR(c.point.x, 0.2f, 1e-4f);  // anywhere along the edge in z
  EXPECT_NEAR(c.point.y, 1.0f, 1e-4f);
  // Sideways and down at once: the same face, a longer path.
  c = shape_cast(a, proxy(small.p, 8, {-1.8f, 5.0f, 0.1f}, {}), {2.0f, -10.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.fraction, 0.35f, 1e-5f);
  expect_vec(c.normal, {0.0f, 1.0f, 0.0f}, kTol);
}

TEST(ShapeCast, CapsuleAtAWall) {
  const BoxCorners wall = corners({0.1f, 5.0f, 5.0f});
  const ConvexProxy a = proxy(wall.p, 8, {});
  const Vec3 seg[2] = {{0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  // Upright: the side meets the wall at x = 0.1 + 0.25.
  ShapeCastOutput c =
      shape_cast(a, proxy(seg, 2, {3.0f, 0.0f, 0.0f}, {}, 0.25f), {-4.0f, 0.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.fraction, (3.0f - 0.35f) / 4.0f, 1e-5f);
  expect_vec(c.normal, {1.0f, 0.0f, 0.0f}, kTol);
  EXPECT_NEAR(c.point.x, 0.1f, kTol);
  // Leaning 45 degrees toward the wall: the lower end leads by sqrt(1/2).
  c = shape_cast(a, proxy(seg, 2, {3.0f, 0.0f, 0.0f}, kZ45, 0.25f), {-4.0f, 0.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.fraction, (3.0f - 0.35f - std::sqrt(0.5f)) / 4.0f, 1e-5f);
  expect_vec(c.normal, {1.0f, 0.0f, 0.0f}, kTol);
  EXPECT_NEAR(c.point.y, std::sqrt(0.5f), 1e-4f);  // the end at +y (turned onto -x)
}

TEST(ShapeCast, Misses) {
  const BoxCorners box = corners({1.0f, 1.0f, 1.0f});
  const Vec3 zero{};
  const ConvexProxy a = proxy(box.p, 8, {});
  const ConvexProxy b = proxy(&zero, 1, {-5.0f, 1.6f, 0.0f}, {}, 0.5f);
  // Passing 0.1 above the top face.
  EXPECT_FALSE(shape_cast(a, b, {10.0f, 0.0f, 0.0f}, 1.0f).hit);
  // Passing the edge at x = y = 1 by 0.01, moving along (-1, 1, 0): the
  // cast slows at the edge but misses.
  const float h = std::sqrt(0.5f);
  const Vec3 closest{1.0f + 0.51f * h, 1.0f + 0.51f * h, 0.3f};
  const ConvexProxy b2 = proxy(&zero, 1, closest - Vec3{-h, h, 0.0f} * 5.0f, {}, 0.5f);
  EXPECT_FALSE(shape_cast(a, b2, Vec3{-h, h, 0.0f} * 10.0f, 1.0f).hit);
  // ... and by -0.01: a hit.
  const Vec3 closer{1.0f + 0.49f * h, 1.0f + 0.49f * h, 0.3f};
  const ConvexProxy b4 = proxy(&zero, 1, closer - Vec3{-h, h, 0.0f} * 5.0f, {}, 0.5f);
  EXPECT_TRUE(shape_cast(a, b4, Vec3{-h, h, 0.0f} * 10.0f, 1.0f).hit);
  // Aimed at it but stopping short: the touch is at 0.35.
  const ConvexProxy b3 = proxy(&zero, 1, {-5.0f, 0.0f, 0.0f}, {}, 0.5f);
  EXPECT_FALSE(shape_cast(a, b3, {10.0f, 0.0f, 0.0f}, 0.3f).hit);
  EXPECT_TRUE(shape_cast(a, b3, {10.0f, 0.0f, 0.0f}, 0.4f).hit);
  // Moving away, and not moving.
  EXPECT_FALSE(shape_cast(a, b3, {-10.0f, 0.0f, 0.0f}, 1.0f).hit);
  EXPECT_FALSE(shape_cast(a, b3, {0.0f, 0.0f, 0.0f}, 1.0f).hit);
}

TEST(ShapeCast, StartingOverlapped) {
  const BoxCorners box = corners({1.0f, 1.0f, 1.0f});
  const Vec3 zero{};
  const ConvexProxy a = proxy(box.p, 8, {});
  // Centre inside (cores overlap): EPA's normal, out through +x.
  ShapeCastOutput c =
      shape_cast(a, proxy(&zero, 1, {0.8f, 0.1f, 0.0f}, {}, 0.5f), {-1.0f, 0.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_TRUE(c.initially_overlapping);
  EXPECT_EQ(c.fraction, 0.0f);
  expect_vec(c.normal, {1.0f, 0.0f, 0.0f}, 1e-4f);
  // Centre outside, surface inside (rounded overlap): GJK's normal.
  c = shape_cast(a, proxy(&zero, 1, {1.2f, 0.1f, 0.0f}, {}, 0.5f), {1.0f, 0.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c.hit);
  EXPECT_TRUE(c.initially_overlapping);
  EXPECT_EQ(c.fraction, 0.0f);
  expect_vec(c.normal, {1.0f, 0.0f, 0.0f}, kTol);
  expect_vec(c.point, {1.0f, 0.1f, 0.0f}, kTol);
}

TEST(ShapeCast, RandomSweepsNeverPassTheImpact) {
  // The reported fraction never lies past the true impact: just before it
  // the shapes are apart, a little after it they overlap.
  test::Rng rng{99};
  int hits = 0;
  const BoxCorners box = corners({0.6f, 0.8f, 0.4f});
  for (int n = 0; n < 200; ++n) {
    const ConvexProxy a = proxy(box.p, 8, {}, rng.rotation());
    const Vec3 start{rng.uniform(-5, 5), rng.uniform(-5, 5), 5.0f};  // one draw per statement
    const ConvexProxy b = proxy(box.p, 8, start, rng.rotation(), 0.1f);
    const Vec3 target{rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f)};
    const Vec3 translation = (target - b.position) * 1.5f;
    const ShapeCastOutput c = shape_cast(a, b, translation, 1.0f);
    ConvexProxy at = b;
    at.position = b.position + translation * c.fraction;
    const GjkOutput g = gjk_distance(a, at);
    if (!c.hit) {
      continue;
    }
    ++hits;
    EXPECT_FALSE(c.initially_overlapping) << n;
    EXPECT_GE(g.distance - 0.1f, -1e-5f) << n;  // not yet overlapping
    EXPECT_LE(g.distance - 0.1f, 2e-3f) << n;   // but touching
    EXPECT_NEAR(length(c.normal), 1.0f, 1e-5f) << n;
  }
  EXPECT_GT(hits, 150);
}

}  // namespace
}  // namespace rwd::sim::d3
