// SPDX-License-Identifier: MIT
// Triangle meshes and height fields through the public API: registration
// errors, static-or-kinematic only, boxes, spheres, capsules and hulls
// resting on a mesh floor and on a height field, sliding across internal
// edges without catching, rays and shape casts, a kinematic mesh platform,
// and snapshots that name their geometry and restore bit for bit.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

// A flat square floor of n x n cells (2 triangles each), `cell` m wide,
// top at y = 0, centred on the origin, vertices shared between cells.
GeometryId flat_floor(World3D& world, int n, float cell) {
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
  const float half = 0.5f * cell * static_cast<float>(n);
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) {
      vertices.push_back(
          {static_cast<float>(c) * cell - half, 0.0f, static_cast<float>(r) * cell - half});
    }
  }
  const auto at = [n](int r, int c) { return static_cast<uint32_t>(r * (n + 1) + c); };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      // Counter-clockwise seen from above (+y).
      indices.insert(indices.end(), {at(r, c), at(r + 1, c), at(r + 1, c + 1)});
      indices.insert(indices.end(), {at(r, c), at(r + 1, c + 1), at(r, c + 1)});
    }
  }
  auto id = world.geometry().add_mesh(vertices, indices);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

BodyId add_static(World3D& world, Shape shape, Vec3 position = {}) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = shape;
  def.position = position;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

WorldConfig awake() {
  WorldConfig c;
  c.enable_sleep = false;
  return c;
}

TEST(MeshBodies, RegistrationRefusesBadMeshesAndFields) {
  World3D world;
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  const std::vector<uint32_t> out_of_range = {0, 1, 3};
  EXPECT_EQ(world.geometry().add_mesh(v, out_of_range).status().code(),
            ErrorCode::kInvalidArgument);
  const std::vector<uint32_t> repeated = {0, 1, 1};
  EXPECT_FALSE(world.geometry().add_mesh(v, repeated).ok());
  const std::vector<uint32_t> partial = {0, 1};
  EXPECT_FALSE(world.geometry().add_mesh(v, partial).ok());
  std::vector<float> heights(4, 0.0f);
  heights[2] = std::nanf("");
  EXPECT_FALSE(world.geometry().add_height_field(2, 2, {1, 1, 1}, heights).ok());
  EXPECT_FALSE(world.geometry().add_height_field(1, 2, {1, 1, 1}, heights).ok());
  EXPECT_EQ(world.geometry().size(), 0u);
}

TEST(MeshBodies, MeshesAreNeverDynamic) {
  World3D world;
  const GeometryId floor = flat_floor(world, 2, 1.0f);
  BodyDef def;
  def.shape = Shape::make_mesh(floor);
  auto r = world.create_body(def);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
  def.kind = BodyKind::kKinematic;
  EXPECT_TRUE(world.create_body(def).ok());
}

TEST(MeshBodies, EveryShapeRestsOnAMeshFloor) {
  World3D world(awake());
  const GeometryId floor = flat_floor(world, 20, 1.0f);
  add_static(world, Shape::make_mesh(floor));
  const std::vector<Vec3> gem = {{0.3f, 0.0f, 0.0f},  {-0.3f, 0.0f, 0.05f}, {0.0f, 0.3f, 0.0f},
                                 {0.0f, -0.3f, 0.0f}, {0.0f, 0.0f, 0.3f},   {0.05f, 0.0f, -0.3f}};
  const GeometryId hull = *world.geometry().add_hull(gem);
  const BodyId box = test::add_box(world, {0.3f, 0.6f, 0.2f});  // spans four cells
  const BodyId ball = test::add_sphere(world, {3.0f, 1.0f, 0.0f}, 0.4f);
  BodyDef cap;
  cap.shape = Shape::make_capsule(0.2f, 0.5f);
  cap.position = {-3.0f, 1.0f, 0.0f};
  cap.rotation = {0.0f, 0.0f, 0.7071068f, 0.7071068f};  // lying along x
  const BodyId capsule = *world.create_body(cap);
  BodyDef h;
  h.shape = Shape::make_hull(hull);
  h.position = {0.0f, 1.0f, 3.0f};
  const BodyId rock = *world.create_body(h);
  test::step_seconds(world, 3.0f);
  const float slop = world.config().linear_slop_m;
  EXPECT_NEAR(world.position(box).y, 0.5f, slop + 1e-3f);
  EXPECT_NEAR(world.position(ball).y, 0.4f, slop + 1e-3f);
  EXPECT_NEAR(world.position(capsule).y, 0.2f, slop + 1e-3f);
  // The rock rests on a face: its lowest corner on the floor.
  std::vector<Vec3> corners;
  world.geometry().hull_vertices(hull, corners);
  float lowest = 1e9f;
  for (const Vec3& c : corners) {
    lowest = std::min(lowest, (world.position(rock) + rotate(world.rotation(rock), c)).y);
  }
  EXPECT_NEAR(lowest, 0.0f, slop + 1e-3f);
  for (const BodyId id : {box, ball, capsule, rock}) {
    EXPECT_LT(length(world.linear_velocity(id)), 0.02f);
  }
  // The box landed flat and did not wander.
  EXPECT_NEAR(world.position(box).x, 0.3f, 0.01f);
  EXPECT_NEAR(world.position(box).z, 0.2f, 0.01f);
}

