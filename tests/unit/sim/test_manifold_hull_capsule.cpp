// SPDX-License-Identifier: MIT
// Hull-capsule manifolds against box-capsule and GJK/EPA answers.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>
#include "d3/gjk.h"
#include "d3/manifold.h"
#include "d3/manifold_hull.h"
#include "hull_round_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace hull_round_test;

// ---- Hull-capsule ------------------------------------------------------------

CapsulePose capsule_at(Vec3 center, Vec3 axis, float half_height, float radius) {
  return CapsulePose{center, normalize_or_zero(axis), half_height, radius};
}

// Local capsule placed in the world by the box pose.
CapsulePose to_world(const CapsulePose& local, Vec3 pos, const Mat3& axes) {
  return CapsulePose{pos + axes * local.center, axes * local.axis, local.half_height, local.radius};
}

TEST(HullCapsule, MatchesBoxCapsuleInEveryConfiguration) {
  const Vec3 half{1.0f, 0.5f, 0.75f};
  const Hull hull = make_box_hull(half);
  const Quat q = turn(Quat{-0.2f, 0.1f, 0.3f, 0.9f});
  const Mat3 axes = mat3_from_quat(q);
  const Vec3 pos{-1.0f, 3.0f, 2.0f};
  const BoxPose box{pos, q, half};
  const CapsulePose cases[] = {
      // Lying on +y, 0.01 into it: two points.
      capsule_at({0.2f, 0.5f + 0.2f - 0.01f, 0.1f}, {1.0f, 0.0f, 0.2f}, 0.6f, 0.2f),
      // Lying on +y hanging over the +x edge: clipped at the edge.
      capsule_at({1.0f, 0.5f + 0.2f - 0.01f, 0.1f}, {1.0f, 0.0f, 0.0f}, 0.6f, 0.2f),
      // Lying along -z, slightly tilted (within the parallel limit).
      capsule_at({0.1f, 0.0f, -0.75f - 0.3f + 0.02f}, {0.0f, 1.0f, 0.05f}, 0.3f, 0.3f),
      // Leaning over +y: one point at the lower end.
      capsule_at({0.0f, 0.5f + 0.2f + 0.5f, 0.0f}, {0.3f, 1.0f, 0.0f}, 0.5f, 0.2f),
      // Beside the +x +z edge, crossing it: one point.
      capsule_at({1.2f, 0.0f, 0.95f}, {1.0f, 0.2f, -1.0f}, 0.4f, 0.1f),
      // Off the (+, +, +) corner, end on.
      capsule_at({1.3f, 0.8f, 1.1f}, {1.0f, 1.0f, 1.0f}, 0.3f, 0.25f),
      // Reaching into +x (segment end 0.1 inside): face axis.
      capsule_at({1.0f + 0.5f - 0.1f, 0.1f, 0.0f}, {1.0f, 0.0f, 0.1f}, 0.5f, 0.1f),
      // Cutting the +x +y edge: edge axis, one point.
      capsule_at({0.95f, 0.45f, 0.0f}, {1.0f, -1.0f, 0.0f}, 1.0f, 0.05f),
      // Lying on +y but 0.05 above: speculative two points, then dropped.
      capsule_at({0.2f, 0.5f + 0.2f + 0.015f, 0.1f}, {1.0f, 0.0f, 0.0f}, 0.6f, 0.2f),
      capsule_at({0.2f, 0.5f + 0.2f + 0.03f, 0.1f}, {1.0f, 0.0f, 0.0f}, 0.6f, 0.2f),
  };
  int n = 0;
  for (const CapsulePose& c : cases) {
    const CapsulePose w = to_world(c, pos, axes);
    Manifold mh;
    Manifold mb;
    collide_hull_capsule(hull, pos, axes, w, kSpec, mh);
    collide_box_capsule(box, w, kSpec, mb);
    expect_same(mh, mb, "capsule", n);
    ++n;
  }
}

