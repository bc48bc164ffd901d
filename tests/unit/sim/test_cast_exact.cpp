// SPDX-License-Identifier: MIT
// Exact casts (cast_exact.h) of spheres and boxes against spheres and
// boxes: analytic answers at a face, an edge and a corner, and random
// sweeps checked against GJK at the reported fraction (the shapes touch
// there and are apart just before) and against conservative advancement.
#include <gtest/gtest.h>
#include <cmath>

#include "d3/cast_exact.h"
#include "d3/gjk.h"
#include "d3/shape_ops.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

struct Posed {
  Shape shape;
  ProxyPoints storage;
  ConvexProxy proxy;
};

void pose(Posed& p, const Shape& shape, Vec3 position, Quat rotation) {
  p.shape = shape;
  p.proxy = shape_ops(shape.type).proxy(shape, GeometryStore{}, p.storage);
  p.proxy.position = position;
  p.proxy.axes = mat3_from_quat(rotation);
}

// Surface gap between the posed target and the swept shape moved by `t`
// of `translation` (negative: overlapping, as far as GJK tells).
float gap_at(const Posed& target, const Posed& swept, Vec3 translation, float t,
             Vec3* normal = nullptr) {
  ConvexProxy moved = swept.proxy;
  moved.position = swept.proxy.position + translation * t;
  const GjkOutput g = gjk_distance(target.proxy, moved);
  if (normal != nullptr) *normal = g.normal;
  const float cores =
      g.overlap ? -epa_penetration(target.proxy, moved, g.simplex).depth : g.distance;
  return cores - target.proxy.radius - moved.radius;
}

// A box of half sizes in [lo, hi) or a ball of radius in [lo, hi).
Shape random_shape(test::Rng& rng, bool box, float lo, float hi) {
  if (!box) return Shape::make_sphere(rng.uniform(lo, hi));
  const float x = rng.uniform(lo, hi);
  const float y = rng.uniform(lo, hi);
  return Shape::make_box({x, y, rng.uniform(lo, hi)});
}

ShapeCastOutput exact(const Posed& target, const Posed& swept, Vec3 translation, bool& handled) {
  ShapeCastOutput out;
  handled = cast_exact(target.shape, target.proxy.position, target.proxy.axes, swept.shape,
                       swept.proxy, translation, 1.0f, out);
  return out;
}

