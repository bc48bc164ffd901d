// SPDX-License-Identifier: MIT
// Invariants of collide() over many seeded random pairs of every shape
// type: bounded point count, unit normal, anchors naming one world point,
// nothing beyond the speculative distance, exact reversal for the pairs the
// table reverses, and bit-identical answers after a large translation.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "sim2d_test_util.h"

namespace rwd::sim2d::test {
namespace {

using detail::kWOne;

// A small seeded generator (64-bit LCG, top bits) so the cases are the same
// on every machine.
struct Lcg {
  uint64_t state;
  uint32_t next() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  }
  /// A raw Fx uniformly in [-span, span] whole units.
  Fx fx(int32_t span) {
    const int64_t range = int64_t{2} * span * Fx::kOneRaw + 1;
    return Fx::from_raw(
        static_cast<int32_t>(static_cast<int64_t>(next() % range) - int64_t{span} * Fx::kOneRaw));
  }
  Fx positive(int32_t max_raw) { return Fx::from_raw(1 << 12) + Fx::from_raw(next() % max_raw); }
};

std::vector<Shape2D> shape_set() {
  std::vector<Shape2D> s;
  s.push_back(ok(make_circle(0.5_fx)));
  s.push_back(ok(make_circle(0.25_fx, {0.5_fx, -0.25_fx})));
  s.push_back(ok(make_capsule({-0.75_fx, 0.0_fx}, {0.5_fx, 0.25_fx}, 0.25_fx)));
  s.push_back(ok(make_box(0.5_fx, 0.25_fx)));
  s.push_back(ok(make_box(1.0_fx, 0.125_fx, {0.25_fx, 0.5_fx}, 0.6_fx)));
  s.push_back(ok(make_polygon(
      std::array<Vec2, 3>{{{0.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, {0.25_fx, 0.75_fx}}}, 0.0625_fx)));
  s.push_back(ok(make_polygon(std::array<Vec2, 6>{{{1.0_fx, 0.0_fx},
                                                   {0.5_fx, 0.875_fx},
                                                   {-0.5_fx, 0.875_fx},
                                                   {-1.0_fx, 0.0_fx},
                                                   {-0.5_fx, -0.875_fx},
                                                   {0.5_fx, -0.875_fx}}})));
  s.push_back(ok(make_segment({-2.0_fx, 0.0_fx}, {2.0_fx, 0.5_fx})));
  return s;
}

bool table_reversed(ShapeType2D a, ShapeType2D b) {
  const bool a_round = a == ShapeType2D::kCircle;
  const bool b_round = b == ShapeType2D::kCircle;
  if (a_round != b_round) return a_round;
  // Segments are always A against polygons and capsules.
  return b == ShapeType2D::kSegment && a != ShapeType2D::kSegment && !a_round;
}

TEST(Manifold2Property, InvariantsOverRandomPairs) {
  const std::vector<Shape2D> shapes = shape_set();
  Lcg rng{12345};
  const W speculative = kSpeculative;
  int touching = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    const Shape2D& a = shapes[rng.next() % shapes.size()];
    const Shape2D& b = shapes[rng.next() % shapes.size()];
    const Xf xa = body(rng.fx(2), rng.fx(2), rng.fx(4));
    const Xf xb = body(rng.fx(2), rng.fx(2), rng.fx(4));
    const Manifold2 m = collide(a, xa, b, xb, speculative);
    ASSERT_GE(m.count, 0);
    ASSERT_LE(m.count, 2);
    if (m.count == 0) continue;
    ++touching;
    EXPECT_TRUE(near_w(detail::vlength_sq(m.normal), kWOne, kWOne >> 14)) << "iteration " << iter;
    for (int i = 0; i < m.count; ++i) {
      const detail::ManifoldPoint2& p = m.points[i];
      EXPECT_LE(p.separation, speculative);
      EXPECT_EQ(xa.p + p.anchor_a, xb.p + p.anchor_b);
    }
    if (m.count == 2) {
      EXPECT_NE(m.points[0].id, m.points[1].id);
    }
    if (table_reversed(a.type, b.type)) {
      expect_reversed(collide(b, xb, a, xa, speculative), m);
    }
    // The same pair 30000 m away answers with the same bits.
    const V2 shift = wv(30000.0_fx, -20000.0_fx);
    const Manifold2 far = collide(a, {xa.p + shift, xa.q}, b, {xb.p + shift, xb.q}, speculative);
    ASSERT_EQ(far.count, m.count);
    EXPECT_EQ(far.normal, m.normal);
    for (int i = 0; i < m.count; ++i) {
      EXPECT_EQ(far.points[i].anchor_a, m.points[i].anchor_a);
      EXPECT_EQ(far.points[i].separation, m.points[i].separation);
      EXPECT_EQ(far.points[i].id, m.points[i].id);
    }
  }
  // The poses are close enough that a good share of pairs touch.
  EXPECT_GT(touching, 500);
}

}  // namespace
}  // namespace rwd::sim2d::test
