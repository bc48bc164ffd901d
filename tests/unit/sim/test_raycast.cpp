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

// The closest-hit walk stops at the best hit so far; it must still pick
// what testing every body would: the first of raycast_all's sorted hits,
// over static, sleeping and awake bodies, rotated, touching and stacked
// shapes (equal distances included), rays from inside and outside.
TEST(Raycast, ClosestIsTheFirstOfAllHits) {
  World3D world;
  test::add_ground(world);
  test::Rng rng{7};
  for (int i = 0; i < 300; ++i) {
    BodyDef def;
    def.kind = i % 3 == 0 ? BodyKind::kStatic : BodyKind::kDynamic;
    const float x = std::floor(rng.uniform(-6.0f, 6.0f));
    const float z = std::floor(rng.uniform(-6.0f, 6.0f));
    def.position = {x, rng.uniform(0.5f, 4.0f), z};
    if (i % 4 == 0) def.position = {x, 0.5f, z};  // aligned faces: equal distances
    def.rotation = i % 2 == 0 ? Quat{} : rng.rotation();
    def.shape = i % 5 == 0 ? Shape::make_sphere(rng.uniform(0.1f, 0.6f))
                           : Shape::make_box({rng.uniform(0.1f, 0.6f), rng.uniform(0.1f, 0.6f),
                                              rng.uniform(0.1f, 0.6f)});
    ASSERT_TRUE(world.create_body(def).ok());
  }
  for (int t = 0; t < 30; ++t) world.step();  // some fall asleep, some move
  int hits = 0;
  int ties = 0;
  for (int r = 0; r < 3000; ++r) {
    Ray ray;
    ray.origin = {rng.uniform(-8.0f, 8.0f), rng.uniform(-0.5f, 6.0f), rng.uniform(-8.0f, 8.0f)};
    if (r % 3 == 0) {  // axis-aligned: parallel slabs, equal distances
      const int axis = r % 9 / 3;
      ray.direction = {axis == 0 ? 1.0f : 0.0f, axis == 1 ? -1.0f : 0.0f, axis == 2 ? 1.0f : 0.0f};
    } else {
      ray.direction = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f),
                       rng.uniform(-1.0f, 1.0f)};
    }
    ray.max_distance = rng.uniform(0.5f, 20.0f);
    std::vector<RayHit> all;
    world.raycast_all(ray, {}, all);
    const auto hit = world.raycast(ray);
    ASSERT_EQ(hit.has_value(), !all.empty()) << "ray " << r;
    if (!hit) continue;
    ++hits;
    if (all.size() > 1 && all[1].distance == all[0].distance) ++ties;
    EXPECT_EQ(hit->body, all.front().body) << "ray " << r;
    EXPECT_EQ(hit->distance, all.front().distance) << "ray " << r;
    EXPECT_EQ(hit->normal, all.front().normal) << "ray " << r;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(ties, 0);
}

// Equal distances go to the lower index however the trees hold the bodies:
// boxes made in every order of their slots, static, kinematic awake and
// kinematic asleep (kinematic, so overlapping does not push them apart).
TEST(Raycast, EqualDistancesGoToTheLowerIndexInAnyTree) {
  for (int round = 0; round < 8; ++round) {
    World3D world;
    std::vector<BodyId> ids;
    for (int i = 0; i < 12; ++i) {
      BodyDef def;
      def.kind = (i + round) % 3 == 0 ? BodyKind::kStatic : BodyKind::kKinematic;
      // Stacked along the ray, every one reaching z = 5 with its near face.
      def.shape =
          Shape::make_box({0.5f, 0.5f, 0.5f + 0.1f * static_cast<float>((i * 5 + round) % 12)});
      def.position = {0.0f, 0.0f, 5.0f + def.shape.half_extents.z};
      ids.push_back(*world.create_body(def));
    }
    // Free some slots and fill them again, so indices and tree order part.
    for (int k = round % 3; k < 12; k += 3)
      ASSERT_TRUE(world.destroy_body(ids[static_cast<size_t>(k)]).ok());
    for (int k = 0; k < 4; ++k) {
      BodyDef def;
      def.kind = BodyKind::kKinematic;
      def.position = {0.0f, 0.0f, 5.5f};
      ASSERT_TRUE(world.create_body(def).ok());
    }
    for (int t = 0; t < round * 10; ++t) world.step();
    Ray ray;
    ray.origin = {0.0f, 0.0f, -3.0f};
    ray.direction = {0.0f, 0.0f, 1.0f};
    ray.max_distance = 50.0f;
    std::vector<RayHit> all;
    world.raycast_all(ray, {}, all);
    const auto hit = world.raycast(ray);
    ASSERT_EQ(hit.has_value(), !all.empty()) << "round " << round;
    ASSERT_FALSE(all.empty()) << "round " << round << ", bodies " << world.body_count();
    EXPECT_EQ(hit->body, all.front().body) << "round " << round;
  }
}

}  // namespace
}  // namespace rwd::sim
