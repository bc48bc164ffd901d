// SPDX-License-Identifier: MIT
// Polygon, capsule and segment manifolds (reference-face clipping),
// against analytic answers.
#include <gtest/gtest.h>

#include "sim2d_test_util.h"

namespace rwd::sim2d::test {
namespace {

using detail::kWOne;
using detail::ManifoldPoint2;
using detail::w_int;
using detail::w_ratio;

// Both boxes' surfaces meet at y = 0: the ground's top face and the box's
// bottom face.
struct Stack {
  Shape2D ground = ok(make_box(5.0_fx, 0.5_fx));
  Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  Xf ground_at = body(0.0_fx, -0.5_fx);
};

TEST(Manifold2Polygons, BoxRestingOnGroundTouchesAtBothCorners) {
  const Stack s;
  const Manifold2 m = collide(s.box, body(0.0_fx, 0.5_fx), s.ground, s.ground_at);
  ASSERT_EQ(m.count, 2);
  EXPECT_EQ(m.normal, (V2{0, -kWOne}));
  const V2 corners[2] = {wv(-0.5_fx, 0.0_fx), wv(0.5_fx, 0.0_fx)};
  for (int i = 0; i < 2; ++i) {
    const ManifoldPoint2& p = m.points[i];
    EXPECT_TRUE(near_w(p.separation, 0, 2 * kFxUlp));
    // anchor_a is from the box origin (0, 0.5), anchor_b from the ground's.
    EXPECT_TRUE(near_v(p.anchor_a + wv(0.0_fx, 0.5_fx), corners[i], 2 * kFxUlp));
    EXPECT_TRUE(near_v(p.anchor_b + wv(0.0_fx, -0.5_fx), corners[i], 2 * kFxUlp));
  }
  EXPECT_NE(m.points[0].id, m.points[1].id);

  // With the ground as A the normal points up, to the box.
  const Manifold2 g = collide(s.ground, s.ground_at, s.box, body(0.0_fx, 0.5_fx));
  ASSERT_EQ(g.count, 2);
  EXPECT_EQ(g.normal, (V2{0, kWOne}));
  EXPECT_TRUE(near_w(g.points[0].separation, 0, 2 * kFxUlp));
  EXPECT_TRUE(near_w(g.points[1].separation, 0, 2 * kFxUlp));
}

TEST(Manifold2Polygons, TurnedStackRestsWithinAnUlp) {
  // Ground and box both turned by 0.3 rad, the box's centre 1 m up the
  // ground's turned y axis: the faces meet along the whole box bottom.
  const Stack s;
  const Fx angle = 0.3_fx;
  const fixed::SinCos sc = fixed::sin_cos(angle);
  const Manifold2 m =
      collide(s.box, body(-sc.sin, sc.cos, angle), s.ground, body(0.0_fx, 0.0_fx, angle));
  ASSERT_EQ(m.count, 2);
  // The box centre was rounded to the Fx grid: half an ulp per axis.
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(near_w(m.points[i].separation, 0, 2 * kFxUlp));
  const V2 down = {detail::w_from(sc.sin), -detail::w_from(sc.cos)};
  EXPECT_TRUE(near_v(m.normal, down, 4 * kFxUlp));
}

TEST(Manifold2Polygons, RoundedBoxSinksByItsRadius) {
  const Stack s;
  const Shape2D rounded = ok(make_polygon(
      std::array<Vec2, 4>{
          {{-0.5_fx, -0.5_fx}, {0.5_fx, -0.5_fx}, {0.5_fx, 0.5_fx}, {-0.5_fx, 0.5_fx}}},
      0.125_fx));
  const Manifold2 m = collide(rounded, body(0.0_fx, 0.5_fx), s.ground, s.ground_at);
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(m.points[i].separation, -w_ratio(1, 8));
    // Rounded surface at y = -0.125, ground at 0: midway -0.0625.
    EXPECT_EQ(m.points[i].anchor_a.y, -w_ratio(9, 16));
  }
}

TEST(Manifold2Polygons, TurnedBoxOnItsCornerGivesOnePoint) {
  const Stack s;
  // Half extent 0.5 turned 45 degrees: the corner hangs 0.5 * sqrt(2) below
  // the centre.
  const Fx h = Fx::from_raw(46341);  // 0.70711
  const Manifold2 m = collide(s.box, body(0.25_fx, h, Fx::pi() / 4), s.ground, s.ground_at);
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, (V2{0, -kWOne}));
  EXPECT_TRUE(near_w(m.points[0].separation, 0, 4 * kFxUlp));
  EXPECT_TRUE(near_v(m.points[0].anchor_a + wv(0.25_fx, h), wv(0.25_fx, 0.0_fx), 4 * kFxUlp));
}