TEST(HullCapsule, LyingFlatGivesTwoPointsWithStableIds) {
  const Hull hull = make_box_hull({1.0f, 0.5f, 1.0f});
  const Mat3 id;
  Manifold m;
  // Along x on the top face (face 3), 0.01 into it.
  collide_hull_capsule(hull, {}, id, capsule_at({0.1f, 0.69f, 0.2f}, {1, 0, 0}, 0.5f, 0.2f), kSpec,
                       m);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.495f, kTol);
    EXPECT_EQ(m.points[i].feature_id, (1u << 16) | (3u << 8) | i);
  }
  EXPECT_NEAR(m.points[0].point.x, -0.4f, kTol);
  EXPECT_NEAR(m.points[1].point.x, 0.6f, kTol);
  // Tipped a little (sin 0.05): still two points, the lower end deeper.
  collide_hull_capsule(hull, {}, id, capsule_at({0.1f, 0.69f, 0.2f}, {1, 0.05f, 0}, 0.5f, 0.2f),
                       kSpec, m);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_LT(m.points[0].separation, m.points[1].separation);
  EXPECT_EQ(m.points[0].feature_id, (1u << 16) | (3u << 8) | 0u);
  // Tipped past the limit: one point, the lower (-axis) end's id kept.
  collide_hull_capsule(hull, {}, id, capsule_at({0.1f, 0.8f, 0.2f}, {1, 0.4f, 0}, 0.5f, 0.2f),
                       kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (1u << 16) | (3u << 8) | 0u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  // Hanging over the +x edge: clipped there (within the 1 mm margin).
  collide_hull_capsule(hull, {}, id, capsule_at({1.0f, 0.69f, 0.2f}, {1, 0, 0}, 0.5f, 0.2f), kSpec,
                       m);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.points[0].point.x, 0.5f, kTol);
  EXPECT_NEAR(m.points[1].point.x, 1.001f, kTol);
}

TEST(HullCapsule, SlantedTriangleFace) {
  // On the tetrahedron's slanted face, along the direction (1, -1, 0):
  // clipped by the triangle's sides.
  const Hull hull = make_tetra_hull();
  const Mat3 id;
  const Vec3 n = Vec3{1.0f, 1.0f, 1.0f} * (1.0f / std::sqrt(3.0f));
  const Vec3 face_center = Vec3{1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f} - Vec3{0.25f, 0.25f, 0.25f};
  const float r = 0.1f;
  Manifold m;
  const CapsulePose cap = capsule_at(face_center + n * (r - 0.01f), {1, -1, 0}, 2.0f, r);
  collide_hull_capsule(hull, {}, id, cap, kSpec, m);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.x, n.x, kTol);
  EXPECT_NEAR(m.normal.y, n.y, kTol);
  EXPECT_NEAR(m.normal.z, n.z, kTol);
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_EQ(m.points[i].feature_id, (1u << 16) | (3u << 8) | i);
  }
  // The line through the face centre along (1, -1, 0) (parallel to the
  // side z = 0) leaves the triangle on its sides x = 0 and y = 0, at
  // (2/3, 0, 1/3) and (0, 2/3, 1/3) less the centroid: 2 sqrt(2) / 3
  // apart, plus the 1 mm clip margin at each end met at 30 degrees.
  const Vec3 span = m.points[1].point - m.points[0].point;
  const float margin = 0.001f / (0.5f * std::sqrt(3.0f));
  EXPECT_NEAR(length(span), 2.0f * std::sqrt(2.0f) / 3.0f + 2.0f * margin, 1e-5f);
}

