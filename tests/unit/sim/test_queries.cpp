// SPDX-License-Identifier: MIT
// Queries through the broadphase: overlap, ray and nearest-body queries
// against a brute force over every body (same exact tests), in a mixed
// scene that moves, sleeps, is edited and restored between queries;
// filters; signed distances to each shape; bad arguments.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "d3/shape_ops.h"
#include "rewind/sim/det_math.h"
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

// Signed distances to surfaces (meshes and height fields): negative behind
// the surface, with the magnitude of the distance to it. Tolerances are
// absolute, in metres: 1e-5 for a few metres of float coordinates, 2e-5
// where the point also passes through a rotated body's frame.

// A box of half extents h about the origin as a mesh: two triangles per
// face, counter-clockwise seen from outside. `welded`: the eight corners
// are shared; otherwise every face has its own four vertices (duplicates
// at the same coordinates).
struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;
};
MeshData box_mesh(Vec3 h, bool welded) {
  MeshData m;
  const auto corner = [h](int i) {
    return Vec3{(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z};
  };
  if (welded) {
    for (int i = 0; i < 8; ++i) m.vertices.push_back(corner(i));
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int u = 1 << ((axis + 1) % 3);
    const int v = 1 << ((axis + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const int base = side ? 1 << axis : 0;
      // base, +u, +u+v, +v runs counter-clockwise about +axis.
      const int quad[4] = {base, base | u, base | u | v, base | v};
      uint32_t at[4];
      for (int k = 0; k < 4; ++k) {
        if (welded) {
          at[k] = static_cast<uint32_t>(quad[k]);
        } else {
          at[k] = static_cast<uint32_t>(m.vertices.size());
          m.vertices.push_back(corner(quad[k]));
        }
      }
      if (side == 1) {
        m.indices.insert(m.indices.end(), {at[0], at[1], at[2], at[0], at[2], at[3]});
      } else {
        m.indices.insert(m.indices.end(), {at[0], at[2], at[1], at[0], at[3], at[2]});
      }
    }
  }
  return m;
}

BodyId add_static_shape(World3D& world, Shape shape, Vec3 position, Quat rotation = {}) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = shape;
  def.position = position;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

// The signed distance of q to the box of half extents h about the origin.
float box_distance(Vec3 q, Vec3 h) {
  const Vec3 d = abs(q) - h;
  const float inside = std::fmin(std::fmax(d.x, std::fmax(d.y, d.z)), 0.0f);
  return length(max(d, Vec3{})) + inside;
}

TEST(Queries, SignedDistanceUnderAFlatHeightFieldIsNegative) {
  World3D world;
  // 11 x 11 samples 1 m apart at height 0, the footprint x, z in [-5, 5].
  const std::vector<float> heights(121, 0.0f);
  const GeometryId flat = *world.geometry().add_height_field(11, 11, {1.0f, 1.0f, 1.0f}, heights);
  const BodyId field =
      add_static_shape(world, Shape::make_height_field(flat), {-5.0f, 0.0f, -5.0f});
  auto d = world.signed_distance(field, {0.3f, -0.1f, 0.2f});
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->distance, -0.1f, 1e-5f);
  EXPECT_NEAR(d->point.y, 0.0f, 1e-5f);
  EXPECT_NEAR(d->normal.y, 1.0f, 1e-5f);  // outward: up, on either side
  d = world.signed_distance(field, {0.3f, 0.1f, 0.2f});
  EXPECT_NEAR(d->distance, 0.1f, 1e-5f);
  EXPECT_NEAR(d->normal.y, 1.0f, 1e-5f);
  // Deep under it, and under a sample and a cell edge (where the nearest
  // feature is a vertex or an edge, not a face).
  EXPECT_NEAR(world.signed_distance(field, {1.3f, -2.0f, 0.7f})->distance, -2.0f, 1e-5f);
  EXPECT_NEAR(world.signed_distance(field, {1.0f, -0.25f, 2.0f})->distance, -0.25f, 1e-5f);
  EXPECT_NEAR(world.signed_distance(field, {1.0f, -0.25f, 2.5f})->distance, -0.25f, 1e-5f);
  // Outside the footprint a point is never behind the field: 3 m beyond
  // its +x border and 1 m below, sqrt(10) from the border edge.
  d = world.signed_distance(field, {8.0f, -1.0f, 0.0f});
  EXPECT_NEAR(d->distance, std::sqrt(10.0f), 1e-5f);
  EXPECT_NEAR(d->point.x, 5.0f, 1e-5f);
  // The nearest body from below is the field, at its negative distance,
  // when its surface is within reach.
  const auto n = world.nearest_body({0.3f, -0.1f, 0.2f}, 0.2f);
  ASSERT_TRUE(n.has_value());
  EXPECT_EQ(n->body, field);
  EXPECT_NEAR(n->distance, -0.1f, 1e-5f);
  EXPECT_FALSE(world.nearest_body({0.3f, -0.1f, 0.2f}, 0.05f).has_value());
}

TEST(Queries, SignedDistanceUnderAHoleIsPositive) {
  World3D world;
  const std::vector<float> heights(9, 0.0f);
  const std::vector<uint8_t> holes = {0, 1, 0, 0};  // cell (row 0, col 1): x in [2, 4], z in [0, 2]
  const GeometryId id =
      *world.geometry().add_height_field(3, 3, {2.0f, 1.0f, 2.0f}, heights, holes);
  const BodyId field = add_static_shape(world, Shape::make_height_field(id), {});
  // Under the hole's middle: 1 m to its edges (x = 2, x = 4, z = 2), 0.5 m down.
  auto d = world.signed_distance(field, {3.0f, -0.5f, 1.0f});
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->distance, std::sqrt(1.25f), 1e-5f);
  // Under ground beside it.
  d = world.signed_distance(field, {1.0f, -0.5f, 1.0f});
  EXPECT_NEAR(d->distance, -0.5f, 1e-5f);
}