TEST(Manifold2Polygons, SpeculativePointsKeptWithinTheDistanceOnly) {
  const Stack s;
  for (const Fx gap : {Fx::from_raw(1 << 9), Fx::from_raw(1 << 10)}) {  // 2^-7, 2^-6 m
    const Manifold2 m = collide(s.box, body(0.0_fx, 0.5_fx + gap), s.ground, s.ground_at);
    ASSERT_EQ(m.count, 2);
    EXPECT_EQ(m.points[0].separation, detail::w_from(gap));
    EXPECT_EQ(m.points[1].separation, detail::w_from(gap));
    // Midway across the gap.
    EXPECT_EQ(m.points[0].anchor_a.y, -w_ratio(1, 2) - detail::w_from(gap) / 2);
  }
  // 2^-5 m is beyond the 0.02 m speculative distance.
  EXPECT_EQ(collide(s.box, body(0.0_fx, 0.53125_fx), s.ground, s.ground_at).count, 0);
  // Two equal boxes exactly stacked with a gap: overlapping parallel faces
  // are clipped (two points), not taken as a vertex pair.
  const Manifold2 twin = collide(s.box, body(0.0_fx, 0.5_fx), s.box, body(0.0_fx, 1.5078125_fx));
  EXPECT_EQ(twin.count, 2);
}

TEST(Manifold2Polygons, SeparatedCornersGiveAVertexPair) {
  const Stack s;
  // Box B's corner (-0.5, -0.5) sits (0.009, 0.012) beyond A's corner
  // (0.5, 0.5): 0.015 m apart, along (0.6, 0.8).
  const Manifold2 m = collide(s.box, body(0.0_fx, 0.0_fx), s.box, body(1.009_fx, 1.012_fx));
  ASSERT_EQ(m.count, 1);
  EXPECT_TRUE(near_w(m.points[0].separation, w_ratio(15, 1000), 2 * kFxUlp));
  EXPECT_TRUE(near_v(m.normal, {w_ratio(6, 10), w_ratio(8, 10)}, 64 * kFxUlp));
  EXPECT_TRUE(near_v(m.points[0].anchor_a, {w_ratio(5045, 10000), w_ratio(506, 1000)}, 2 * kFxUlp));
}

TEST(Manifold2Polygons, IdsStayWhileTheSameFeaturesTouch) {
  const Stack s;
  const Manifold2 m0 = collide(s.box, body(0.0_fx, 0.5_fx), s.ground, s.ground_at);
  const Manifold2 m1 = collide(s.box, body(0.01_fx, 0.499_fx, 0.002_fx), s.ground, s.ground_at);
  const Manifold2 m2 = collide(s.box, body(-0.3_fx, 0.503_fx, -0.001_fx), s.ground, s.ground_at);
  ASSERT_EQ(m0.count, 2);
  ASSERT_EQ(m1.count, 2);
  ASSERT_EQ(m2.count, 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(m0.points[i].id, m1.points[i].id);
    EXPECT_EQ(m0.points[i].id, m2.points[i].id);
  }
}

