// SPDX-License-Identifier: MIT
// Box-box manifolds: face-face (4 points), a box turned 45 degrees on a
// larger one, clipping to 8 candidates reduced to 4, edge-edge, separation
// beyond the speculative distance, and feature-id persistence. Tolerance
// 1e-5 m unless stated.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::d3 {
namespace {

constexpr float kTol = 1e-5f;
constexpr float kSpec = 0.02f;
const float kHalfSqrt2 = std::sqrt(0.5f);

Quat about_y(float c, float s) {
  return {0.0f, s, 0.0f, c};
}  // c = cos(a/2), s = sin(a/2)

bool has_point(const Manifold& m, Vec3 p, float tol) {
  for (uint32_t i = 0; i < m.point_count; ++i) {
    Vec3 d = m.points[i].point - p;
    if (std::fabs(d.x) < tol && std::fabs(d.y) < tol && std::fabs(d.z) < tol) return true;
  }
  return false;
}

TEST(ManifoldBoxBox, FaceFaceGivesFourCorners) {
  BoxPose ground{{0.0f, 0.0f, 0.0f}, Quat{}, {2.0f, 0.5f, 2.0f}};
  BoxPose box{{0.0f, 0.9f, 0.0f}, Quat{}, {0.5f, 0.5f, 0.5f}};
  Manifold m;
  collide_boxes(ground, box, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.1f, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.45f, kTol);           // midway between y = 0.5 and 0.4
    EXPECT_EQ(m.points[i].feature_id >> 8, (3u << 4) | 2u);  // ref face +y of A, inc face -y of B
  }
  for (float x : {-0.5f, 0.5f}) {
    for (float z : {-0.5f, 0.5f}) EXPECT_TRUE(has_point(m, {x, 0.45f, z}, kTol)) << x << " " << z;
  }
  // Reversed roles: the normal still points from A (now the box) to B.
  collide_boxes(box, ground, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y, -1.0f, kTol);
}

TEST(ManifoldBoxBox, BoxTurned45DegreesOnLargerBox) {
  BoxPose ground{{0.0f, 0.0f, 0.0f}, Quat{}, {1.0f, 0.5f, 1.0f}};
  BoxPose box{{0.0f, 0.95f, 0.0f}, about_y(det_cos(kPi / 8), det_sin(kPi / 8)), {0.5f, 0.5f, 0.5f}};
  Manifold m;
  collide_boxes(ground, box, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  // The turned bottom face is a diamond with corners sqrt(0.5) from centre.
  for (Vec3 p : {Vec3{kHalfSqrt2, 0.475f, 0.0f}, Vec3{-kHalfSqrt2, 0.475f, 0.0f},
                 Vec3{0.0f, 0.475f, kHalfSqrt2}, Vec3{0.0f, 0.475f, -kHalfSqrt2}}) {
    EXPECT_TRUE(has_point(m, p, 1e-4f)) << p.x << " " << p.z;
  }
  for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, -0.05f, kTol);
}

TEST(ManifoldBoxBox, OctagonIsReducedToFourWellSpreadPoints) {
  // Equal boxes, one turned 45 degrees: the overlap is an octagon.
  BoxPose lower{{0.0f, 0.0f, 0.0f}, Quat{}, {0.5f, 0.5f, 0.5f}};
  BoxPose upper{
      {0.0f, 0.95f, 0.0f}, about_y(det_cos(kPi / 8), det_sin(kPi / 8)), {0.5f, 0.5f, 0.5f}};
  Manifold m;
  collide_boxes(lower, upper, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  float min_x = 1.0f, max_x = -1.0f, min_z = 1.0f, max_z = -1.0f;
  for (uint32_t i = 0; i < 4; ++i) {
    const Vec3 p = m.points[i].point;
    EXPECT_NEAR(m.points[i].separation, -0.05f, kTol);
    EXPECT_LE(std::fabs(p.x), 0.5f + 0.002f);  // inside the lower top face (+ clip margin)
    EXPECT_LE(std::fabs(p.z), 0.5f + 0.002f);
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_z = std::min(min_z, p.z);
    max_z = std::max(max_z, p.z);
  }
  // Spread over the face, not bunched on one side.
  EXPECT_GT(max_x - min_x, 0.5f);
  EXPECT_GT(max_z - min_z, 0.5f);
  // Deterministic: the same input gives the same points and ids.
  Manifold again;
  collide_boxes(lower, upper, kSpec, again);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(again.points[i].feature_id, m.points[i].feature_id);
    EXPECT_EQ(again.points[i].point, m.points[i].point);
  }
}

