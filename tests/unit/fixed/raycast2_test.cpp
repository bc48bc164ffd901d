// SPDX-License-Identifier: MIT
#include "rewind/fixed/raycast2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "rewind/fixed/fx_literal.h"

namespace rwd::fixed {
namespace {

Vec2 v(int32_t x, int32_t y) {
  return {Fx(x), Fx(y)};
}
Aabb2 box(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  return *Aabb2::make(v(x0, y0), v(x1, y1));
}

TEST(FixedRaycastAabb, HitsTheNearFaceWithExactFraction) {
  const auto hit = raycast(Ray2{v(-3, 0), v(4, 0)}, box(-1, -1, 1, 1));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->fraction, 0.5_fx);
  EXPECT_EQ(hit->point, v(-1, 0));
  EXPECT_EQ(hit->normal, v(-1, 0));
  const auto from_above = raycast(Ray2{v(0, 10), v(0, -30)}, box(-1, -1, 1, 1));
  ASSERT_TRUE(from_above.has_value());
  EXPECT_EQ(from_above->fraction, Fx::ratio(9, 30));
  EXPECT_EQ(from_above->point, v(0, 1));
  EXPECT_EQ(from_above->normal, v(0, 1));
}

TEST(FixedRaycastAabb, FollowsTheSharedRules) {
  const Aabb2 b = box(-1, -1, 1, 1);
  EXPECT_FALSE(raycast(Ray2{v(0, 0), v(5, 0)}, b).has_value());    // starts inside
  EXPECT_FALSE(raycast(Ray2{v(-3, 0), v(0, 0)}, b).has_value());   // zero delta
  EXPECT_FALSE(raycast(Ray2{v(-3, 0), v(1, 0)}, b).has_value());   // too short
  EXPECT_FALSE(raycast(Ray2{v(-3, 2), v(10, 0)}, b).has_value());  // parallel, outside
  EXPECT_FALSE(raycast(Ray2{v(3, 0), v(5, 0)}, b).has_value());    // pointing away
  const auto end = raycast(Ray2{v(-3, 0), v(2, 0)}, b);            // reaches it exactly
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->fraction, Fx::one());
  const auto on_face = raycast(Ray2{v(-1, 0), v(2, 0)}, b);  // starts on the face
  ASSERT_TRUE(on_face.has_value());
  EXPECT_EQ(on_face->fraction, Fx::zero());
  const auto corner = raycast(Ray2{v(-2, -2), v(4, 4)}, b);  // x face wins the tie
  ASSERT_TRUE(corner.has_value());
  EXPECT_EQ(corner->normal, v(-1, 0));
  EXPECT_EQ(corner->point, v(-1, -1));
  const auto graze = raycast(Ray2{v(-3, 1), v(6, 0)}, b);  // along the top face
  ASSERT_TRUE(graze.has_value());
  EXPECT_EQ(graze->fraction, Fx::ratio(2, 6));
}

TEST(FixedRaycastAabb, WorksAcrossTheWholeRange) {
  const Aabb2 far = box(32000, -10, 32767, 10);
  const auto hit = raycast(Ray2{Vec2(Fx::min(), Fx::zero()), Vec2(Fx::max(), Fx::zero())}, far);
  EXPECT_FALSE(hit.has_value());  // reaches only -2^-16
  const auto across = raycast(Ray2{Vec2(Fx(-500), Fx::zero()), Vec2(Fx::max(), Fx::zero())}, far);
  ASSERT_TRUE(across.has_value());
  EXPECT_EQ(across->point.x, Fx(32000));
  EXPECT_EQ(across->fraction, Fx::ratio(int64_t{32500} * 65536, INT32_MAX));
}

TEST(FixedRaycastCircle, HitsWithFractionPointAndNormal) {
  const Circle c = *Circle::make(v(0, 0), Fx(1));
  const auto hit = raycast(Ray2{v(-3, 0), v(6, 0)}, c);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->fraction, Fx::ratio(1, 3));
  EXPECT_EQ(hit->point, v(-1, 0));
  EXPECT_EQ(hit->normal, v(-1, 0));
  // An oblique hit against the analytic answer.
  const auto oblique = raycast(Ray2{v(-4, -3), v(8, 6)}, *Circle::make(v(1, 0), Fx(2)));
  ASSERT_TRUE(oblique.has_value());
  // |o + t d - c| = 2 with o - c = (-5, -3), d = (8, 6): 100 t^2 - 116 t + 30 = 0.
  const long double t = (116.0L - std::sqrt(116.0L * 116.0L - 4.0L * 100.0L * 30.0L)) / 200.0L;
  EXPECT_LE(std::fabs(oblique->fraction.raw() - t * 65536.0L), 1.0L);
  EXPECT_LE(std::abs(length(oblique->normal).raw() - 65536), 2);
  EXPECT_LT(dot(oblique->normal, v(8, 6)), Fx::zero());
}

