// SPDX-License-Identifier: MIT
// Ray queries: hits, misses, normals, filters, ordering and ties.
#include <cmath>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr float kTol = 1e-5f;

TEST(Raycast, HitsSphereAndBoxWithNormals) {
  World3D world;
  BodyId ball = test::add_sphere(world, {0.0f, 0.0f, 5.0f}, 1.0f);
  BodyId box = test::add_box(world, {0.0f, 0.0f, 10.0f});
  Ray ray;
  ray.origin = {0.0f, 0.0f, 0.0f};
  ray.direction = {0.0f, 0.0f, 2.0f};  // normalized by the query
  auto hit = world.raycast(ray);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ball);
  EXPECT_NEAR(hit->distance, 4.0f, kTol);
  EXPECT_NEAR(hit->point.z, 4.0f, kTol);
  EXPECT_NEAR(hit->normal.z, -1.0f, kTol);

  std::vector<RayHit> all;
  world.raycast_all(ray, {}, all);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, ball);
  EXPECT_EQ(all[1].body, box);
  EXPECT_NEAR(all[1].distance, 9.5f, kTol);
  EXPECT_NEAR(all[1].normal.z, -1.0f, kTol);
}

TEST(Raycast, HitsRotatedBoxFace) {
  World3D world;
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_box({1.0f, 1.0f, 1.0f});
  const float h = std::sqrt(0.5f);
  def.rotation = {0.0f, h, 0.0f, h};  // 90 degrees about y
  def.position = {5.0f, 0.0f, 0.0f};
  BodyId id = *world.create_body(def);
  Ray ray;
  ray.origin = {0.0f, 0.5f, 0.0f};
  ray.direction = {1.0f, 0.0f, 0.0f};
  auto hit = world.raycast(ray);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, id);
  EXPECT_NEAR(hit->distance, 4.0f, 1e-4f);
  EXPECT_NEAR(hit->normal.x, -1.0f, 1e-4f);
}

TEST(Raycast, MissesRespectMaxDistanceFilterAndSensors) {
  World3D world;
  BodyDef def;
  def.shape = Shape::make_sphere(1.0f);
  def.position = {0.0f, 0.0f, 5.0f};
  def.layer = 2;
  ASSERT_TRUE(world.create_body(def).ok());
  Ray ray;
  ray.direction = {0.0f, 0.0f, 1.0f};
  ray.max_distance = 3.0f;
  EXPECT_FALSE(world.raycast(ray).has_value());  // too short
  ray.max_distance = 100.0f;
  EXPECT_TRUE(world.raycast(ray).has_value());
  QueryFilter filter;
  filter.layer_mask = 1;
  EXPECT_FALSE(world.raycast(ray, filter).has_value());  // other layer
  ray.direction = {0.0f, 1.0f, 0.0f};
  EXPECT_FALSE(world.raycast(ray).has_value());  // pointing away
  ray.direction = {};
  EXPECT_FALSE(world.raycast(ray).has_value());  // invalid direction

  World3D sensors;
  BodyDef zone;
  zone.kind = BodyKind::kStatic;
  zone.sensor = true;
  zone.shape = Shape::make_box({1.0f, 1.0f, 1.0f});
  zone.position = {0.0f, 0.0f, 5.0f};
  ASSERT_TRUE(sensors.create_body(zone).ok());
  ray.direction = {0.0f, 0.0f, 1.0f};
  EXPECT_FALSE(sensors.raycast(ray).has_value());
  QueryFilter with_sensors;
  with_sensors.include_sensors = true;
  EXPECT_TRUE(sensors.raycast(ray, with_sensors).has_value());
}

TEST(Raycast, TiesGoToTheLowerIndexAndInsideHitsAtZero) {
  World3D world;
  BodyId first = test::add_box(world, {0.0f, 0.0f, 5.0f});
  BodyId second = test::add_box(world, {0.0f, 0.0f, 5.0f});
  Ray ray;
  ray.direction = {0.0f, 0.0f, 1.0f};
  auto hit = world.raycast(ray);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, first);
  std::vector<RayHit> all;
  world.raycast_all(ray, {}, all);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, first);
  EXPECT_EQ(all[1].body, second);
  ray.origin = {0.0f, 0.0f, 5.0f};  // inside both
  hit = world.raycast(ray);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->distance, 0.0f);
  EXPECT_EQ(hit->body, first);
}

}  // namespace
}  // namespace rwd::sim
