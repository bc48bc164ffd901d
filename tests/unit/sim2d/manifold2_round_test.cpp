// SPDX-License-Identifier: MIT
// Manifolds with a circle or capsule, against analytic answers.
#include <gtest/gtest.h>

#include "sim2d_test_util.h"

namespace rwd::sim2d::test {
namespace {

using detail::kWOne;
using detail::w_from;
using detail::w_int;
using detail::w_ratio;

TEST(Manifold2Circle, CircleCircleSeparationNormalAndPoint) {
  const Shape2D a = ok(make_circle(1.0_fx));
  const Shape2D b = ok(make_circle(0.5_fx));
  const Manifold2 m = collide(a, body(0.0_fx, 0.0_fx), b, body(2.0_fx, 0.0_fx), w_int(1));
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, (V2{kWOne, 0}));
  EXPECT_EQ(m.points[0].separation, w_ratio(1, 2));
  // Surfaces at x = 1 and x = 1.5: the point sits at 1.25.
  EXPECT_EQ(m.points[0].anchor_a, wv(1.25_fx, 0.0_fx));
  EXPECT_EQ(m.points[0].anchor_b, wv(-0.75_fx, 0.0_fx));
  // Beyond the speculative distance: nothing.
  EXPECT_EQ(collide(a, body(0.0_fx, 0.0_fx), b, body(2.0_fx, 0.0_fx)).count, 0);
}

TEST(Manifold2Circle, OverlappingCirclesOnTurnedBodies) {
  // B's circle sits 0.5 m along its body's x axis and the body is turned a
  // quarter turn, so the circle's centre is the body origin + (0, 0.5).
  const Shape2D a = ok(make_circle(2.0_fx));
  const Shape2D b = ok(make_circle(1.0_fx, {0.5_fx, 0.0_fx}));
  // Centres (0, 0) and (3, 4): separation 5 - 3 = 2, beyond 1 m.
  EXPECT_EQ(
      collide(a, body(0.0_fx, 0.0_fx), b, body(3.0_fx, 3.5_fx, Fx::half_pi()), w_int(1)).count, 0);
  const Manifold2 near = collide(a, body(0.0_fx, 0.0_fx), b, body(1.5_fx, 1.5_fx, Fx::half_pi()));
  // Centres (0, 0) and (1.5, 2): distance 2.5, separation -0.5, normal (0.6, 0.8).
  ASSERT_EQ(near.count, 1);
  EXPECT_TRUE(near_w(near.points[0].separation, -w_ratio(1, 2), 8 * kFxUlp));
  EXPECT_TRUE(near_v(near.normal, {w_ratio(6, 10), w_ratio(8, 10)}, 8 * kFxUlp));
  // Surfaces at 2 and 1.5 along the normal: the point is 1.75 along it.
  EXPECT_TRUE(near_v(near.points[0].anchor_a, {w_ratio(105, 100), w_ratio(14, 10)}, 8 * kFxUlp));
  const V2 world_b = wv(1.5_fx, 1.5_fx) + near.points[0].anchor_b;
  EXPECT_EQ(world_b, near.points[0].anchor_a);
}

TEST(Manifold2Circle, CoincidentCentresUseAUnitNormal) {
  const Shape2D a = ok(make_circle(1.0_fx));
  const Manifold2 m = collide(a, body(5.0_fx, 5.0_fx), a, body(5.0_fx, 5.0_fx));
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, (V2{kWOne, 0}));
  EXPECT_EQ(m.points[0].separation, -w_int(2));
}

TEST(Manifold2Polygon, CircleOnAFace) {
  const Shape2D box = ok(make_box(1.0_fx, 1.0_fx));
  const Shape2D ball = ok(make_circle(0.5_fx));
  const Manifold2 m = collide(box, body(0.0_fx, 0.0_fx), ball, body(0.25_fx, 1.25_fx));
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, (V2{0, kWOne}));
  EXPECT_EQ(m.points[0].separation, -w_ratio(1, 4));
  // Face at y = 1, ball's surface at y = 0.75: midway at 0.875.
  EXPECT_EQ(m.points[0].anchor_a, wv(0.25_fx, 0.875_fx));
  EXPECT_EQ(m.points[0].anchor_b, wv(0.0_fx, -0.375_fx));
}

TEST(Manifold2Polygon, CircleInAVertexRegion) {
  const Shape2D box = ok(make_box(1.0_fx, 1.0_fx));
  const Shape2D ball = ok(make_circle(0.125_fx));
  // The centre is (0.375, 0.5) beyond the corner (1, 1): distance 0.625.
  const Manifold2 m = collide(box, body(0.0_fx, 0.0_fx), ball, body(1.375_fx, 1.5_fx), w_int(1));
  ASSERT_EQ(m.count, 1);
  EXPECT_TRUE(near_v(m.normal, {w_ratio(6, 10), w_ratio(8, 10)}, 4));
  EXPECT_EQ(m.points[0].separation, w_ratio(1, 2));
  // Corner (1, 1) and ball surface (1.3, 1.4): midway (1.15, 1.2).
  EXPECT_TRUE(near_v(m.points[0].anchor_a, {w_ratio(115, 100), w_ratio(12, 10)}, 4));
  EXPECT_EQ(collide(box, body(0.0_fx, 0.0_fx), ball, body(1.375_fx, 1.5_fx)).count, 0);
}

