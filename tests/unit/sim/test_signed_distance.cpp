// SPDX-License-Identifier: MIT
// Signed distances to surfaces (meshes and height fields): negative behind
// the surface or below it, against analytic answers and a brute force; and
// nearest_body's reach on either side of a surface.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

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
      test::add_static(world, Shape::make_height_field(flat), {-5.0f, 0.0f, -5.0f});
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
  const BodyId field = test::add_static(world, Shape::make_height_field(id), {});
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
  const BodyId field = test::add_static(world, Shape::make_height_field(id), origin);
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
  const BodyId box = test::add_static(world, Shape::make_mesh(id), {10.0f, 1.0f, -3.0f});
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
    const BodyId body = test::add_static(world, Shape::make_mesh(id), {});
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
        test::add_static(world, Shape::make_mesh(id), {1.5f, 2.0f, -0.5f}, rng.rotation());
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
      test::add_static(world, Shape::make_height_field(bumps), {-2.0f, 0.0f, -2.0f}));
  surfaces.push_back(test::add_static(world, Shape::make_mesh(mesh), {0.6f, 0.9f, 0.3f}));
  test::add_static(world, Shape::make_sphere(0.4f), {-0.8f, 0.5f, 0.4f});
  test::add_static(world, Shape::make_box({0.3f, 0.6f, 0.3f}), {0.9f, -0.4f, -1.0f});
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

}  // namespace
}  // namespace rwd::sim
