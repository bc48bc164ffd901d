// SPDX-License-Identifier: MIT
#include "rewind/fixed/intersect2.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "rewind/fixed/aabb2.h"
#include "rewind/fixed/circle.h"
#include "rewind/fixed/fx_literal.h"

namespace rwd::fixed {
namespace {

Vec2 v(int32_t x, int32_t y) {
  return {Fx(x), Fx(y)};
}
Vec2 raw_v(int32_t x, int32_t y) {
  return {Fx::from_raw(x), Fx::from_raw(y)};
}
Aabb2 box(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  return *Aabb2::make(v(x0, y0), v(x1, y1));
}
Circle circle(Vec2 c, Fx r) {
  return *Circle::make(c, r);
}

TEST(FixedAabb2, ConstructionValidatesAndLeavesNothingBehind) {
  const Result<Aabb2> bad = Aabb2::make(v(1, 0), v(0, 1));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(bad.status().message().find("exceeds"), std::string::npos);
  EXPECT_FALSE(Aabb2::from_center(v(0, 0), v(-1, 1)).ok());
  EXPECT_EQ(*Aabb2::from_center(v(1, 1), v(2, 3)), box(-1, -2, 3, 4));
  // Near the edge the corners saturate and the box stays valid.
  const Aabb2 edge = *Aabb2::from_center(v(32000, 0), v(2000, 1));
  EXPECT_EQ(edge.upper.x, Fx::max());
  EXPECT_FALSE(Circle::make(v(0, 0), Fx::from_raw(-1)).ok());
  EXPECT_TRUE(Circle::make(v(0, 0), Fx::zero()).ok());
}

TEST(FixedAabb2, OverlapContainUnionTranslate) {
  EXPECT_TRUE(overlaps(box(0, 0, 2, 2), box(2, 2, 3, 3)));  // touching corner
  EXPECT_FALSE(overlaps(box(0, 0, 2, 2), *Aabb2::make(raw_v(2 * 65536 + 1, 0), v(3, 1))));
  EXPECT_TRUE(contains(box(0, 0, 2, 2), v(2, 1)));
  EXPECT_FALSE(contains(box(0, 0, 2, 2), raw_v(-1, 0)));
  EXPECT_TRUE(contains(box(-5, -5, 5, 5), box(0, 0, 5, 5)));
  EXPECT_FALSE(contains(box(-5, -5, 5, 5), box(0, 0, 6, 5)));
  EXPECT_EQ(union_of(box(0, 0, 1, 1), box(-3, 2, -2, 4)), box(-3, 0, 1, 4));
  EXPECT_EQ(translated(box(0, 0, 1, 1), v(2, -1)), box(2, -1, 3, 0));
  EXPECT_EQ(center(box(-32768, -32768, 32767, 32767)),
            raw_v(-32768, -32768));  // (-2^31 + 32767*2^16) / 2, floored
  EXPECT_EQ(center(box(0, 0, 4, 2)), v(2, 1));
}

TEST(FixedCircle, OverlapsExactlyAtTheBoundary) {
  // 3-4-5: centers 5 apart, radii summing to exactly 5 touch.
  EXPECT_TRUE(overlaps(circle(v(0, 0), Fx(2)), circle(v(3, 4), Fx(3))));
  EXPECT_FALSE(overlaps(circle(v(0, 0), Fx(2)), circle(v(3, 4), Fx(3) - Fx::epsilon())));
  EXPECT_TRUE(contains(circle(v(0, 0), Fx(5)), v(-3, -4)));
  EXPECT_FALSE(contains(circle(v(0, 0), Fx(5)), raw_v(-3 * 65536 - 1, -4 * 65536)));
  // Opposite range edges: the difference needs 33 bits.
  EXPECT_FALSE(overlaps(circle(Vec2(Fx::min(), Fx::min()), Fx::max()),
                        circle(Vec2(Fx::max(), Fx::max()), Fx::max())));
  // Centers 2^32 - 2 raw apart, radii summing to exactly that: touching.
  const Vec2 left(Fx::min(), Fx::zero());
  const Vec2 right(Fx::max() - Fx::epsilon(), Fx::zero());
  EXPECT_TRUE(overlaps(circle(left, Fx::max()), circle(right, Fx::max())));
  EXPECT_FALSE(overlaps(circle(left, Fx::max()), circle(right, Fx::max() - Fx::epsilon())));
}

TEST(FixedCircle, OverlapsAabbIncludingCorners) {
  const Aabb2 b = box(0, 0, 4, 4);
  EXPECT_TRUE(overlaps(circle(v(2, 2), Fx::zero()), b));  // center inside
  EXPECT_TRUE(overlaps(circle(v(-1, 2), Fx(1)), b));      // touching a side
  EXPECT_FALSE(overlaps(circle(v(-1, 2), Fx(1) - Fx::epsilon()), b));
  EXPECT_TRUE(overlaps(b, circle(v(7, 8), Fx(5))));  // corner (4,4): 3-4-5
  EXPECT_FALSE(overlaps(circle(v(7, 8), Fx(5) - Fx::epsilon()), b));
}

TEST(FixedSegment2, IntersectsCrossingTouchingAndCollinear) {
  EXPECT_TRUE(intersects({v(0, 0), v(4, 4)}, {v(0, 4), v(4, 0)}));
  EXPECT_TRUE(intersects({v(0, 0), v(4, 0)}, {v(4, 0), v(5, 3)}));   // shared end
  EXPECT_TRUE(intersects({v(0, 0), v(4, 0)}, {v(2, 0), v(2, 3)}));   // T junction
  EXPECT_TRUE(intersects({v(0, 0), v(4, 0)}, {v(3, 0), v(9, 0)}));   // collinear overlap
  EXPECT_FALSE(intersects({v(0, 0), v(4, 0)}, {v(5, 0), v(9, 0)}));  // collinear, apart
  EXPECT_FALSE(intersects({v(0, 0), v(4, 0)}, {v(0, 1), v(4, 1)}));  // parallel
  EXPECT_FALSE(intersects({v(0, 0), v(4, 4)}, {v(3, 0), raw_v(4 * 65536 - 1, 0)}));
  EXPECT_TRUE(intersects({v(2, 2), v(2, 2)}, {v(0, 0), v(4, 4)}));  // a point on it
  const Segment2 huge{Vec2(Fx::min(), Fx::min()), Vec2(Fx::max(), Fx::max())};
  EXPECT_TRUE(intersects(huge, {Vec2(Fx::min(), Fx::max()), Vec2(Fx::max(), Fx::min())}));
}

TEST(FixedPolygon, ContainsWithBoundaryAndConcaveShapes) {
  // An L shape (concave), counter-clockwise.
  const std::array<Vec2, 6> l = {v(0, 0), v(4, 0), v(4, 1), v(1, 1), v(1, 4), v(0, 4)};
  EXPECT_TRUE(*polygon_contains(l, v(2, 0)));  // on an edge
  EXPECT_TRUE(*polygon_contains(l, v(4, 1)));  // a vertex
  EXPECT_TRUE(*polygon_contains(l, 0.5_fx * v(1, 5)));
  EXPECT_FALSE(*polygon_contains(l, v(2, 2)));             // in the notch
  EXPECT_FALSE(*polygon_contains(l, v(-1, 1)));            // level with a vertex, outside
  EXPECT_TRUE(*polygon_contains(l, Vec2(0.5_fx, Fx(1))));  // level with vertex (1,1), inside
  // The same polygon wound clockwise gives the same answers.
  const std::array<Vec2, 6> cw = {v(0, 4), v(1, 4), v(1, 1), v(4, 1), v(4, 0), v(0, 0)};
  EXPECT_FALSE(*polygon_contains(cw, v(2, 2)));
  EXPECT_TRUE(*polygon_contains(cw, Vec2(0.5_fx, 0.5_fx)));
  const std::array<Vec2, 2> line = {v(0, 0), v(1, 1)};
  const Result<bool> bad = polygon_contains(line, v(0, 0));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::fixed
