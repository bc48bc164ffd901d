// SPDX-License-Identifier: MIT
// Shape casts through the public API: analytic distances for each swept
// shape against boxes, hulls and capsules, nearest-first ordering, filters,
// shapes that start touching, bad arguments, and the broadphase against a
// sweep of every body one by one.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "d3/gjk.h"
#include "d3/shape_ops.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

// Conservative advancement stops within its tolerance of the touch, never
// past it.
constexpr float kTol = 2e-3f;

std::optional<ShapeCastHit> cast(const World3D& world, const Shape& shape, Vec3 from,
                                 Vec3 translation, Quat rotation = {},
                                 const QueryFilter& filter = {}) {
  std::optional<ShapeCastHit> hit;
  EXPECT_TRUE(world.shape_cast(shape, from, rotation, translation, filter, hit).ok());
  return hit;
}

TEST(ShapeCast, ASphereLandsOnTheGround) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const auto hit = cast(world, Shape::make_sphere(0.5f), {1.0f, 10.0f, 2.0f}, {0.0f, -20.0f, 0.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ground);
  EXPECT_NEAR(hit->distance, 9.5f, kTol);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-4f);
  EXPECT_NEAR(hit->point.y, 0.0f, kTol);
  EXPECT_NEAR(hit->point.x, 1.0f, kTol);
  // Too short a sweep reaches nothing.
  EXPECT_FALSE(cast(world, Shape::make_sphere(0.5f), {1.0f, 10.0f, 2.0f}, {0.0f, -9.0f, 0.0f}));
}

TEST(ShapeCast, EachShapeStopsAtAWall) {
  World3D world;
  BodyDef wall;
  wall.kind = BodyKind::kStatic;
  wall.shape = Shape::make_box({0.5f, 5.0f, 5.0f});
  wall.position = {10.5f, 0.0f, 0.0f};  // its face at x = 10
  const BodyId w = *world.create_body(wall);
  const std::vector<Vec3> tetra = {
      {0.0f, 0.0f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.4f, 0.0f}, {0.0f, 0.0f, 0.4f}};
  const GeometryId hull = *world.geometry().add_hull(tetra);
  struct Case {
    Shape shape;
    float reach;  // how far the shape reaches along +x from its position
  };
  const Case cases[] = {
      {Shape::make_sphere(0.3f), 0.3f},
      {Shape::make_box({0.2f, 0.3f, 0.4f}), 0.2f},
      {Shape::make_capsule(0.25f, 0.5f), 0.25f},
      {Shape::make_hull(hull), 0.4f},  // placed by its corner at the origin
  };
  for (const Case& c : cases) {
    const auto hit = cast(world, c.shape, {0.0f, 0.0f, 0.0f}, {50.0f, 0.0f, 0.0f});
    ASSERT_TRUE(hit.has_value()) << static_cast<int>(c.shape.type);
    EXPECT_EQ(hit->body, w);
    EXPECT_NEAR(hit->distance, 10.0f - c.reach, kTol) << static_cast<int>(c.shape.type);
    EXPECT_NEAR(hit->normal.x, -1.0f, 1e-4f);
    EXPECT_NEAR(hit->point.x, 10.0f, kTol);
  }
}

TEST(ShapeCast, HitsHullsAndCapsules) {
  World3D world;
  const std::vector<Vec3> wedge = {{0.0f, 0.0f, 0.0f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
                                   {0.0f, 0.0f, 0.6f}, {0.8f, 0.0f, 0.6f}, {0.0f, 0.5f, 0.6f}};
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_hull(*world.geometry().add_hull(wedge));
  const BodyId w = *world.create_body(def);
  // A small sphere straight down onto the slope at x = 0.4 (y = 0.25 there):
  // it touches where its centre is r / cos(slope) above the slope line.
  const float r = 0.05f;
  const auto hit = cast(world, Shape::make_sphere(r), {0.4f, 3.0f, 0.3f}, {0.0f, -5.0f, 0.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, w);
  const float cos_slope = 0.8f / std::sqrt(0.8f * 0.8f + 0.5f * 0.5f);
  EXPECT_NEAR(hit->distance, 3.0f - 0.25f - r / cos_slope, kTol);
  // A capsule lying along z swept down onto a standing capsule's top cap.
  World3D caps;
  BodyDef standing;
  standing.kind = BodyKind::kStatic;
  standing.shape = Shape::make_capsule(0.3f, 1.0f);  // top at y = 1.3
  const BodyId s = *caps.create_body(standing);
  const Quat along_z{0.7071068f, 0.0f, 0.0f, 0.7071068f};  // local y onto z
  const auto c = cast(caps, Shape::make_capsule(0.2f, 0.5f), {0.0f, 5.0f, 0.3f},
                      {0.0f, -10.0f, 0.0f}, along_z);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->body, s);
  EXPECT_NEAR(c->distance, 5.0f - 1.3f - 0.2f, kTol);
}

TEST(ShapeCast, AllHitsComeNearestFirstAndFiltersApply) {
  World3D world;
  std::vector<BodyId> boxes;
  for (int i = 0; i < 5; ++i) {
    BodyDef def;
    def.kind = BodyKind::kStatic;
    def.shape = Shape::make_box({0.5f, 0.5f, 0.5f});
    def.position = {2.0f + 3.0f * static_cast<float>(4 - i), 0.0f, 0.0f};  // created far to near
    def.layer = i == 2 ? 2u : 1u;
    boxes.push_back(*world.create_body(def));
  }
  std::vector<ShapeCastHit> hits;
  ASSERT_TRUE(world
                  .shape_cast_all(Shape::make_sphere(0.25f), {0.0f, 0.0f, 0.0f}, {},
                                  {20.0f, 0.0f, 0.0f}, {}, hits)
                  .ok());
  ASSERT_EQ(hits.size(), 5u);
  for (size_t i = 0; i < hits.size(); ++i) {
    EXPECT_EQ(hits[i].body, boxes[4 - i]);
    EXPECT_NEAR(hits[i].distance, 1.25f + 3.0f * static_cast<float>(i), kTol);
  }
  QueryFilter only_one;
  only_one.layer_mask = 1u;
  ASSERT_TRUE(world
                  .shape_cast_all(Shape::make_sphere(0.25f), {0.0f, 0.0f, 0.0f}, {},
                                  {20.0f, 0.0f, 0.0f}, only_one, hits)
                  .ok());
  EXPECT_EQ(hits.size(), 4u);
  QueryFilter layer2;
  layer2.layer_mask = 2u;
  const auto first = cast(world, Shape::make_sphere(0.25f), {}, {20.0f, 0.0f, 0.0f}, {}, layer2);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->body, boxes[2]);
}