TEST(Manifold2Polygon, RoundedPolygonAddsItsRadius) {
  const Shape2D box = ok(make_polygon(
      std::array<Vec2, 4>{
          {{-1.0_fx, -1.0_fx}, {1.0_fx, -1.0_fx}, {1.0_fx, 1.0_fx}, {-1.0_fx, 1.0_fx}}},
      0.25_fx));
  const Shape2D ball = ok(make_circle(0.5_fx));
  const Manifold2 m = collide(box, body(0.0_fx, 0.0_fx), ball, body(0.0_fx, 1.5_fx));
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.points[0].separation, -w_ratio(1, 4));
  // Rounded face at 1.25, ball surface at 1.0: midway 1.125.
  EXPECT_EQ(m.points[0].anchor_a, wv(0.0_fx, 1.125_fx));
}

TEST(Manifold2Reversed, CirclePairsFlipTheNormalAndSwapAnchors) {
  const Shape2D box = ok(make_box(1.0_fx, 0.5_fx, {0.25_fx, 0.0_fx}, 0.3_fx));
  const Shape2D ball = ok(make_circle(0.5_fx, {0.0_fx, 0.125_fx}));
  const Shape2D cap = ok(make_capsule({-1.0_fx, 0.0_fx}, {1.0_fx, 0.5_fx}, 0.25_fx));
  const Shape2D seg = ok(make_segment({-3.0_fx, 0.0_fx}, {3.0_fx, 0.0_fx}));
  const Xf xa = body(10.0_fx, -2.0_fx, 0.7_fx);
  const Xf xb = body(10.25_fx, -1.0_fx, -1.1_fx);
  for (const Shape2D* s : {&box, &cap, &seg}) {
    const Manifold2 ab = collide(*s, xa, ball, xb, w_int(1));
    const Manifold2 ba = collide(ball, xb, *s, xa, w_int(1));
    EXPECT_EQ(ab.count, 1);
    expect_reversed(ab, ba);
  }
}

TEST(Manifold2Capsule, CapsuleCircleAtTheEndAndAlongTheCore) {
  const Shape2D cap = ok(make_capsule({-1.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, 0.25_fx));
  const Shape2D ball = ok(make_circle(0.5_fx));
  // Along the core: the nearest core point is (0.5, 0).
  const Manifold2 side = collide(cap, body(0.0_fx, 0.0_fx), ball, body(0.5_fx, -0.625_fx));
  ASSERT_EQ(side.count, 1);
  EXPECT_EQ(side.normal, (V2{0, -kWOne}));
  EXPECT_EQ(side.points[0].separation, -w_ratio(1, 8));
  EXPECT_EQ(side.points[0].anchor_a, wv(0.5_fx, -0.1875_fx));
  // Beyond the end (1, 0): the normal runs from the end to the centre.
  const Manifold2 end = collide(cap, body(0.0_fx, 0.0_fx), ball, body(1.75_fx, 0.0_fx));
  ASSERT_EQ(end.count, 1);
  EXPECT_EQ(end.normal, (V2{kWOne, 0}));
  EXPECT_EQ(end.points[0].separation, 0);
  EXPECT_EQ(end.points[0].anchor_a, wv(1.25_fx, 0.0_fx));
}

TEST(Manifold2Capsule, ParallelCapsulesGiveTwoPoints) {
  const Shape2D cap = ok(make_capsule({-1.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, 0.25_fx));
  const Manifold2 m = collide(cap, body(0.0_fx, 0.0_fx), cap, body(0.5_fx, 0.375_fx));
  ASSERT_EQ(m.count, 2);
  EXPECT_EQ(m.normal, (V2{0, kWOne}));
  for (int i = 0; i < 2; ++i) EXPECT_EQ(m.points[i].separation, -w_ratio(1, 8));
  // The overlap of the cores is x in [-0.5, 1]; midway in y is 0.1875.
  EXPECT_EQ(m.points[0].anchor_a, wv(1.0_fx, 0.1875_fx));
  EXPECT_EQ(m.points[1].anchor_a, wv(-0.5_fx, 0.1875_fx));
  EXPECT_NE(m.points[0].id, m.points[1].id);
  // A capsule standing on another's middle touches at one point: the end
  // of its core, 0.375 above the other core.
  const Manifold2 x =
      collide(cap, body(0.0_fx, 0.0_fx), cap, body(0.0_fx, 1.375_fx, Fx::half_pi()));
  ASSERT_EQ(x.count, 1);
  EXPECT_TRUE(near_w(x.points[0].separation, -w_ratio(1, 8), 4 * kFxUlp));
  EXPECT_TRUE(near_v(x.points[0].anchor_a, wv(0.0_fx, 0.1875_fx), 4 * kFxUlp));
}

}  // namespace
}  // namespace rwd::sim2d::test