TEST(MeshBodies, ABoxSlidesAcrossInternalEdgesWithoutCatching) {
  // Frictionless: a box sliding over a floor of 0.25 m cells keeps its
  // speed (an edge contact catching it would slow it or tip it).
  World3D world(awake());
  const GeometryId floor = flat_floor(world, 80, 0.25f);
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_mesh(floor);
  ground.material.friction = 0.0f;
  (void)*world.create_body(ground);
  BodyDef b;
  b.shape = Shape::make_box({0.3f, 0.2f, 0.3f});
  b.position = {-8.0f, 0.2f, 0.1f};
  b.linear_velocity = {5.0f, 0.0f, 0.0f};
  b.material.friction = 0.0f;
  b.angular_damping = 0.0f;
  const BodyId box = *world.create_body(b);
  float max_tilt = 0.0f;
  for (int t = 0; t < 120; ++t) {
    world.step();
    const Quat q = world.rotation(box);
    max_tilt = std::max(max_tilt, std::fabs(q.x) + std::fabs(q.z));
    ASSERT_NEAR(world.linear_velocity(box).x, 5.0f, 0.05f) << "tick " << t;
  }
  EXPECT_LT(max_tilt, 1e-3f);
  EXPECT_NEAR(world.position(box).y, 0.2f, world.config().linear_slop_m + 1e-3f);
}

TEST(MeshBodies, BoxesRestOnAHeightFieldSlope) {
  World3D world(awake());
  // A plane rising 0.1 m per metre along x, 1 m cells, 21 x 21 samples.
  const uint32_t n = 21;
  std::vector<float> heights(n * n);
  for (uint32_t r = 0; r < n; ++r) {
    for (uint32_t c = 0; c < n; ++c) heights[r * n + c] = 0.1f * static_cast<float>(c);
  }
  const GeometryId field = *world.geometry().add_height_field(n, n, {1.0f, 1.0f, 1.0f}, heights);
  add_static(world, Shape::make_height_field(field), {-10.0f, 0.0f, -10.0f});
  // Spheres (which roll) and a sticky box (which stays).
  const BodyId ball = test::add_sphere(world, {0.0f, 2.0f, 0.0f}, 0.3f);
  const BodyId box = test::add_box(world, {-4.0f, 1.5f, 3.0f}, {0.3f, 0.3f, 0.3f}, 0.0f, 0.9f);
  test::step_seconds(world, 2.0f);
  // The box settles on the slope (its lowest corner on the surface) and
  // stays; the ball rolls down toward -x.
  const float surface_at_box = 0.1f * (world.position(box).x + 10.0f);
  EXPECT_GT(world.position(box).y, surface_at_box);
  EXPECT_LT(world.position(box).y, surface_at_box + 0.45f);
  EXPECT_LT(length(world.linear_velocity(box)), 0.02f);
  EXPECT_LT(world.linear_velocity(ball).x, -0.3f);
  // A ray straight down finds the surface at the analytic height.
  auto hit = world.raycast({{2.5f, 10.0f, 1.5f}, {0.0f, -1.0f, 0.0f}, 20.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->point.y, 0.1f * 12.5f, 1e-4f);
  EXPECT_NEAR(hit->normal.y, 1.0f / std::sqrt(1.01f), 1e-4f);
}

TEST(MeshBodies, HolesLetThingsThrough) {
  World3D world(awake());
  std::vector<float> heights(9, 0.0f);
  std::vector<uint8_t> holes = {0, 1, 0, 0};  // cell (row 0, col 1) open
  const GeometryId field =
      *world.geometry().add_height_field(3, 3, {2.0f, 1.0f, 2.0f}, heights, holes);
  add_static(world, Shape::make_height_field(field));
  EXPECT_FALSE(world.raycast({{3.0f, 5.0f, 1.0f}, {0.0f, -1.0f, 0.0f}, 10.0f}).has_value());
  EXPECT_TRUE(world.raycast({{1.0f, 5.0f, 1.0f}, {0.0f, -1.0f, 0.0f}, 10.0f}).has_value());
  const BodyId through = test::add_sphere(world, {3.0f, 1.0f, 1.0f}, 0.3f);
  const BodyId held = test::add_sphere(world, {1.0f, 1.0f, 3.0f}, 0.3f);
  test::step_seconds(world, 1.5f);
  EXPECT_LT(world.position(through).y, -2.0f);
  EXPECT_NEAR(world.position(held).y, 0.3f, world.config().linear_slop_m + 1e-3f);
}

TEST(MeshBodies, ShapeCastsAndOverlapsFindTheFloor) {
  World3D world;
  const GeometryId floor = flat_floor(world, 10, 1.0f);
  const BodyId ground = add_static(world, Shape::make_mesh(floor), {0.0f, 1.0f, 0.0f});
  std::optional<ShapeCastHit> hit;
  ASSERT_TRUE(world
                  .shape_cast(Shape::make_sphere(0.5f), {0.5f, 10.0f, 0.5f}, {},
                              {0.0f, -20.0f, 0.0f}, {}, hit)
                  .ok());
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ground);
  EXPECT_NEAR(hit->distance, 10.0f - 1.0f - 0.5f, 2e-3f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-4f);
  // A mesh cannot be swept.
  EXPECT_EQ(world.shape_cast(Shape::make_mesh(floor), {}, {}, {0.0f, -1.0f, 0.0f}, {}, hit).code(),
            ErrorCode::kInvalidArgument);
  std::vector<BodyId> out;
  ASSERT_TRUE(
      world.overlap(Shape::make_box({0.5f, 0.5f, 0.5f}), {2.0f, 1.3f, 2.0f}, {}, {}, out).ok());
  EXPECT_EQ(out.size(), 1u);
  ASSERT_TRUE(
      world.overlap(Shape::make_box({0.5f, 0.5f, 0.5f}), {2.0f, 1.6f, 2.0f}, {}, {}, out).ok());
  EXPECT_TRUE(out.empty());
}

