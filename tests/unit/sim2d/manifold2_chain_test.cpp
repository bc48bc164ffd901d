// SPDX-License-Identifier: MIT
// Chain segments at the manifold level: the ghost vertices keep the joints
// of collinear edges flat (face normals only, where plain segments give a
// sideways normal at the shared vertex), nothing collides from behind, a
// convex corner still rounds, and the invariants of collide() hold.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "rewind/sim2d/chain2d.h"
#include "sim2d_test_util.h"

namespace rwd::sim2d::test {
namespace {

using detail::kWOne;

const V2 kUp{0, kWOne};

// A flat floor open upwards (right to left) with a joint at x = 0.
std::vector<Shape2D> flat_chain() {
  const std::array<Vec2, 3> points{{{4_fx, Fx()}, {Fx(), Fx()}, {-4_fx, Fx()}}};
  Result<std::vector<Shape2D>> chain = make_chain(points, false);
  EXPECT_TRUE(chain.ok()) << chain.status().message();
  return chain.ok() ? *chain : std::vector<Shape2D>(2);
}

std::vector<Shape2D> flat_segments() {
  return {ok(make_segment({4_fx, Fx()}, {Fx(), Fx()})),
          ok(make_segment({Fx(), Fx()}, {-4_fx, Fx()}))};
}

// The box whose bottom sinks 0.004 m into the floor and whose left face
// has just crossed the joint by 0.001 m: the shared vertex sits inside the
// box nearer its side face than its bottom face.
Xf box_over_joint() {
  return body(0.499_fx, 0.496_fx);
}

TEST(ManifoldChain, BoxAcrossACollinearJointGetsOnlyFaceNormals) {
  const Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  const Xf xb = box_over_joint();
  int points = 0;
  for (const Shape2D& edge : flat_chain()) {
    const Manifold2 m = collide(edge, Xf{}, box, xb);
    if (m.count == 0) continue;
    EXPECT_EQ(m.normal, kUp);
    for (int i = 0; i < m.count; ++i) {
      EXPECT_TRUE(near_w(m.points[i].separation, -detail::w_ratio(4, 1000), kFxUlp));
    }
    points += m.count;
  }
  EXPECT_GE(points, 2);
}

TEST(ManifoldChain, PlainSegmentsGiveASidewaysNormalAtTheSameJoint) {
  // The difference the ghosts make: the second plain segment meets the
  // box's side face, shallower than its bottom, and pushes sideways.
  const Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  const Manifold2 m = collide(flat_segments()[1], Xf{}, box, box_over_joint());
  ASSERT_GT(m.count, 0);
  EXPECT_EQ(m.normal, (V2{kWOne, 0}));
  // The chain edge in the same place answers with the floor's normal.
  const Manifold2 c = collide(flat_chain()[1], Xf{}, box, box_over_joint());
  ASSERT_GT(c.count, 0);
  EXPECT_EQ(c.normal, kUp);
}

TEST(ManifoldChain, CircleRollingOverTheJointMeetsAFlatFloor) {
  const Shape2D ball = ok(make_circle(0.5_fx));
  const std::vector<Shape2D> chain = flat_chain();
  const std::vector<Shape2D> plain = flat_segments();
  bool plain_tilted = false;
  for (int step = -40; step <= 40; ++step) {
    const Xf xb = body(Fx::from_raw(step * 328), 0.499_fx);  // x in about +-0.2 m
    int touching = 0;
    for (const Shape2D& edge : chain) {
      const Manifold2 m = collide(edge, Xf{}, ball, xb);
      if (m.count == 0) continue;
      ++touching;
      EXPECT_EQ(m.normal, kUp) << "x step " << step;
      EXPECT_TRUE(near_w(m.points[0].separation, -detail::w_ratio(1, 1000), kFxUlp));
    }
    EXPECT_GE(touching, 1) << "x step " << step;
    for (const Shape2D& edge : plain) {
      const Manifold2 m = collide(edge, Xf{}, ball, xb);
      if (m.count > 0 && m.normal.x != 0) plain_tilted = true;
    }
  }
  // Plain segments round their shared end: near the joint one of them
  // pushes the ball along a tilted normal.
  EXPECT_TRUE(plain_tilted);
}

TEST(ManifoldChain, CapsuleAcrossTheJointGetsOnlyFaceNormals) {
  // A capsule lying across the joint, sunk 0.002 m.
  const Shape2D capsule = ok(make_capsule({-0.5_fx, Fx()}, {0.5_fx, Fx()}, 0.25_fx));
  int points = 0;
  for (const Shape2D& edge : flat_chain()) {
    const Manifold2 m = collide(edge, Xf{}, capsule, body(0.25_fx, 0.248_fx));
    if (m.count == 0) continue;
    EXPECT_EQ(m.normal, kUp);
    points += m.count;
  }
  EXPECT_GE(points, 2);
}

TEST(ManifoldChain, ApartCornersMeetAlongTheLineBetweenThem) {
  // A ledge: flat to the left of (0, 0), a wall straight down below it
  // (the square end make_chain gives). A box whose corner is 0.01 m from
  // the ledge's corner along (1, 1) / sqrt(2), up and to the right: the
  // two corners are the nearest features and the joint admits that normal.
  const std::array<Vec2, 2> points{{{Fx(), Fx()}, {-4_fx, Fx()}}};
  const Shape2D edge = (*make_chain(points, false))[0];
  const Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  const Xf xb = body(0.5_fx + 0.00707_fx, 0.5_fx + 0.00707_fx);
  const Manifold2 m = collide(edge, Xf{}, box, xb);
  ASSERT_EQ(m.count, 1);
  EXPECT_TRUE(near_v(m.normal, V2{kWOne * 7071 / 10000, kWOne * 7071 / 10000}, kWOne >> 10));
  EXPECT_TRUE(near_w(m.points[0].separation, detail::w_ratio(1, 100), kWOne >> 12));
}

TEST(ManifoldChain, NothingCollidesFromBehind) {
  const Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  const Shape2D ball = ok(make_circle(0.5_fx));
  const Shape2D capsule = ok(make_capsule({-0.5_fx, Fx()}, {0.5_fx, Fx()}, 0.25_fx));
  const Shape2D edge = flat_chain()[0];
  const Shape2D plain = flat_segments()[0];
  // Under the floor, overlapping it from below.
  const Xf below = body(2_fx, -0.49_fx, 0.1_fx);
  const Xf capsule_below = body(2_fx, -0.24_fx);
  EXPECT_EQ(collide(edge, Xf{}, box, below).count, 0);
  EXPECT_EQ(collide(edge, Xf{}, ball, below).count, 0);
  EXPECT_EQ(collide(edge, Xf{}, capsule, capsule_below).count, 0);
  EXPECT_EQ(collide(box, below, edge, Xf{}).count, 0);
  // A plain segment pushes the same box down.
  const Manifold2 m = collide(plain, Xf{}, box, below);
  ASSERT_GT(m.count, 0);
  EXPECT_LT(m.normal.y, 0);
  // The same shapes above the floor do touch.
  EXPECT_GT(collide(edge, Xf{}, box, body(2_fx, 0.49_fx, 0.1_fx)).count, 0);
  EXPECT_GT(collide(edge, Xf{}, ball, body(2_fx, 0.49_fx)).count, 0);
  EXPECT_GT(collide(edge, Xf{}, capsule, body(2_fx, 0.24_fx)).count, 0);
}

TEST(ManifoldChain, ConvexCornerStillRounds) {
  // The floor bends down at (0, 0): flat to the right, a 45 degree slope
  // down to the left.
  const std::array<Vec2, 3> points{{{4_fx, Fx()}, {Fx(), Fx()}, {-4_fx, -4_fx}}};
  const std::vector<Shape2D> chain = *make_chain(points, false);
  // A ball over the corner, its centre along (-0.6, 0.8) from it: between
  // the two faces' normals, so the corner itself pushes along that line.
  const Shape2D ball = ok(make_circle(0.5_fx));
  const Xf ball_at = body(-0.2994_fx, 0.3992_fx);
  int ball_contacts = 0;
  for (const Shape2D& edge : chain) {
    const Manifold2 m = collide(edge, Xf{}, ball, ball_at);
    if (m.count == 0) continue;
    ++ball_contacts;
    EXPECT_TRUE(near_v(m.normal, V2{-detail::w_ratio(6, 10), detail::w_ratio(8, 10)}, kWOne >> 12));
  }
  EXPECT_GE(ball_contacts, 1);
  // A box tipped by 0.3 rad resting its bottom face on the corner: the
  // face normal is admitted, so the box pivots on the corner.
  const Shape2D box = ok(make_box(0.5_fx, 0.5_fx));
  const Xf box_at = body(-0.1472_fx, 0.4757_fx, 0.3_fx);
  const V2 face{-detail::w_ratio(29552, 100000), detail::w_ratio(95534, 100000)};
  int box_contacts = 0;
  for (const Shape2D& edge : chain) {
    const Manifold2 m = collide(edge, Xf{}, box, box_at);
    if (m.count == 0) continue;
    ++box_contacts;
    EXPECT_TRUE(near_v(m.normal, face, kWOne >> 12));
    EXPECT_LT(m.points[0].separation, 0);
  }
  EXPECT_GE(box_contacts, 1);
}

TEST(ManifoldChain, ConcaveJointSnapsToTheFaceNormal) {
  // A valley at (0, 0): the left edge rises to the left. A box resting on
  // the right edge with its corner at the valley gets the right edge's
  // face normal, never a normal from the valley vertex.
  const std::array<Vec2, 3> points{{{4_fx, Fx()}, {Fx(), Fx()}, {-4_fx, 4_fx}}};
  const std::vector<Shape2D> chain = *make_chain(points, false);
  const Shape2D box = ok(make_box(0.25_fx, 0.25_fx));
  const Manifold2 m = collide(chain[0], Xf{}, box, body(0.251_fx, 0.248_fx));
  ASSERT_GT(m.count, 0);
  EXPECT_EQ(m.normal, kUp);
}

TEST(ManifoldChain, ChainsAndSegmentsDoNotCollideWithEachOther) {
  const Shape2D edge = flat_chain()[0];
  const Shape2D plain = ok(make_segment({Fx(), -1_fx}, {Fx(), 1_fx}));
  EXPECT_EQ(collide(edge, Xf{}, plain, body(2_fx, Fx())).count, 0);
  EXPECT_EQ(collide(plain, body(2_fx, Fx()), edge, Xf{}).count, 0);
  EXPECT_EQ(collide(edge, Xf{}, edge, body(Fx(), 0.001_fx)).count, 0);
}

TEST(ManifoldChain, InvariantsOverManyPoses) {
  // Poses on a grid around a bent chain edge: unit normals, anchors naming
  // one point, nothing beyond the speculative distance, exact reversal,
  // and the same bits 30000 m away.
  const std::array<Vec2, 4> points{{{3_fx, 1_fx}, {1_fx, Fx()}, {-1_fx, Fx()}, {-3_fx, -1_fx}}};
  const Shape2D edge = (*make_chain(points, false))[1];
  const std::vector<Shape2D> movers = {
      ok(make_circle(0.375_fx)), ok(make_box(0.5_fx, 0.25_fx)),
      ok(make_capsule({-0.5_fx, Fx()}, {0.5_fx, 0.25_fx}, 0.125_fx)),
      ok(make_polygon(std::array<Vec2, 3>{{{Fx(), Fx()}, {0.75_fx, Fx()}, {0.25_fx, 0.5_fx}}},
                      0.0625_fx))};
  const Xf xa = body(0.25_fx, -0.125_fx, 0.2_fx);
  const V2 shift = wv(30000.0_fx, -20000.0_fx);
  int touching = 0;
  for (const Shape2D& b : movers) {
    for (int ix = -12; ix <= 12; ++ix) {
      for (int iy = -4; iy <= 8; ++iy) {
        for (int ia = 0; ia < 4; ++ia) {
          const Xf xb =
              body(Fx::from_raw(ix * 13107), Fx::from_raw(iy * 6554), Fx::from_raw(ia * 26214));
          const Manifold2 m = collide(edge, xa, b, xb);
          ASSERT_LE(m.count, 2);
          expect_reversed(m, collide(b, xb, edge, xa));
          const Manifold2 far = collide(edge, {xa.p + shift, xa.q}, b, {xb.p + shift, xb.q});
          ASSERT_EQ(far.count, m.count);
          EXPECT_EQ(far.normal, m.normal);
          if (m.count == 0) continue;
          ++touching;
          EXPECT_TRUE(near_w(detail::vlength_sq(m.normal), kWOne, kWOne >> 14));
          for (int i = 0; i < m.count; ++i) {
            EXPECT_LE(m.points[i].separation, kSpeculative);
            EXPECT_EQ(xa.p + m.points[i].anchor_a, xb.p + m.points[i].anchor_b);
            EXPECT_EQ(far.points[i].anchor_a, m.points[i].anchor_a);
            EXPECT_EQ(far.points[i].separation, m.points[i].separation);
          }
        }
      }
    }
  }
  EXPECT_GT(touching, 100);
}

}  // namespace
}  // namespace rwd::sim2d::test