TEST(HullCapsule, RandomPosesMatchBoxCapsule) {
  test::Rng rng{57};
  int compared = 0;
  int two = 0;
  int border = 0;
  for (int n = 0; n < 3000; ++n) {
    const Vec3 half{rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f)};
    const Hull hull = make_box_hull(half);
    const Quat q = rng.rotation();
    const Mat3 axes = mat3_from_quat(q);
    const Vec3 pos{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    Vec3 u{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    Vec3 local{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    const float hh = rng.uniform(0.0f, 1.0f);
    const float r = rng.uniform(0.05f, 0.6f);
    // Half the cases lie nearly flat on a face, as capsules at rest do.
    if (n % 2 == 0) {
      const int axis = static_cast<int>(rng.next() % 3);
      const float side = (rng.next() & 1) ? 1.0f : -1.0f;
      const float height = side * (component(half, axis) + r + rng.uniform(-0.1f, 0.03f));
      float uc[3] = {u.x, u.y, u.z};
      float lc[3] = {rng.uniform(-half.x - 0.5f, half.x + 0.5f),
                     rng.uniform(-half.y - 0.5f, half.y + 0.5f),
                     rng.uniform(-half.z - 0.5f, half.z + 0.5f)};
      uc[axis] *= 0.05f;
      lc[axis] = height;
      u = {uc[0], uc[1], uc[2]};
      local = {lc[0], lc[1], lc[2]};
    }
    u = normalize_or_zero(u);
    const CapsulePose cap = to_world(CapsulePose{local, u, hh, r}, pos, axes);
    Manifold mb;
    collide_box_capsule(BoxPose{pos, q, half}, cap, kSpec, mb);
    Manifold mh;
    collide_hull_capsule(hull, pos, axes, cap, kSpec, mh);
    // Skip what is ill-posed for a comparison: near the parallel limit,
    // near touching cores, and near-ties between axes (either answer is
    // right there, and the routines break ties differently).
    const Vec3 p0 = local - u * hh;
    const Vec3 p1 = local + u * hh;
    bool borderline = false;
    for (int i = 0; i < 3; ++i) {
      if (std::fabs(std::fabs(component(u, i)) - 0.1f) < 0.01f) borderline = true;
    }
    // Ends and the segment's distance to the box surface.
    float dist_sq = 1e30f;
    for (int k = 0; k <= 64; ++k) {
      const Vec3 p = p0 + (p1 - p0) * (static_cast<float>(k) / 64.0f);
      const Vec3 c = min(max(p, -half), half);
      dist_sq = std::min(dist_sq, length_squared(p - c));
    }
    if (dist_sq < 1e-4f) borderline = true;  // the segment within 1 cm: SAT territory
    if (borderline) continue;
    ASSERT_EQ(mb.point_count > 0, mh.point_count > 0) << n;
    if (mb.point_count != mh.point_count || length(mh.normal - mb.normal) > 1e-5f) {
      // One routine saw a face, the other an edge just beyond it (the
      // closest point within a hair of the face's border): both are right
      // if they nearly agree on the normal and the deepest separation.
      float deepest_b = mb.points[0].separation;
      float deepest_h = mh.points[0].separation;
      for (uint32_t i = 1; i < mb.point_count; ++i) {
        deepest_b = std::min(deepest_b, mb.points[i].separation);
      }
      for (uint32_t i = 1; i < mh.point_count; ++i) {
        deepest_h = std::min(deepest_h, mh.points[i].separation);
      }
      EXPECT_NEAR(deepest_h, deepest_b, 1e-4f) << n;
      EXPECT_LT(length(mh.normal - mb.normal), 1e-3f) << n;
      ++border;
      continue;
    }
    expect_same(mh, mb, "random capsule", n);
    if (mb.point_count == 2) ++two;
    ++compared;
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(two, 100);
  EXPECT_LT(border, 10);
}

TEST(HullCapsule, FeatureIdsForEdgesAndAxes) {
  const Hull hull = make_box_hull({1.0f, 1.0f, 1.0f});
  const Mat3 id;
  Manifold m;
  // Across the edge between vertices 3 (+,+,-) and 7 (+,+,+), outside.
  collide_hull_capsule(hull, {}, id, capsule_at({1.1f, 1.1f, 0.0f}, {1, -1, 0.2f}, 0.5f, 0.2f),
                       kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (2u << 16) | (7u << 8) | 3u);
  // Cutting that edge (segment reaching in): the edge axis, whichever index
  // the edge has.
  collide_hull_capsule(hull, {}, id, capsule_at({0.95f, 0.95f, 0.0f}, {1, -1, 0}, 1.0f, 0.05f),
                       kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  const uint32_t e = m.points[0].feature_id & 0xFFFFu;
  EXPECT_EQ(m.points[0].feature_id >> 16, 4u);
  ASSERT_LT(e, hull.edges.size());
  const HullEdge& edge = hull.edges[e];
  EXPECT_TRUE((edge.v0 == 3 && edge.v1 == 7) || (edge.v0 == 7 && edge.v1 == 3));
  const float h = std::sqrt(0.5f);
  EXPECT_NEAR(m.normal.x, h, kTol);
  EXPECT_NEAR(m.normal.y, h, kTol);
  EXPECT_NEAR(m.points[0].separation, (1.9f - 2.0f) * h - 0.05f, kTol);
}

TEST(HullCapsule, OutOfReachAndDegenerate) {
  const Hull hull = make_box_hull({1.0f, 1.0f, 1.0f});
  const Mat3 id;
  Manifold m;
  collide_hull_capsule(hull, {}, id, capsule_at({0.0f, 1.5f, 0.0f}, {1, 0, 0}, 0.5f, 0.4f), kSpec,
                       m);
  EXPECT_EQ(m.point_count, 0u);  // 0.1 apart
  collide_hull_capsule(hull, {}, id, capsule_at({2.0f, 2.0f, 2.0f}, {1, 0, 0}, 0.5f, 0.4f), kSpec,
                       m);
  EXPECT_EQ(m.point_count, 0u);
  // A capsule of no length is a sphere.
  Manifold ms;
  collide_hull_capsule(hull, {}, id, capsule_at({0.3f, 1.2f, -0.2f}, {0, 1, 0}, 0.0f, 0.25f), kSpec,
                       m);
  collide_hull_sphere(hull, {}, id, {0.3f, 1.2f, -0.2f}, 0.25f, kSpec, ms);
  ASSERT_EQ(m.point_count, 1u);
  ASSERT_EQ(ms.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, ms.points[0].separation, kTol);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  // Wholly inside: out through the nearest face, two points along it.
  collide_hull_capsule(hull, {}, id, capsule_at({0.1f, 0.7f, 0.0f}, {0, 0, 1}, 0.3f, 0.1f), kSpec,
                       m);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.4f, kTol);
}

TEST(HullCapsule, SameBitsTwice) {
  const Hull hull = make_box_hull({0.5f, 0.7f, 0.9f});
  const Mat3 axes = mat3_from_quat(turn(Quat{0.3f, -0.1f, 0.2f, 0.8f}));
  const CapsulePose caps[3] = {capsule_at({0.9f, 0.8f, 0.1f}, {1, 0, 0}, 0.5f, 0.3f),
                               capsule_at({0.2f, 0.1f, 0.3f}, {0, 1, 1}, 0.5f, 0.3f),
                               capsule_at({0.1f, 1.1f, -0.2f}, {0, 0.02f, 1}, 0.5f, 0.4f)};
  for (const CapsulePose& c : caps) {
    Manifold m1;
    Manifold m2;
    collide_hull_capsule(hull, {0.1f, 0.2f, 0.3f}, axes, c, kSpec, m1);
    collide_hull_capsule(hull, {0.1f, 0.2f, 0.3f}, axes, c, kSpec, m2);
    EXPECT_GT(m1.point_count, 0u);
    expect_same_bits(m1, m2);
  }
}

}  // namespace
}  // namespace rwd::sim::d3