TEST(CastExact, ASphereMeetsABoxAtAFaceAnEdgeAndACorner) {
  Posed box;
  pose(box, Shape::make_box({1.0f, 1.0f, 1.0f}), {}, {});
  Posed ball;
  bool handled = false;
  // Face: the centre reaches x = -1.5 after 3.5 of 10 m.
  pose(ball, Shape::make_sphere(0.5f), {-5.0f, 0.3f, 0.2f}, {});
  ShapeCastOutput c = exact(box, ball, {10.0f, 0.0f, 0.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  EXPECT_NEAR(c.fraction, 0.35f, 1e-6f);
  EXPECT_NEAR(c.normal.x, -1.0f, 1e-6f);
  EXPECT_NEAR(c.point.x, -1.0f, 1e-6f);
  EXPECT_NEAR(c.point.y, 0.3f, 1e-6f);
  // Edge: down along -y at z = 1.2, past the top face: the ball meets the
  // cylinder of the edge y = z = 1 where its centre is 0.5 from it, at
  // y = 1 + sqrt(0.25 - 0.04).
  pose(ball, Shape::make_sphere(0.5f), {0.0f, 5.0f, 1.2f}, {});
  c = exact(box, ball, {0.0f, -10.0f, 0.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  const float above = std::sqrt(0.21f);
  EXPECT_NEAR(c.fraction * 10.0f, 4.0f - above, 1e-5f);
  EXPECT_NEAR(c.normal.y, above / 0.5f, 1e-5f);
  EXPECT_NEAR(c.normal.z, 0.4f, 1e-5f);
  EXPECT_NEAR(c.point.y, 1.0f, 1e-6f);
  EXPECT_NEAR(c.point.z, 1.0f, 1e-6f);
  // Along -x at y = z = 1.2 the path stays 0.2 sqrt2 from the edge along
  // x, inside its cylinder: the ball meets the corner (-1, 1, 1) instead.
  pose(ball, Shape::make_sphere(0.5f), {-5.0f, 1.2f, 1.2f}, {});
  c = exact(box, ball, {10.0f, 0.0f, 0.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  const float short_of = std::sqrt(0.25f - 0.08f);
  EXPECT_NEAR(c.fraction * 10.0f, 4.0f - short_of, 1e-5f);
  EXPECT_NEAR(c.normal.x, -short_of / 0.5f, 1e-4f);
  EXPECT_NEAR(c.normal.y, 0.4f, 1e-4f);
  // Corner, along the diagonal: the centre stops 0.5 from (1, 1, 1).
  pose(ball, Shape::make_sphere(0.5f), {4.0f, 4.0f, 4.0f}, {});
  c = exact(box, ball, {-4.0f, -4.0f, -4.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  const float s3 = std::sqrt(3.0f);
  EXPECT_NEAR(c.fraction, (3.0f * s3 - 0.5f) / (4.0f * s3), 1e-6f);
  EXPECT_NEAR(c.normal.x, 1.0f / s3, 1e-5f);
  // Passing 1 mm wide of the corner's ball misses (advancement's target gap
  // would count it).
  pose(ball, Shape::make_sphere(0.5f), {-5.0f, 1.501f, 0.0f}, {});
  c = exact(box, ball, {10.0f, 0.0f, 0.0f}, handled);
  ASSERT_TRUE(handled);
  EXPECT_FALSE(c.hit);
  // Starting inside: left to GJK and EPA.
  pose(ball, Shape::make_sphere(0.5f), {0.0f, 1.2f, 0.0f}, {});
  exact(box, ball, {10.0f, 0.0f, 0.0f}, handled);
  EXPECT_FALSE(handled);
}

TEST(CastExact, ABoxLandsFlatOnABoxAndEdgeOnAcrossAnother) {
  Posed big;
  pose(big, Shape::make_box({1.0f, 1.0f, 1.0f}), {}, {});
  Posed small;
  bool handled = false;
  pose(small, Shape::make_box({0.5f, 0.5f, 0.5f}), {0.2f, 5.0f, 0.1f}, {});
  ShapeCastOutput c = exact(big, small, {0.0f, -10.0f, 0.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  EXPECT_NEAR(c.fraction, 0.35f, 1e-6f);
  EXPECT_NEAR(c.normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(c.point.y, 1.0f, 1e-6f);
  EXPECT_NEAR(c.point.x, 0.2f, 1e-5f);
  // The big box turned 45 degrees about z (a top edge along z), the small
  // one 45 degrees about x (a bottom edge along x): edge across edge.
  const float s = std::sin(0.125f * 3.14159265f);
  const float co = std::cos(0.125f * 3.14159265f);
  pose(big, Shape::make_box({1.0f, 1.0f, 1.0f}), {}, Quat{0.0f, 0.0f, s, co});
  pose(small, Shape::make_box({0.5f, 0.5f, 0.5f}), {0.0f, 5.0f, 0.0f}, Quat{s, 0.0f, 0.0f, co});
  c = exact(big, small, {0.0f, -10.0f, 0.0f}, handled);
  ASSERT_TRUE(handled && c.hit);
  // The big box's top edge at y = sqrt2, the small one's lowest edge
  // sqrt(0.5) below its centre.
  EXPECT_NEAR(c.fraction * 10.0f, 5.0f - std::sqrt(2.0f) - std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(c.normal.y, 1.0f, 1e-5f);
  EXPECT_NEAR(c.point.y, std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(c.point.x, 0.0f, 1e-5f);
  EXPECT_NEAR(c.point.z, 0.0f, 1e-5f);
}

// Random poses, sizes and sweeps of every pair: where the exact cast says
// the shapes first touch, GJK finds them touching, and 1 mm before it
// apart; conservative advancement stops there or a little early.
TEST(CastExact, RandomSweepsTouchWhereTheySayAndAgreeWithAdvancement) {
  test::Rng rng{0xCA57};
  int hits = 0;
  int misses = 0;
  for (int n = 0; n < 4000; ++n) {
    const bool target_box = n % 2 == 0;
    const bool swept_box = (n / 2) % 2 == 0;
    const Shape target_shape = random_shape(rng, target_box, 0.1f, target_box ? 2.0f : 1.5f);
    const Shape swept_shape = random_shape(rng, swept_box, 0.05f, 1.0f);
    Posed target;
    const Vec3 at{rng.uniform(-50.0f, 50.0f), rng.uniform(-50.0f, 50.0f),
                  rng.uniform(-50.0f, 50.0f)};
    pose(target, target_shape, at, rng.rotation());
    Posed swept;
    const Vec3 offset{rng.uniform(-6.0f, 6.0f), rng.uniform(-6.0f, 6.0f), rng.uniform(-6.0f, 6.0f)};
    pose(swept, swept_shape, at + offset, rng.rotation());
    const Vec3 aim{rng.uniform(-2.5f, 2.5f), rng.uniform(-2.5f, 2.5f), rng.uniform(-2.5f, 2.5f)};
    const Vec3 translation = (aim - offset) * rng.uniform(0.5f, 2.0f);
    bool handled = false;
    const ShapeCastOutput c = exact(target, swept, translation, handled);
    const ShapeCastOutput ca = shape_cast(target.proxy, swept.proxy, translation, 1.0f);
    if (!handled) {
      EXPECT_TRUE(ca.initially_overlapping) << n;
      continue;
    }
    const float length_m = length(translation);
    if (!c.hit) {
      ++misses;
      // Advancement may count a pass within its target gap as a touch.
      if (ca.hit) {
        EXPECT_LE(gap_at(target, swept, translation, ca.fraction), 2e-3f) << n;
      }
      continue;
    }
    ++hits;
    EXPECT_FALSE(c.initially_overlapping) << n;
    EXPECT_GT(c.fraction, 0.0f) << n;
    EXPECT_NEAR(length(c.normal), 1.0f, 1e-4f) << n;
    EXPECT_NEAR(gap_at(target, swept, translation, c.fraction), 0.0f, 2e-4f) << n;
    const float before = c.fraction - 1e-3f / length_m;
    if (before > 0.0f) {
      Vec3 gjk_normal;
      EXPECT_GT(gap_at(target, swept, translation, before, &gjk_normal), 0.0f) << n;
      EXPECT_GT(dot(gjk_normal, c.normal), 0.97f) << n;
    }
    // The point is on the target's surface.
    const Vec3 local =
        gjk_detail::mul_transpose(target.proxy.axes, c.point - target.proxy.position);
    const float off_surface =
        target_box ? std::fmax(std::fmax(std::fabs(local.x) - target_shape.half_extents.x,
                                         std::fabs(local.y) - target_shape.half_extents.y),
                               std::fabs(local.z) - target_shape.half_extents.z)
                   : length(local) - target_shape.radius;
    EXPECT_NEAR(off_surface, 0.0f, 1e-4f) << n;
    // Advancement stops at the touch or early (its last step extrapolates
    // along a normal that may still turn), within its target gap.
    ASSERT_TRUE(ca.hit) << n;
    EXPECT_LE(ca.fraction * length_m, c.fraction * length_m + 1e-4f) << n;
    EXPECT_LE(gap_at(target, swept, translation, ca.fraction), 2e-3f) << n;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 500);
}

// Far from the origin and over hundreds of metres (a long cast across a
// level), the touch is still where the cast says: within a fraction of a
// millimetre plus the coordinates' own rounding.
TEST(CastExact, LongSweepsFarFromTheOriginTouchWhereTheySay) {
  test::Rng rng{77};
  int hits = 0;
  for (int n = 0; n < 40000; ++n) {
    const bool target_box = n % 2 == 0;
    const bool swept_box = (n / 2) % 2 == 0;
    const Shape target_shape = random_shape(rng, target_box, 0.05f, 5.0f);
    const Shape swept_shape = random_shape(rng, swept_box, 0.02f, 3.0f);
    Posed target;
    const Vec3 at{rng.uniform(-3000.0f, 3000.0f), rng.uniform(-3000.0f, 3000.0f),
                  rng.uniform(-3000.0f, 3000.0f)};
    pose(target, target_shape, at, rng.rotation());
    const float spread = rng.uniform(1.0f, 300.0f);
    const Vec3 offset{rng.uniform(-1.0f, 1.0f) * spread, rng.uniform(-1.0f, 1.0f) * spread,
                      rng.uniform(-1.0f, 1.0f) * spread};
    Posed swept;
    pose(swept, swept_shape, at + offset, rng.rotation());
    const Vec3 aim{rng.uniform(-4.0f, 4.0f), rng.uniform(-4.0f, 4.0f), rng.uniform(-4.0f, 4.0f)};
    const Vec3 translation = (aim - offset) * rng.uniform(0.3f, 3.0f);
    bool handled = false;
    const ShapeCastOutput c = exact(target, swept, translation, handled);
    if (!handled || !c.hit) continue;
    ++hits;
    const float rounding =
        2e-6f * (std::fabs(at.x) + std::fabs(at.y) + std::fabs(at.z) + length(translation));
    ASSERT_NEAR(gap_at(target, swept, translation, c.fraction), 0.0f, 2e-4f + rounding) << n;
    ASSERT_NEAR(length(c.normal), 1.0f, 1e-3f) << n;
  }
  EXPECT_GT(hits, 15000);
}

}  // namespace
}  // namespace rwd::sim::d3