TEST(MeshBodies, AKinematicMeshPlatformCarriesABox) {
  World3D world(awake());
  const GeometryId deck = flat_floor(world, 4, 0.5f);
  BodyDef platform;
  platform.kind = BodyKind::kKinematic;
  platform.shape = Shape::make_mesh(deck);
  platform.position = {0.0f, 1.0f, 0.0f};
  platform.linear_velocity = {1.0f, 0.0f, 0.0f};
  const BodyId p = *world.create_body(platform);
  const BodyId box = test::add_box(world, {0.0f, 1.25f, 0.0f}, {0.25f, 0.25f, 0.25f}, 0.0f, 0.9f);
  test::step_seconds(world, 2.0f);
  EXPECT_NEAR(world.position(p).x, 2.0f, 1e-3f);
  // Friction takes the box up to the platform's speed: it lags by
  // v^2 / (2 mu g), mu = sqrt(0.9 * 0.6) (the platform keeps the default).
  const float mu = std::sqrt(0.9f * 0.6f);
  EXPECT_NEAR(world.position(box).x, 2.0f - 1.0f / (2.0f * mu * 9.81f), 0.01f);
  EXPECT_NEAR(world.linear_velocity(box).x, 1.0f, 1e-3f);
  EXPECT_NEAR(world.position(box).y, 1.25f, world.config().linear_slop_m + 2e-3f);
}

TEST(MeshBodies, SnapshotsNameTheirMeshesAndRestoreBitForBit) {
  World3D world;
  const GeometryId floor = flat_floor(world, 12, 1.0f);
  add_static(world, Shape::make_mesh(floor));
  std::vector<float> heights(25);
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = 0.05f * static_cast<float>(i % 5);
  const GeometryId field = *world.geometry().add_height_field(5, 5, {1.0f, 1.0f, 1.0f}, heights);
  add_static(world, Shape::make_height_field(field), {2.0f, 0.5f, 2.0f});
  for (int i = 0; i < 10; ++i) {
    test::add_box(world,
                  {-2.0f + 0.5f * static_cast<float>(i), 1.0f + 0.6f * static_cast<float>(i),
                   0.3f * static_cast<float>(i % 3)},
                  {0.2f, 0.2f, 0.2f});
  }
  test::step_seconds(world, 0.5f);
  test::expect_snapshots_restore(world);
}

}  // namespace
}  // namespace rwd::sim