// Heights 1 - 0.5 |x - 5| (a roof) or 0.5 |x - 5| (a valley) over x in
// [0, 10], the same along z: the surface is two slopes meeting at a ridge
// or a crease, so the distance is the distance to two segments in the
// (x, y) plane, negative under the surface.
void expect_tent_matches_analytic(bool roof) {
  World3D world;
  const uint32_t cols = 11;
  const uint32_t rows = 7;
  const auto height = [roof](float x) {
    const float slope = 0.5f * std::fabs(x - 5.0f);
    return roof ? 1.0f - slope : slope;
  };
  std::vector<float> heights(rows * cols);
  for (uint32_t r = 0; r < rows; ++r) {
    for (uint32_t c = 0; c < cols; ++c) heights[r * cols + c] = height(static_cast<float>(c));
  }
  const GeometryId id = *world.geometry().add_height_field(rows, cols, {1.0f, 1.0f, 1.0f}, heights);
  const Vec3 origin{-5.0f, 2.0f, -3.0f};
  const BodyId field = add_static_shape(world, Shape::make_height_field(id), origin);
  const auto to_segment = [](float px, float py, float ax, float ay, float bx, float by) {
    const float ex = bx - ax;
    const float ey = by - ay;
    float t = ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey);
    t = std::fmin(std::fmax(t, 0.0f), 1.0f);
    const float dx = px - (ax + ex * t);
    const float dy = py - (ay + ey * t);
    return std::sqrt(dx * dx + dy * dy);
  };
  test::Rng rng;
  rng.state = roof ? 7 : 8;
  for (int i = 0; i < 300; ++i) {
    // Local x in [1, 9], z in [2, 4] (the nearest point keeps its z, well
    // inside the footprint), y from 1.5 m under to 1.5 m over.
    const float x = rng.uniform(1.0f, 9.0f);
    const float y = rng.uniform(-1.5f, 2.5f);
    const float z = rng.uniform(2.0f, 4.0f);
    const float unsigned_d = std::fmin(to_segment(x, y, 0.0f, height(0.0f), 5.0f, height(5.0f)),
                                       to_segment(x, y, 5.0f, height(5.0f), 10.0f, height(10.0f)));
    const float expected = y < height(x) ? -unsigned_d : unsigned_d;
    const auto d = world.signed_distance(field, origin + Vec3{x, y, z});
    ASSERT_TRUE(d.has_value());
    EXPECT_NEAR(d->distance, expected, 1e-5f)
        << (roof ? "roof" : "valley") << " at local " << x << ", " << y << ", " << z;
  }
}

TEST(Queries, SignedDistanceToASlopedHeightFieldMatchesTheAnalyticSurface) {
  expect_tent_matches_analytic(true);
  expect_tent_matches_analytic(false);
}