TEST(Manifold2Polygons, FarFromTheOriginMatchesNearTheOrigin) {
  const Stack s;
  const Fx far = 30000.0_fx;
  const Manifold2 near = collide(s.box, body(0.125_fx, 0.49_fx, 0.01_fx), s.ground, s.ground_at);
  const Manifold2 away =
      collide(s.box, body(far + 0.125_fx, 0.49_fx, 0.01_fx), s.ground, body(far, -0.5_fx));
  ASSERT_EQ(near.count, 2);
  ASSERT_EQ(away.count, near.count);
  EXPECT_EQ(away.normal, near.normal);
  for (int i = 0; i < near.count; ++i) {
    EXPECT_EQ(away.points[i].separation, near.points[i].separation);
    EXPECT_EQ(away.points[i].anchor_a, near.points[i].anchor_a);
    EXPECT_EQ(away.points[i].anchor_b, near.points[i].anchor_b);
    EXPECT_EQ(away.points[i].id, near.points[i].id);
  }
  // The tilted box's low corner is 0.01 m below the ground's surface.
  EXPECT_LT(near.points[0].separation, 0);
}

TEST(Manifold2Capsule, CapsuleLyingOnABoxGivesTwoPoints) {
  const Stack s;
  const Shape2D cap = ok(make_capsule({-1.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, 0.25_fx));
  const Manifold2 m = collide(cap, body(2.0_fx, 0.25_fx), s.ground, s.ground_at);
  ASSERT_EQ(m.count, 2);
  EXPECT_EQ(m.normal, (V2{0, -kWOne}));
  const V2 ends[2] = {wv(1.0_fx, 0.0_fx), wv(3.0_fx, 0.0_fx)};
  bool seen[2] = {false, false};
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(m.points[i].separation, 0);
    const V2 world = m.points[i].anchor_a + wv(2.0_fx, 0.25_fx);
    for (int k = 0; k < 2; ++k) seen[k] = seen[k] || world == ends[k];
  }
  EXPECT_TRUE(seen[0] && seen[1]);
  // Tilted, only its low end touches.
  EXPECT_EQ(collide(cap, body(2.0_fx, 0.3_fx, 0.2_fx), s.ground, s.ground_at).count, 1);
}

TEST(Manifold2Segment, SegmentAgainstABoxFromEitherSide) {
  const Stack s;
  const Shape2D seg = ok(make_segment({-5.0_fx, 0.0_fx}, {5.0_fx, 0.0_fx}));
  const Xf origin = body(0.0_fx, 0.0_fx);
  const Manifold2 above = collide(seg, origin, s.box, body(1.0_fx, 0.5_fx));
  ASSERT_EQ(above.count, 2);
  EXPECT_EQ(above.normal, (V2{0, kWOne}));
  EXPECT_EQ(above.points[0].separation, 0);
  EXPECT_EQ(above.points[1].separation, 0);
  EXPECT_EQ(above.points[0].anchor_a, wv(1.5_fx, 0.0_fx));
  EXPECT_EQ(above.points[1].anchor_a, wv(0.5_fx, 0.0_fx));
  const Manifold2 below = collide(seg, origin, s.box, body(1.0_fx, -0.49_fx));
  ASSERT_EQ(below.count, 2);
  EXPECT_EQ(below.normal, (V2{0, -kWOne}));
  // The reversed pair runs the same routine with the roles swapped.
  expect_reversed(above, collide(s.box, body(1.0_fx, 0.5_fx), seg, origin));
  expect_reversed(below, collide(s.box, body(1.0_fx, -0.49_fx), seg, origin));
  // Segments never collide with each other, even crossing.
  const Shape2D cross = ok(make_segment({0.0_fx, -1.0_fx}, {0.0_fx, 1.0_fx}));
  EXPECT_EQ(collide(seg, origin, cross, origin).count, 0);
}

TEST(Manifold2Dispatch, FarApartPairsAreEmpty) {
  const Stack s;
  const Shape2D ball = ok(make_circle(1.0_fx));
  const Shape2D cap = ok(make_capsule({-1.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, 0.25_fx));
  const Shape2D* shapes[] = {&ball, &cap, &s.box, &s.ground};
  for (const Shape2D* a : shapes) {
    for (const Shape2D* b : shapes) {
      EXPECT_EQ(collide(*a, body(-30000.0_fx, 0.0_fx), *b, body(30000.0_fx, 100.0_fx)).count, 0);
    }
  }
}

}  // namespace
}  // namespace rwd::sim2d::test
