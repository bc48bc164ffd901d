// SPDX-License-Identifier: MIT
// The one polygon clipping rule (sim/src/d3/polygon_clip.h): a square cut
// by a turned square's sides is the regular octagon, a polygon inside is
// kept whole and one outside vanishes, a vertex on the plane is kept once
// (not doubled by a crossing), segments and points clip as such, crossings
// say whether they leave or enter, and the capacity is never exceeded.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "d3/polygon_clip.h"

namespace rwd::sim::d3 {
namespace {

struct P2 {
  float x;
  float y;
};

constexpr int kCap = 16;

// Keeps the part of `poly` where nx x + ny y <= offset.
std::vector<P2> cut(const std::vector<P2>& poly, float nx, float ny, float offset) {
  float dist[kCap];
  for (size_t i = 0; i < poly.size(); ++i) dist[i] = nx * poly[i].x + ny * poly[i].y - offset;
  P2 out[kCap];
  const int n = clip_polygon<kCap>(poly.data(), dist, static_cast<int>(poly.size()), out,
                                   [](const P2& p, const P2& q, float t, bool) {
                                     return P2{p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t};
                                   });
  return {out, out + n};
}

std::vector<P2> unit_square() {
  return {{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}};
}

float area(const std::vector<P2>& p) {
  float sum = 0.0f;
  for (size_t i = 0; i < p.size(); ++i) {
    const P2& a = p[i];
    const P2& b = p[(i + 1) % p.size()];
    sum += a.x * b.y - a.y * b.x;
  }
  return 0.5f * sum;
}

TEST(PolygonClip, SquareCutByATurnedSquareIsTheOctagon) {
  // The square [-1, 1]^2 turned 45 degrees about its centre: sides at
  // distance 1 along (+-1, +-1) / sqrt(2).
  const float s = std::sqrt(0.5f);
  std::vector<P2> poly = unit_square();
  const float normals[4][2] = {{s, s}, {-s, s}, {-s, -s}, {s, -s}};
  for (const auto& n : normals) poly = cut(poly, n[0], n[1], 1.0f);
  ASSERT_EQ(poly.size(), 8u);
  // Every corner is cut off by a right triangle with legs 2 - sqrt(2).
  const float leg = 2.0f - std::sqrt(2.0f);
  EXPECT_NEAR(area(poly), 4.0f - 2.0f * leg * leg, 1e-5f);
  for (const P2& p : poly) {
    EXPECT_LE(std::fabs(p.x), 1.0f + 1e-6f);
    EXPECT_LE(std::fabs(p.y), 1.0f + 1e-6f);
    EXPECT_LE(std::fabs(p.x) + std::fabs(p.y), std::sqrt(2.0f) + 1e-5f);
  }
}

TEST(PolygonClip, InsideIsKeptWholeAndOutsideVanishes) {
  const std::vector<P2> inside = cut(unit_square(), 1.0f, 0.0f, 5.0f);
  ASSERT_EQ(inside.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(inside[i].x, unit_square()[i].x);
    EXPECT_EQ(inside[i].y, unit_square()[i].y);
  }
  EXPECT_TRUE(cut(unit_square(), 1.0f, 0.0f, -5.0f).empty());
}

TEST(PolygonClip, AVertexOnThePlaneIsKeptOnce) {
  // The plane x <= 1 passes through two corners: nothing is cut and
  // nothing is doubled.
  EXPECT_EQ(cut(unit_square(), 1.0f, 0.0f, 1.0f).size(), 4u);
  // x + y <= 0 passes through two opposite corners: a triangle of three
  // distinct corners, with no crossing beside them.
  const std::vector<P2> half = cut(unit_square(), 1.0f, 1.0f, 0.0f);
  ASSERT_EQ(half.size(), 3u);
  EXPECT_NEAR(area(half), 2.0f, 1e-6f);
  float dist[4] = {0.0f, -1.0f, 0.0f, 1.0f};
  ClipStep steps[8];
  ASSERT_EQ(clip_by_plane(dist, 4, steps, 8), 3);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(steps[i].kind, ClipStep::kKept);
}

TEST(PolygonClip, CrossingsSayWhetherTheyLeaveOrEnter) {
  // Vertex 0 inside, 1 and 2 outside: leaves on side 0 -> 1, enters on
  // side 2 -> 0, in the polygon's order.
  const float dist[3] = {-1.0f, 1.0f, 3.0f};
  ClipStep steps[8];
  ASSERT_EQ(clip_by_plane(dist, 3, steps, 8), 3);
  EXPECT_EQ(steps[0].kind, ClipStep::kKept);
  EXPECT_EQ(steps[0].from, 0);
  EXPECT_EQ(steps[1].kind, ClipStep::kLeaving);
  EXPECT_EQ(steps[1].from, 0);
  EXPECT_EQ(steps[1].to, 1);
  EXPECT_EQ(steps[1].t, 0.5f);
  EXPECT_EQ(steps[2].kind, ClipStep::kEntering);
  EXPECT_EQ(steps[2].from, 2);
  EXPECT_EQ(steps[2].to, 0);
  EXPECT_EQ(steps[2].t, 0.75f);
}

TEST(PolygonClip, SegmentsAndPointsAreNotClosed) {
  // A segment from inside to outside keeps its inside end and the crossing,
  // and no second crossing on the way back.
  const std::vector<P2> seg = cut({{0.0f, 0.0f}, {4.0f, 0.0f}}, 1.0f, 0.0f, 1.0f);
  ASSERT_EQ(seg.size(), 2u);
  EXPECT_EQ(seg[0].x, 0.0f);
  EXPECT_EQ(seg[1].x, 1.0f);
  // Outside to inside: the crossing replaces the first end, in place.
  const std::vector<P2> back = cut({{4.0f, 0.0f}, {0.0f, 0.0f}}, 1.0f, 0.0f, 1.0f);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].x, 1.0f);
  EXPECT_EQ(back[1].x, 0.0f);
  EXPECT_EQ(cut({{0.5f, 0.0f}}, 1.0f, 0.0f, 1.0f).size(), 1u);
  EXPECT_TRUE(cut({{1.5f, 0.0f}}, 1.0f, 0.0f, 1.0f).empty());
}

TEST(PolygonClip, NaNDistancesAreNeitherKeptNorCrossed) {
  const float dist[4] = {-1.0f, NAN, -1.0f, -1.0f};
  ClipStep steps[8];
  EXPECT_EQ(clip_by_plane(dist, 4, steps, 8), 3);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(steps[i].kind, ClipStep::kKept);
}

TEST(PolygonClip, NeverWritesPastTheCapacity) {
  // Alternating signs: every vertex of the 8 is kept or crossed, 12 steps
  // in all (a polygon rounding has bent out of convexity); a capacity of 5
  // gets the first 5 and the slot after them is untouched.
  const float dist[8] = {-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f};
  ClipStep all[16];
  ASSERT_EQ(clip_by_plane(dist, 8, all, 16), 12);
  ClipStep steps[6];
  steps[5].kind = ClipStep::kKept;
  steps[5].from = 999;
  ASSERT_EQ(clip_by_plane(dist, 8, steps, 5), 5);
  EXPECT_EQ(steps[5].from, 999);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(steps[i].kind, all[i].kind);
    EXPECT_EQ(steps[i].from, all[i].from);
  }
}

}  // namespace
}  // namespace rwd::sim::d3