TEST(FixedRaycastCircle, FollowsTheSharedRules) {
  const Circle c = *Circle::make(v(0, 0), Fx(1));
  EXPECT_FALSE(raycast(Ray2{v(0, 0), v(5, 0)}, c).has_value());    // inside
  EXPECT_FALSE(raycast(Ray2{v(-3, 0), v(0, 0)}, c).has_value());   // zero delta
  EXPECT_FALSE(raycast(Ray2{v(-3, 0), v(1, 0)}, c).has_value());   // too short
  EXPECT_FALSE(raycast(Ray2{v(-3, 0), v(-5, 0)}, c).has_value());  // away
  EXPECT_FALSE(raycast(Ray2{v(-1, 0), v(-5, 0)}, c).has_value());  // on it, leaving
  EXPECT_FALSE(raycast(Ray2{v(-3, 2), v(6, 0)}, c).has_value());   // passes above
  const auto tangent = raycast(Ray2{v(-3, 1), v(6, 0)}, c);
  ASSERT_TRUE(tangent.has_value());
  EXPECT_EQ(tangent->fraction, 0.5_fx);
  EXPECT_EQ(tangent->normal, v(0, 1));
  const auto exact_end = raycast(Ray2{v(-3, 0), v(2, 0)}, c);
  ASSERT_TRUE(exact_end.has_value());
  EXPECT_EQ(exact_end->fraction, Fx::one());
  const auto point = raycast(Ray2{v(-3, 0), v(6, 0)}, *Circle::make(v(0, 0), Fx::zero()));
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->fraction, 0.5_fx);
  EXPECT_EQ(point->normal, v(-1, 0));
}

TEST(FixedRaycastCircle, FarApartInputsStayInRange) {
  // Origin and center 60000 units apart on x: the reduced-resolution path.
  const Circle c = *Circle::make(v(30000, 0), Fx(100));
  const auto hit = raycast(Ray2{v(-30000, 0), Vec2(Fx::max(), Fx::zero())}, c);
  ASSERT_FALSE(hit.has_value());  // the sweep ends at about 2768
  const auto reaching =
      raycast(Ray2{v(-30000, 0), v(30000, 0)}, *Circle::make(v(30000, 0), Fx(30000)));
  ASSERT_TRUE(reaching.has_value());
  EXPECT_EQ(reaching->fraction, Fx::one());  // the sweep ends exactly on the circle
  EXPECT_EQ(reaching->point, v(0, 0));
  const auto at_edge = raycast(Ray2{Vec2(Fx::min(), Fx::min()), Vec2(Fx::max(), Fx::max())},
                               *Circle::make(Vec2(Fx(32000), Fx(32000)), Fx(1000)));
  EXPECT_FALSE(at_edge.has_value());
  const auto edge_hit = raycast(Ray2{Vec2(Fx(-32000), Fx(0)), Vec2(Fx::max(), Fx::zero())},
                                *Circle::make(Vec2(Fx(32000), Fx(0)), Fx(32000)));
  ASSERT_TRUE(edge_hit.has_value());
  EXPECT_LE(std::abs(edge_hit->point.x.raw()), 2);  // hits x = 0, one bit of resolution lost
}

TEST(FixedRaycastSegment, HitsWithNormalFacingTheRay) {
  const Segment2 wall{v(2, -2), v(2, 2)};
  const auto hit = raycast(Ray2{v(0, 0), v(4, 0)}, wall);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->fraction, 0.5_fx);
  EXPECT_EQ(hit->point, v(2, 0));
  EXPECT_EQ(hit->normal, v(-1, 0));
  const auto back = raycast(Ray2{v(4, 0), v(-4, 0)}, wall);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->normal, v(1, 0));
  const auto end = raycast(Ray2{v(0, 2), v(4, 0)}, wall);  // through the end point
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->point, v(2, 2));
  EXPECT_FALSE(raycast(Ray2{v(0, 3), v(4, 0)}, wall).has_value());    // misses the end
  EXPECT_FALSE(raycast(Ray2{v(2, -5), v(0, 10)}, wall).has_value());  // along it
  EXPECT_FALSE(raycast(Ray2{v(0, 0), v(1, 0)}, wall).has_value());    // too short
  EXPECT_FALSE(raycast(Ray2{v(0, 0), v(0, 0)}, wall).has_value());    // zero delta
  const auto diag = raycast(Ray2{v(0, 0), v(4, 4)}, Segment2{v(0, 4), v(4, 0)});
  ASSERT_TRUE(diag.has_value());
  EXPECT_EQ(diag->fraction, 0.5_fx);
  EXPECT_LE(std::abs(diag->normal.x.raw() + 46341), 1);  // -(1/sqrt 2)
  EXPECT_EQ(diag->normal.x, diag->normal.y);
}

}  // namespace
}  // namespace rwd::fixed
