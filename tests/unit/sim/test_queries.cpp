// SPDX-License-Identifier: MIT
// Queries through the broadphase: overlap, ray and nearest-body queries
// against a brute force over every body (same exact tests), in a mixed
// scene that moves, sleeps, is edited and restored between queries;
// filters; signed distances to each shape (surfaces: test_signed_distance.cpp);
// bad arguments.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "d3/shape_ops.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

// Reproducible random shapes on top of the shared generator.
struct Rng : test::Rng {
  Shape shape() {
    switch (next() % 3) {
      case 0:
        return Shape::make_sphere(uniform(0.1f, 0.6f));
      case 1:
        return Shape::make_box({uniform(0.1f, 0.6f), uniform(0.1f, 0.6f), uniform(0.1f, 0.6f)});
      default:
        return Shape::make_capsule(uniform(0.1f, 0.4f), uniform(0.1f, 0.5f));
    }
  }
};

std::vector<BodyId> brute_overlap(const World3D& world, const Shape& shape, Vec3 p, Quat q,
                                  const QueryFilter& filter) {
  std::vector<BodyId> out;
  std::vector<BodyId> ids;
  world.body_ids(ids);
  for (const BodyId id : ids) {
    const BodyInfo& info = world.state().infos[id.index];
    if (info.enabled == 0 || (info.layer & filter.layer_mask) == 0) continue;
    if (info.sensor != 0 && !filter.include_sensors) continue;
    d3::Manifold m;
    d3::collide_shapes(shape, p, q, info.shape, world.position(id), world.rotation(id), 0.0f, m);
    bool touching = false;
    for (uint32_t k = 0; k < m.point_count; ++k) touching |= m.points[k].separation <= 0.0f;
    if (touching) out.push_back(id);
  }
  return out;
}

std::vector<RayHit> brute_ray(const World3D& world, const Ray& ray, const QueryFilter& filter) {
  std::vector<RayHit> out;
  std::vector<BodyId> ids;
  world.body_ids(ids);
  const Vec3 dir = normalize_or_zero(ray.direction);
  for (const BodyId id : ids) {
    const BodyInfo& info = world.state().infos[id.index];
    if (info.enabled == 0 || (info.layer & filter.layer_mask) == 0) continue;
    if (info.sensor != 0 && !filter.include_sensors) continue;
    float t = 0.0f;
    Vec3 n;
    if (d3::shape_ops(info.shape.type)
            .raycast(info.shape, world.geometry(), world.state().sims[id.index].position,
                     world.state().sims[id.index].rotation, ray.origin, dir, ray.max_distance, t,
                     n)) {
      out.push_back(RayHit{id, t, ray.origin + dir * t, n});
    }
  }
  std::sort(out.begin(), out.end(), [](const RayHit& l, const RayHit& r) {
    return l.distance < r.distance || (l.distance == r.distance && l.body.index < r.body.index);
  });
  return out;
}

void build_scene(World3D& world, Rng& rng) {
  test::add_ground(world);
  for (int i = 0; i < 120; ++i) {
    BodyDef def;
    def.shape = rng.shape();
    def.kind = i % 10 == 0 ? BodyKind::kStatic : BodyKind::kDynamic;
    def.position = {rng.uniform(-6.0f, 6.0f), rng.uniform(0.5f, 8.0f), rng.uniform(-6.0f, 6.0f)};
    def.rotation = rng.rotation();
    def.layer = i % 7 == 0 ? 2u : 1u;
    def.sensor = i % 13 == 0;
    ASSERT_TRUE(world.create_body(def).ok());
  }
}