TEST(Queries, SignedDistanceInsideAClosedMeshBoxIsNegative) {
  World3D world;
  const Vec3 h{1.0f, 0.5f, 2.0f};
  const MeshData m = box_mesh(h, true);
  const GeometryId id = *world.geometry().add_mesh(m.vertices, m.indices);
  const BodyId box = add_static_shape(world, Shape::make_mesh(id), {10.0f, 1.0f, -3.0f});
  const Vec3 at{10.0f, 1.0f, -3.0f};
  // Inside: nearest the top face (0.4 m), then the +x face (0.1 m).
  auto d = world.signed_distance(box, at + Vec3{0.2f, 0.1f, -0.3f});
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->distance, -0.4f, 1e-5f);
  EXPECT_NEAR(d->normal.y, 1.0f, 1e-5f);
  EXPECT_NEAR(d->point.y, at.y + 0.5f, 1e-5f);
  d = world.signed_distance(box, at + Vec3{0.9f, 0.0f, 0.0f});
  EXPECT_NEAR(d->distance, -0.1f, 1e-5f);
  EXPECT_NEAR(d->normal.x, 1.0f, 1e-5f);
  // The centre: 0.5 m from the top and bottom faces.
  EXPECT_NEAR(world.signed_distance(box, at)->distance, -0.5f, 1e-5f);
  // Outside: over the top face, and beyond a corner (nearest a vertex).
  d = world.signed_distance(box, at + Vec3{0.2f, 1.5f, 0.3f});
  EXPECT_NEAR(d->distance, 1.0f, 1e-5f);
  d = world.signed_distance(box, at + Vec3{2.0f, 1.5f, 3.0f});
  EXPECT_NEAR(d->distance, std::sqrt(3.0f), 1e-5f);
  EXPECT_NEAR(d->normal.x, 1.0f / std::sqrt(3.0f), 1e-5f);
  // Beyond an edge (nearest two faces' shared edge).
  d = world.signed_distance(box, at + Vec3{1.3f, 0.9f, 0.0f});
  EXPECT_NEAR(d->distance, 0.5f, 1e-5f);
}

TEST(Queries, SignedDistanceBehindAnOpenTriangleIsNegative) {
  // One triangle in the plane y = 0 facing +y, two-sided and one-sided.
  const std::vector<Vec3> v = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}};
  const std::vector<uint32_t> tri = {0, 1, 2};
  for (const bool one_sided : {false, true}) {
    World3D world;
    const GeometryId id = *world.geometry().add_mesh(v, tri, one_sided);
    const BodyId body = add_static_shape(world, Shape::make_mesh(id), {});
    auto d = world.signed_distance(body, {0.2f, -0.3f, 0.2f});
    ASSERT_TRUE(d.has_value());
    EXPECT_NEAR(d->distance, -0.3f, 1e-5f) << one_sided;
    EXPECT_NEAR(d->normal.y, 1.0f, 1e-5f) << one_sided;
    EXPECT_NEAR(world.signed_distance(body, {0.2f, 0.3f, 0.2f})->distance, 0.3f, 1e-5f);
    // Behind the plane beyond the corner (1, 0, 0): still behind.
    d = world.signed_distance(body, {2.0f, -1.0f, 0.2f});
    EXPECT_NEAR(d->distance, -std::sqrt(2.04f), 1e-5f) << one_sided;
    EXPECT_NEAR(d->point.x, 1.0f, 1e-5f);
    // In front beyond the long edge, and level with the plane past it.
    EXPECT_NEAR(world.signed_distance(body, {1.0f, 0.5f, 1.0f})->distance, std::sqrt(0.5f + 0.25f),
                1e-5f);
    EXPECT_NEAR(world.signed_distance(body, {-1.0f, 0.0f, 0.5f})->distance, 1.0f, 1e-5f);
  }
}

