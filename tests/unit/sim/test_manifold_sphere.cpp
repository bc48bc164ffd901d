// SPDX-License-Identifier: MIT
// Sphere-sphere and sphere-box manifolds against hand-computed normals,
// separations and contact points. Tolerance 1e-5 m (float rounding of
// values near 1).
#include <cmath>

#include <gtest/gtest.h>

#include "d3/manifold.h"

namespace rwd::sim::d3 {
namespace {

constexpr float kTol = 1e-5f;
constexpr float kSpec = 0.02f;

void expect_vec(Vec3 actual, Vec3 expected, float tol = kTol) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
  EXPECT_NEAR(actual.z, expected.z, tol);
}

TEST(ManifoldSphere, SphereSphereOverlap) {
  Manifold m;
  collide_spheres({0.0f, 0.0f, 0.0f}, 1.0f, {1.5f, 0.0f, 0.0f}, 1.0f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  expect_vec(m.normal, {1.0f, 0.0f, 0.0f});
  EXPECT_NEAR(m.points[0].separation, -0.5f, kTol);
  expect_vec(m.points[0].point, {0.75f, 0.0f, 0.0f});  // between (1,0,0) and (0.5,0,0)
  EXPECT_EQ(m.points[0].feature_id, 0u);
}

TEST(ManifoldSphere, SphereSphereSpeculativeAndApart) {
  Manifold m;
  collide_spheres({0.0f, 0.0f, 0.0f}, 1.0f, {0.0f, 2.01f, 0.0f}, 1.0f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  expect_vec(m.normal, {0.0f, 1.0f, 0.0f});
  collide_spheres({0.0f, 0.0f, 0.0f}, 1.0f, {0.0f, 2.03f, 0.0f}, 1.0f, kSpec, m);
  EXPECT_EQ(m.point_count, 0u);
  // Coincident centres still give a defined unit normal.
  collide_spheres({1.0f, 1.0f, 1.0f}, 0.5f, {1.0f, 1.0f, 1.0f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(length(m.normal), 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -1.0f, kTol);
}

BoxPose unit_box() {
  return {{0.0f, 0.0f, 0.0f}, Quat{}, {1.0f, 1.0f, 1.0f}};
}

TEST(ManifoldSphere, SphereOnBoxFace) {
  Manifold m;
  collide_box_sphere(unit_box(), {0.0f, 1.4f, 0.0f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  expect_vec(m.normal, {0.0f, 1.0f, 0.0f});
  EXPECT_NEAR(m.points[0].separation, -0.1f, kTol);
  expect_vec(m.points[0].point, {0.0f, 0.95f, 0.0f});
  EXPECT_EQ(m.points[0].feature_id, 1u + 3u * 2u + 9u * 1u);  // y above, x and z within
}

TEST(ManifoldSphere, SphereOnBoxEdge) {
  Manifold m;
  collide_box_sphere(unit_box(), {1.3f, 1.3f, 0.0f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  const float r = std::sqrt(0.5f);
  expect_vec(m.normal, {r, r, 0.0f});
  EXPECT_NEAR(m.points[0].separation, std::sqrt(0.18f) - 0.5f, kTol);
  EXPECT_EQ(m.points[0].feature_id, 2u + 3u * 2u + 9u * 1u);
}

TEST(ManifoldSphere, SphereOnBoxCorner) {
  Manifold m;
  collide_box_sphere(unit_box(), {1.2f, 1.2f, 1.2f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  const float r = 1.0f / std::sqrt(3.0f);
  expect_vec(m.normal, {r, r, r});
  EXPECT_NEAR(m.points[0].separation, std::sqrt(0.12f) - 0.5f, kTol);
  EXPECT_EQ(m.points[0].feature_id, 26u);
}

TEST(ManifoldSphere, SphereCentreInsideBox) {
  Manifold m;
  collide_box_sphere(unit_box(), {0.1f, 0.8f, -0.3f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  expect_vec(m.normal, {0.0f, 1.0f, 0.0f});  // nearest face is +y (0.2 away)
  EXPECT_NEAR(m.points[0].separation, -0.2f - 0.5f, kTol);
  EXPECT_EQ(m.points[0].feature_id, 27u + 2u + 1u);
}

TEST(ManifoldSphere, RotatedBoxAndDispatchFlipsNormal) {
  // Box turned 90 degrees about z: its local +x face now faces +y.
  const float h = std::sqrt(0.5f);
  BoxPose box{{0.0f, 0.0f, 0.0f}, Quat{0.0f, 0.0f, h, h}, {0.5f, 2.0f, 2.0f}};
  Manifold m;
  collide_box_sphere(box, {0.0f, 0.9f, 0.0f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  expect_vec(m.normal, {0.0f, 1.0f, 0.0f});
  EXPECT_NEAR(m.points[0].separation, -0.1f, kTol);
  // Sphere as shape A: the normal must still point from A to B.
  collide_shapes(Shape::make_sphere(0.5f), {0.0f, 0.9f, 0.0f}, Quat{},
                 Shape::make_box({0.5f, 2.0f, 2.0f}), {0.0f, 0.0f, 0.0f}, box.rotation, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  expect_vec(m.normal, {0.0f, -1.0f, 0.0f});
  expect_vec(m.points[0].anchor_a, m.points[0].point - Vec3{0.0f, 0.9f, 0.0f});
  expect_vec(m.points[0].anchor_b, m.points[0].point);
}

}  // namespace
}  // namespace rwd::sim::d3