void expect_queries_match(const World3D& world, Rng& rng, const char* when) {
  std::vector<BodyId> got;
  for (int k = 0; k < 60; ++k) {
    const Shape shape = rng.shape();
    const Vec3 p{rng.uniform(-7.0f, 7.0f), rng.uniform(-0.5f, 8.0f), rng.uniform(-7.0f, 7.0f)};
    const Quat q = rng.rotation();
    QueryFilter filter;
    if (k % 3 == 1) filter.layer_mask = 2u;
    if (k % 4 == 2) filter.include_sensors = true;
    ASSERT_TRUE(world.overlap(shape, p, q, filter, got).ok());
    EXPECT_EQ(got, brute_overlap(world, shape, p, q, filter)) << when << ", query " << k;

    Ray ray{{rng.uniform(-8.0f, 8.0f), rng.uniform(0.0f, 10.0f), rng.uniform(-8.0f, 8.0f)},
            {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 0.3f), rng.uniform(-1.0f, 1.0f)},
            rng.uniform(1.0f, 30.0f)};
    std::vector<RayHit> all;
    world.raycast_all(ray, filter, all);
    const std::vector<RayHit> expected = brute_ray(world, ray, filter);
    ASSERT_EQ(all.size(), expected.size()) << when << ", ray " << k;
    for (size_t h = 0; h < all.size(); ++h) {
      EXPECT_EQ(all[h].body, expected[h].body) << when << ", ray " << k;
      EXPECT_EQ(all[h].distance, expected[h].distance) << when << ", ray " << k;
    }
    // The nearest body: a brute force over every body's signed distance.
    const Vec3 at{rng.uniform(-7.0f, 7.0f), rng.uniform(-0.5f, 8.0f), rng.uniform(-7.0f, 7.0f)};
    const float reach = rng.uniform(0.0f, 2.0f);
    std::optional<PointHit> nearest;
    std::vector<BodyId> every;
    world.body_ids(every);
    for (const BodyId id : every) {
      const BodyInfo& info = world.state().infos[id.index];
      if (info.enabled == 0 || (info.layer & filter.layer_mask) == 0) continue;
      if (info.sensor != 0 && !filter.include_sensors) continue;
      const std::optional<PointHit> d = world.signed_distance(id, at);
      ASSERT_TRUE(d.has_value());
      if (d->distance <= reach && (!nearest || d->distance < nearest->distance)) nearest = d;
    }
    const std::optional<PointHit> found = world.nearest_body(at, reach, filter);
    ASSERT_EQ(found.has_value(), nearest.has_value()) << when << ", point " << k;
    if (found) {
      EXPECT_EQ(found->body, nearest->body) << when << ", point " << k;
      EXPECT_EQ(found->distance, nearest->distance) << when << ", point " << k;
    }

    const auto closest = world.raycast(ray, filter);
    ASSERT_EQ(closest.has_value(), !expected.empty()) << when << ", ray " << k;
    if (closest) {
      EXPECT_EQ(closest->body, expected[0].body) << when << ", ray " << k;
    }
  }
}

TEST(Queries, MatchABruteForceThroughStepsSleepEditsAndRestore) {
  World3D world;
  Rng rng;
  rng.state = 42;
  build_scene(world, rng);
  expect_queries_match(world, rng, "before any step");
  WorldState early;
  for (int i = 0; i < 40; ++i) world.step();
  world.save(early);
  expect_queries_match(world, rng, "falling");
  for (int i = 0; i < 400; ++i) world.step();  // settled; many asleep
  expect_queries_match(world, rng, "resting");
  // Edits between steps: a teleport, a disabled body, a new and a
  // destroyed one.
  std::vector<BodyId> ids;
  world.body_ids(ids);
  ASSERT_TRUE(world.set_transform(ids[5], {0.0f, 3.0f, 0.0f}, Quat{}).ok());
  ASSERT_TRUE(world.set_enabled(ids[9], false).ok());
  ASSERT_TRUE(world.destroy_body(ids[11]).ok());
  BodyDef extra;
  extra.shape = Shape::make_capsule(0.3f, 1.0f);
  extra.position = {1.0f, 2.0f, 1.0f};
  ASSERT_TRUE(world.create_body(extra).ok());
  expect_queries_match(world, rng, "edited");
  world.restore(early);
  expect_queries_match(world, rng, "restored");
}

TEST(Queries, OverlapFindsWhatItTouchesAndRefusesBadShapes) {
  World3D world;
  test::add_ground(world);
  const BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  const BodyId ball = test::add_sphere(world, {3.0f, 0.5f, 0.0f});
  std::vector<BodyId> got;
  // A sphere touching the box's top face exactly: overlap (touching counts).
  ASSERT_TRUE(world.overlap(Shape::make_sphere(0.25f), {0.0f, 1.25f, 0.0f}, {}, {}, got).ok());
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], box);
  // A long capsule lying across both, above the ground.
  const float h = std::sqrt(0.5f);
  ASSERT_TRUE(world
                  .overlap(Shape::make_capsule(0.2f, 2.0f), {1.5f, 0.6f, 0.0f},
                           Quat{0.0f, 0.0f, -h, h}, {}, got)
                  .ok());
  EXPECT_EQ(got, (std::vector<BodyId>{box, ball}));
  // Bad shapes and poses: an error, nothing reported.
  got.push_back(box);
  EXPECT_FALSE(world.overlap(Shape::make_sphere(-1.0f), {}, {}, {}, got).ok());
  EXPECT_TRUE(got.empty());
  EXPECT_FALSE(
      world.overlap(Shape::make_sphere(1.0f), {std::nanf(""), 0.0f, 0.0f}, {}, {}, got).ok());
  EXPECT_FALSE(
      world.overlap(Shape::make_sphere(1.0f), {}, Quat{0.0f, 0.0f, 0.0f, 0.0f}, {}, got).ok());
  Shape unknown;
  unknown.type = static_cast<ShapeType>(200);
  EXPECT_FALSE(world.overlap(unknown, {}, {}, {}, got).ok());
}