// Random points near, in and around a rotated mesh box, welded and with
// every face's corners duplicated: the signed distance is the analytic
// box's within 2e-5 m, the surface point lies on the box that far from the
// point, and the normal is a unit vector.
TEST(Queries, MeshBoxSignedDistanceMatchesTheAnalyticBox) {
  const Vec3 h{0.7f, 0.4f, 1.1f};
  for (const bool welded : {true, false}) {
    World3D world;
    test::Rng rng;
    rng.state = welded ? 11 : 12;
    const MeshData m = box_mesh(h, welded);
    const GeometryId id = *world.geometry().add_mesh(m.vertices, m.indices);
    const BodyId box =
        add_static_shape(world, Shape::make_mesh(id), {1.5f, 2.0f, -0.5f}, rng.rotation());
    const Vec3 pos = world.position(box);
    const Quat rot = world.rotation(box);
    int inside = 0;
    for (int i = 0; i < 3000; ++i) {
      Vec3 local;
      if (i % 3 == 0) {  // anywhere around the box
        local = {rng.uniform(-2.0f, 2.0f) * h.x, rng.uniform(-2.0f, 2.0f) * h.y,
                 rng.uniform(-2.0f, 2.0f) * h.z};
      } else if (i % 3 == 1) {  // near a face, either side
        local = {rng.uniform(-1.0f, 1.0f) * h.x, rng.uniform(-1.0f, 1.0f) * h.y,
                 rng.uniform(-1.0f, 1.0f) * h.z};
        const int axis = static_cast<int>(rng.next() % 3);
        const float s = (rng.next() & 1) ? 1.0f : -1.0f;
        const float offset = rng.uniform(-0.05f, 0.05f);
        if (axis == 0) local.x = s * (h.x + offset);
        if (axis == 1) local.y = s * (h.y + offset);
        if (axis == 2) local.z = s * (h.z + offset);
      } else {  // near a corner or an edge
        const uint64_t bits = rng.next();
        local = {(bits & 1) ? h.x : -h.x, (bits & 2) ? h.y : -h.y, (bits & 4) ? h.z : -h.z};
        if (bits & 8) local.z = rng.uniform(-1.0f, 1.0f) * h.z;  // along an edge
        local = local +
                Vec3{rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f)};
      }
      const Vec3 p = pos + rotate(rot, local);
      const Vec3 q = inv_rotate(rot, p - pos);  // the point as the body sees it
      const float expected = box_distance(q, h);
      inside += expected < 0.0f ? 1 : 0;
      const auto d = world.signed_distance(box, p);
      ASSERT_TRUE(d.has_value());
      ASSERT_NEAR(d->distance, expected, 2e-5f)
          << (welded ? "welded" : "unwelded") << ", point " << i << " local " << q.x << ", " << q.y
          << ", " << q.z;
      EXPECT_NEAR(box_distance(inv_rotate(rot, d->point - pos), h), 0.0f, 2e-5f) << i;
      EXPECT_NEAR(length(p - d->point), std::fabs(expected), 2e-5f) << i;
      EXPECT_NEAR(length(d->normal), 1.0f, 1e-5f) << i;
    }
    EXPECT_GT(inside, 600);  // both sides well covered
    EXPECT_LT(inside, 2400);
  }
}

// nearest_body() among surfaces and solids against a brute force over
// signed_distance(): a solid counts when the point is within reach of it
// or inside it, a surface when it is within reach on either side.
TEST(Queries, NearestBodyCountsASurfaceWithinReachOnEitherSide) {
  World3D world;
  test::Rng rng;
  rng.state = 5;
  const uint32_t n = 9;
  std::vector<float> heights(n * n);
  for (float& h : heights) h = rng.uniform(-0.3f, 0.3f);
  const GeometryId bumps = *world.geometry().add_height_field(n, n, {0.5f, 1.0f, 0.5f}, heights);
  const MeshData cube = box_mesh({0.5f, 0.5f, 0.5f}, true);
  const GeometryId mesh = *world.geometry().add_mesh(cube.vertices, cube.indices);
  std::vector<BodyId> surfaces;
  surfaces.push_back(
      add_static_shape(world, Shape::make_height_field(bumps), {-2.0f, 0.0f, -2.0f}));
  surfaces.push_back(add_static_shape(world, Shape::make_mesh(mesh), {0.6f, 0.9f, 0.3f}));
  add_static_shape(world, Shape::make_sphere(0.4f), {-0.8f, 0.5f, 0.4f});
  add_static_shape(world, Shape::make_box({0.3f, 0.6f, 0.3f}), {0.9f, -0.4f, -1.0f});
  std::vector<BodyId> every;
  world.body_ids(every);
  int behind_a_surface = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec3 at{rng.uniform(-2.5f, 2.5f), rng.uniform(-1.5f, 2.0f), rng.uniform(-2.5f, 2.5f)};
    const float reach = rng.uniform(0.0f, 0.8f);
    std::optional<PointHit> nearest;
    for (const BodyId id : every) {
      const std::optional<PointHit> d = world.signed_distance(id, at);
      ASSERT_TRUE(d.has_value());
      const bool surface = std::find(surfaces.begin(), surfaces.end(), id) != surfaces.end();
      if (d->distance > reach || (surface && -d->distance > reach)) continue;
      if (!nearest || d->distance < nearest->distance) nearest = d;
    }
    const std::optional<PointHit> found = world.nearest_body(at, reach);
    ASSERT_EQ(found.has_value(), nearest.has_value()) << "point " << k;
    if (found) {
      EXPECT_EQ(found->body, nearest->body) << "point " << k;
      EXPECT_EQ(found->distance, nearest->distance) << "point " << k;
      const bool surface =
          std::find(surfaces.begin(), surfaces.end(), found->body) != surfaces.end();
      behind_a_surface += surface && found->distance < 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(behind_a_surface, 20);
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