TEST(ManifoldBoxBox, EdgeEdgeGivesOnePoint) {
  // A turned 45 degrees about z: top edge along z at y = sqrt(0.5).
  // B turned 45 degrees about x: bottom edge along x, 0.05 below A's edge.
  const float c = det_cos(kPi / 8);
  const float s = det_sin(kPi / 8);
  const float e = kHalfSqrt2;
  BoxPose a{{0.0f, 0.0f, 0.0f}, Quat{0.0f, 0.0f, s, c}, {0.5f, 0.5f, 0.5f}};
  BoxPose b{{0.0f, 2.0f * e - 0.05f, 0.0f}, Quat{s, 0.0f, 0.0f, c}, {0.5f, 0.5f, 0.5f}};
  Manifold m;
  collide_boxes(a, b, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.x, 0.0f, kTol);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  EXPECT_NEAR(m.normal.z, 0.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.05f, kTol);
  EXPECT_NEAR(m.points[0].point.x, 0.0f, kTol);
  EXPECT_NEAR(m.points[0].point.y, e - 0.025f, kTol);
  EXPECT_NEAR(m.points[0].point.z, 0.0f, kTol);
  EXPECT_NE(m.points[0].feature_id & 0x80000000u, 0u);
}

TEST(ManifoldBoxBox, SeparatedBeyondSpeculativeDistanceGivesNothing) {
  BoxPose a{{0.0f, 0.0f, 0.0f}, Quat{}, {0.5f, 0.5f, 0.5f}};
  BoxPose b{{0.0f, 1.03f, 0.0f}, Quat{}, {0.5f, 0.5f, 0.5f}};
  Manifold m;
  collide_boxes(a, b, kSpec, m);
  EXPECT_EQ(m.point_count, 0u);
  b.center.y = 1.01f;  // within the speculative distance: points with positive separation
  collide_boxes(a, b, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
}

TEST(ManifoldBoxBox, FeatureIdsPersistAcrossSmallMotion) {
  BoxPose ground{{0.0f, 0.0f, 0.0f}, Quat{}, {2.0f, 0.5f, 2.0f}};
  BoxPose box{{0.1f, 0.89f, -0.2f}, about_y(det_cos(0.1f), det_sin(0.1f)), {0.5f, 0.4f, 0.3f}};
  Manifold frame1;
  collide_boxes(ground, box, kSpec, frame1);
  // Next frame: slid 3 mm, turned a little more, sunk 1 mm.
  box.center = {0.103f, 0.889f, -0.2f};
  box.rotation = about_y(det_cos(0.11f), det_sin(0.11f));
  Manifold frame2;
  collide_boxes(ground, box, kSpec, frame2);
  ASSERT_EQ(frame1.point_count, 4u);
  ASSERT_EQ(frame2.point_count, 4u);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(frame1.points[i].feature_id, frame2.points[i].feature_id) << i;
    for (uint32_t j = 0; j < i; ++j) {
      EXPECT_NE(frame2.points[i].feature_id, frame2.points[j].feature_id);  // unique per manifold
    }
  }
}

TEST(ManifoldBoxBox, WorldWarmStartsMatchingFeatureIds) {
  WorldConfig config;
  config.enable_sleep = false;
  World3D world(config);
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box({5.0f, 0.5f, 5.0f});
  ground.position = {0.0f, -0.5f, 0.0f};
  ASSERT_TRUE(world.create_body(ground).ok());
  BodyDef box;
  box.position = {0.0f, 0.5f, 0.0f};
  BodyId id = *world.create_body(box);
  for (int i = 0; i < 30; ++i) world.step();
  ASSERT_EQ(world.state().contacts.size(), 1u);
  ContactRecord before = world.state().contacts[0];
  world.step();
  ContactRecord after = world.state().contacts[0];
  ASSERT_EQ(before.point_count, 4u);
  ASSERT_EQ(after.point_count, 4u);
  // Same ids; the impulses carry the box's weight (per substep, four points).
  float weight_impulse = world.mass(id) * 9.81f * config.tick_seconds / 4.0f;
  float total = 0.0f;
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(before.points[i].feature_id, after.points[i].feature_id);
    EXPECT_GT(after.points[i].normal_impulse, 0.0f);
    total += after.points[i].normal_impulse;
  }
  EXPECT_NEAR(total, weight_impulse, 0.02f * weight_impulse);
}

}  // namespace
}  // namespace rwd::sim::d3