TEST(Queries, FilterSkipsTheIgnoredBodyAndKindsItExcludes) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  const Ray down{{0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 10.0f};
  ASSERT_TRUE(world.raycast(down).has_value());
  EXPECT_EQ(world.raycast(down)->body, box);
  QueryFilter skip_box;
  skip_box.ignore = box;
  ASSERT_TRUE(world.raycast(down, skip_box).has_value());
  EXPECT_EQ(world.raycast(down, skip_box)->body, ground);
  QueryFilter static_only;
  static_only.include_dynamic = false;
  static_only.include_kinematic = false;
  EXPECT_EQ(world.raycast(down, static_only)->body, ground);
  QueryFilter no_static;
  no_static.include_static = false;
  no_static.ignore = box;
  EXPECT_FALSE(world.raycast(down, no_static).has_value());
  // A stale id of the ignored slot skips nothing.
  QueryFilter stale;
  stale.ignore = {box.index, box.generation + 1};
  EXPECT_EQ(world.raycast(down, stale)->body, box);
  std::vector<BodyId> got;
  ASSERT_TRUE(
      world.overlap(Shape::make_sphere(0.25f), {0.0f, 1.25f, 0.0f}, {}, skip_box, got).ok());
  EXPECT_TRUE(got.empty());
}

TEST(Queries, SignedDistanceToEachShape) {
  World3D world;
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_box({1.0f, 0.5f, 2.0f});
  const BodyId box = *world.create_body(def);
  def.shape = Shape::make_sphere(0.5f);
  def.position = {10.0f, 0.0f, 0.0f};
  const BodyId ball = *world.create_body(def);
  def.shape = Shape::make_capsule(0.25f, 1.0f);
  def.position = {20.0f, 0.0f, 0.0f};
  const BodyId cap = *world.create_body(def);
  // Box: above the top face, beyond a corner, and inside near the +x face.
  auto d = world.signed_distance(box, {0.2f, 1.5f, 0.3f});
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->distance, 1.0f, 1e-5f);
  EXPECT_NEAR(d->normal.y, 1.0f, 1e-5f);
  EXPECT_NEAR(d->point.y, 0.5f, 1e-5f);
  d = world.signed_distance(box, {2.0f, 1.5f, 3.0f});
  EXPECT_NEAR(d->distance, std::sqrt(3.0f), 1e-5f);
  d = world.signed_distance(box, {0.9f, 0.0f, 0.0f});
  EXPECT_NEAR(d->distance, -0.1f, 1e-5f);
  EXPECT_NEAR(d->normal.x, 1.0f, 1e-5f);
  EXPECT_NEAR(d->point.x, 1.0f, 1e-5f);
  // Sphere and capsule (side and cap).
  d = world.signed_distance(ball, {10.0f, 2.0f, 0.0f});
  EXPECT_NEAR(d->distance, 1.5f, 1e-5f);
  EXPECT_NEAR(d->point.y, 0.5f, 1e-5f);
  d = world.signed_distance(cap, {20.5f, 0.3f, 0.0f});
  EXPECT_NEAR(d->distance, 0.25f, 1e-5f);
  EXPECT_NEAR(d->normal.x, 1.0f, 1e-5f);
  d = world.signed_distance(cap, {20.0f, 2.0f, 0.0f});
  EXPECT_NEAR(d->distance, 0.75f, 1e-5f);
  // Unknown ids and bad points find nothing; a nearest search within
  // reach finds the sphere, and with no reach nothing.
  EXPECT_FALSE(world.signed_distance(BodyId{9, 1}, {}).has_value());
  EXPECT_FALSE(world.signed_distance(box, {std::nanf(""), 0.0f, 0.0f}).has_value());
  auto n = world.nearest_body({10.0f, 1.2f, 0.0f}, 1.0f);
  ASSERT_TRUE(n.has_value());
  EXPECT_EQ(n->body, ball);
  EXPECT_FALSE(world.nearest_body({10.0f, 1.2f, 0.0f}, 0.5f).has_value());
  EXPECT_FALSE(world.nearest_body({10.0f, 1.2f, 0.0f}, -1.0f).has_value());
}

TEST(Queries, ContactManifoldOfTwoBodies) {
  World3D world;
  test::add_ground(world);
  const BodyId ground = BodyId{0, 1};
  const BodyId box = test::add_box(world, {0.0f, 0.49f, 0.0f});  // 1 cm into the ground
  const BodyId far = test::add_box(world, {5.0f, 0.6f, 0.0f});   // 10 cm above it
  auto m = world.contact_manifold(ground, box);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->point_count, 4u);
  EXPECT_NEAR(m->normal.y, 1.0f, 1e-5f);
  for (uint32_t i = 0; i < m->point_count; ++i) {
    EXPECT_NEAR(m->points[i].separation, -0.01f, 1e-5f);
  }
  // Reversed order: the normal runs from the first body.
  m = world.contact_manifold(box, ground);
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->normal.y, -1.0f, 1e-5f);
  // Apart: nothing at 0, the gap within a larger reach.
  EXPECT_FALSE(world.contact_manifold(ground, far).has_value());
  m = world.contact_manifold(ground, far, 0.2f);
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->points[0].separation, 0.1f, 1e-5f);
  // Bad arguments.
  EXPECT_FALSE(world.contact_manifold(box, box).has_value());
  EXPECT_FALSE(world.contact_manifold(box, BodyId{40, 1}).has_value());
  EXPECT_FALSE(world.contact_manifold(ground, far, -1.0f).has_value());
}

}  // namespace
}  // namespace rwd::sim