TEST(ShapeCast, AShapeThatStartsInsideHitsAtZero) {
  World3D world;
  const BodyId box = test::add_box(world, {0.0f, 0.0f, 0.0f});
  const auto hit = cast(world, Shape::make_sphere(0.2f), {0.1f, 0.1f, 0.0f}, {5.0f, 0.0f, 0.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, box);
  EXPECT_EQ(hit->distance, 0.0f);
}

// A compound sweeps by its children: a dumbbell (two 0.2 m balls 1 m
// apart on a thin bar) dropped onto the ground stops when its lower ball
// touches, and one swept toward a wall that only its near ball can reach
// stops at that ball, whatever the authored origin.
TEST(ShapeCast, ACompoundSweepsByItsChildren) {
  World3D world;
  test::add_ground(world);
  const std::vector<CompoundChild> parts = {
      {Shape::make_sphere(0.2f), {-0.5f, 0.0f, 0.0f}, {}},
      {Shape::make_sphere(0.2f), {0.5f, 0.0f, 0.0f}, {}},
      {Shape::make_capsule(0.05f, 0.3f), {0.0f, 0.0f, 0.0f}, {}}};
  const GeometryId dumbbell = *world.geometry().add_compound(parts);
  const Shape shape = Shape::make_compound(dumbbell);
  // Tilted 90 degrees about z: the balls sit at y = +-0.5 about the origin.
  const Quat upright = Quat{0.0f, 0.0f, 0.70710678f, 0.70710678f};
  const auto down = cast(world, shape, {3.0f, 4.0f, 0.0f}, {0.0f, -10.0f, 0.0f}, upright);
  ASSERT_TRUE(down.has_value());
  // The lower ball's bottom starts at 4 - 0.5 - 0.2 = 3.3 m above y = 0.
  EXPECT_NEAR(down->distance, 3.3f, 2e-3f);
  EXPECT_NEAR(down->normal.y, 1.0f, 1e-3f);

  const BodyId wall = test::add_box(world, {5.0f, 1.5f, 0.0f}, {0.1f, 0.3f, 2.0f});
  const auto side = cast(world, shape, {0.0f, 1.5f, 0.0f}, {10.0f, 0.0f, 0.0f});
  ASSERT_TRUE(side.has_value());
  EXPECT_EQ(side->body, wall);
  // The near ball's front is at 0.5 + 0.2 = 0.7 m; the wall's face at 4.9 m.
  EXPECT_NEAR(side->distance, 4.2f, 2e-3f);
}

TEST(ShapeCast, RefusesBadArguments) {
  World3D world;
  test::add_ground(world);
  std::optional<ShapeCastHit> hit = ShapeCastHit{};
  EXPECT_EQ(world
                .shape_cast(Shape::make_sphere(0.5f), {0.0f, 5.0f, 0.0f}, {},
                            {0.0f, std::nanf(""), 0.0f}, {}, hit)
                .code(),
            ErrorCode::kInvalidArgument);
  EXPECT_FALSE(hit.has_value());
  EXPECT_EQ(
      world.shape_cast(Shape::make_sphere(-1.0f), {}, {}, {0.0f, -1.0f, 0.0f}, {}, hit).code(),
      ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.shape_cast(Shape::make_hull(GeometryId{3}), {}, {}, {0.0f, -1.0f, 0.0f}, {}, hit)
                .code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world
                .shape_cast(Shape::make_sphere(0.5f), {}, Quat{0.0f, 0.0f, 0.0f, 0.0f},
                            {0.0f, -1.0f, 0.0f}, {}, hit)
                .code(),
            ErrorCode::kInvalidArgument);
  std::vector<ShapeCastHit> all(3);
  EXPECT_EQ(world
                .shape_cast_all(Shape::make_sphere(0.5f), {0.0f, 5.0f, 0.0f}, {},
                                {std::nanf(""), 0.0f, 0.0f}, {}, all)
                .code(),
            ErrorCode::kInvalidArgument);
  EXPECT_TRUE(all.empty());
  // Meshes and height fields stand still to be struck; they are not swept.
  const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  const std::vector<uint32_t> tri = {0, 1, 2};
  const GeometryId mesh = *world.geometry().add_mesh(corners, tri);
  EXPECT_EQ(world.shape_cast(Shape::make_mesh(mesh), {}, {}, {0.0f, -1.0f, 0.0f}, {}, hit).code(),
            ErrorCode::kInvalidArgument);
}

// Random boxes, capsules and spheres; random sweeps: the query (through the
// trees) finds exactly what sweeping every body one by one finds.
TEST(ShapeCast, TreesFindWhatABruteForceSweepFinds) {
  World3D world;
  test::Rng rng{0x5CA57};
  for (int i = 0; i < 150; ++i) {
    BodyDef def;
    def.kind = i % 3 == 0 ? BodyKind::kStatic : BodyKind::kDynamic;
    def.position = {rng.uniform(-20.0f, 20.0f), rng.uniform(-20.0f, 20.0f),
                    rng.uniform(-20.0f, 20.0f)};
    def.rotation = rng.rotation();
    def.shape = i % 3 == 1   ? Shape::make_sphere(rng.uniform(0.2f, 1.0f))
                : i % 3 == 2 ? Shape::make_capsule(rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 1.0f))
                             : Shape::make_box({rng.uniform(0.2f, 2.0f), rng.uniform(0.2f, 2.0f),
                                                rng.uniform(0.2f, 2.0f)});
    ASSERT_TRUE(world.create_body(def).ok());
  }
  world.step();
  std::vector<BodyId> ids;
  world.body_ids(ids);
  const GeometryStore& store = world.geometry();
  std::vector<ShapeCastHit> hits;
  for (int q = 0; q < 60; ++q) {
    const Shape shape = q % 2 == 0 ? Shape::make_sphere(0.4f) : Shape::make_box({0.3f, 0.5f, 0.2f});
    const Vec3 from{rng.uniform(-25.0f, 25.0f), rng.uniform(-25.0f, 25.0f),
                    rng.uniform(-25.0f, 25.0f)};
    const Vec3 move{rng.uniform(-30.0f, 30.0f), rng.uniform(-30.0f, 30.0f),
                    rng.uniform(-30.0f, 30.0f)};
    const Quat rotation = rng.rotation();
    ASSERT_TRUE(world.shape_cast_all(shape, from, rotation, move, {}, hits).ok());
    // Brute force: every body.
    std::vector<BodyId> expected;
    d3::ProxyPoints cast_storage;
    d3::ConvexProxy swept = d3::shape_ops(shape.type).proxy(shape, store, cast_storage);
    swept.position = from;
    swept.axes = mat3_from_quat(normalize(rotation));
    for (const BodyId id : ids) {
      const BodyInfo& info = world.state().infos[id.index];
      d3::ProxyPoints storage;
      d3::ConvexProxy body = d3::shape_ops(info.shape.type).proxy(info.shape, store, storage);
      body.position = world.state().sims[id.index].position;
      body.axes = mat3_from_quat(world.state().sims[id.index].rotation);
      if (d3::shape_cast(body, swept, move, 1.0f).hit) expected.push_back(id);
    }
    std::vector<BodyId> found;
    for (const ShapeCastHit& h : hits) found.push_back(h.body);
    std::sort(found.begin(), found.end(), [](BodyId l, BodyId r) { return l.index < r.index; });
    EXPECT_EQ(found, expected) << "query " << q;
    for (size_t i = 1; i < hits.size(); ++i) EXPECT_LE(hits[i - 1].distance, hits[i].distance);
    // The closest cast (near to far, each body swept no further than the
    // best so far) gives the first of all hits, bit for bit.
    std::optional<ShapeCastHit> nearest;
    ASSERT_TRUE(world.shape_cast(shape, from, rotation, move, {}, nearest).ok());
    ASSERT_EQ(nearest.has_value(), !hits.empty()) << "query " << q;
    if (!nearest) continue;
    EXPECT_EQ(nearest->body, hits.front().body) << "query " << q;
    EXPECT_EQ(nearest->distance, hits.front().distance) << "query " << q;
    EXPECT_EQ(nearest->point, hits.front().point) << "query " << q;
    EXPECT_EQ(nearest->normal, hits.front().normal) << "query " << q;
  }
}

}  // namespace
}  // namespace rwd::sim
