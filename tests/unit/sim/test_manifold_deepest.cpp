// SPDX-License-Identifier: MIT
// Property: a contact manifold's deepest point is as deep as the moving
// body's deepest corner. The oracle is World3D::signed_distance of each
// corner of a box or a convex hull to the static body (a box, a triangle
// mesh or a height field), which is exact for the planar grounds used here;
// the manifold, World3D::contact_manifold at max_separation 0, must report a
// point that deep within kAbsTolerance or kRelTolerance of the depth.
// Random poses put the body from 1 mm to 6 cm into the ground at every
// rotation; the solver pushes out whatever the manifold reports, so a
// corner it misses sinks (a hull resting on a point of a face while a
// corner of it is a centimetre into the floor). On a bumpy height field
// (folds between cells) the oracle also measures where the body's chords
// cross the folds, within a looser tolerance (BoxAndHullOnABumpyField).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr float kAbsTolerance = 0.001f;  // metres
constexpr float kRelTolerance = 0.01f;   // of the depth
constexpr float kMinDepth = 0.001f;      // shallower overlaps are not checked
constexpr int kPoses = 300;

// The corners of a body of `points` (its frame) as it stands.
std::vector<Vec3> corners(const World3D& world, BodyId id, const std::vector<Vec3>& points) {
  std::vector<Vec3> out;
  const Vec3 p = world.position(id);
  const Quat q = world.rotation(id);
  for (const Vec3& v : points) out.push_back(p + rotate(q, v));
  return out;
}

std::vector<Vec3> box_points(Vec3 h) {
  std::vector<Vec3> out;
  for (int i = 0; i < 8; ++i) {
    out.push_back({(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  }
  return out;
}

// Irregular hulls: points on a lumpy ellipsoid (every one a corner), and
// clouds in a flat slab and in a cube (some points inside, which the hull
// drops; they cannot be deeper than its corners, so the oracle may keep
// them).
std::vector<Vec3> hull_points(int kind) {
  test::Rng rng{77u + static_cast<uint64_t>(kind)};
  std::vector<Vec3> out;
  const size_t count = kind == 0 ? 14 : (kind == 1 ? 30 : 9);
  while (out.size() < count) {
    const Vec3 d{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
    if (kind == 0) {
      const float len = std::sqrt(dot(d, d));
      if (len < 0.2f || len > 1.0f) continue;
      const Vec3 u = d * (1.0f / len);
      out.push_back({0.45f * u.x, 0.3f * u.y, 0.35f * u.z});
    } else if (kind == 1) {
      out.push_back({0.5f * d.x, 0.12f * d.y, 0.4f * d.z});
    } else {
      out.push_back({0.35f * d.x, 0.35f * d.y, 0.35f * d.z});
    }
  }
  return out;
}

struct Moving {
  Shape shape;
  std::vector<Vec3> points;  // its corners (or points whose hull it is), body frame
};

struct Stats {
  int checked = 0;
  int failed = 0;
};

// Points of the body the oracle measures besides its corners, from the
// corners as the body stands (none on planar ground, where a corner is
// always the deepest point).
using MorePoints = std::function<std::vector<Vec3>(const std::vector<Vec3>&)>;

// The deepest corner's signed distance to `ground`.
float oracle_depth(const World3D& world, BodyId ground, const std::vector<Vec3>& pts) {
  float deepest = 1e9f;
  for (const Vec3& v : pts) {
    const std::optional<PointHit> d = world.signed_distance(ground, v);
    if (d) deepest = std::fmin(deepest, d->distance);
  }
  return deepest;
}

// Checks the manifold of (ground, body) against the oracle; prints a
// failure so the pose can be reproduced.
void check(const World3D& world, BodyId ground, BodyId body, const std::vector<Vec3>& pts,
           const char* what, int pose, Stats& stats, float rel_tolerance = kRelTolerance) {
  const float oracle = oracle_depth(world, ground, pts);
  if (!(oracle < -kMinDepth)) return;
  ++stats.checked;
  const std::optional<ContactManifold> m = world.contact_manifold(ground, body);
  float deepest = 1e9f;
  if (m) {
    for (uint32_t i = 0; i < m->point_count; ++i) {
      deepest = std::fmin(deepest, m->points[i].separation);
    }
  }
  const float tolerance = std::fmax(kAbsTolerance, rel_tolerance * -oracle);
  if (std::fabs(deepest - oracle) <= tolerance) return;
  ++stats.failed;
  if (stats.failed <= 5) {
    const Vec3 p = world.position(body);
    const Quat q = world.rotation(body);
    ADD_FAILURE() << what << " pose " << pose << ": deepest point " << oracle * 1000.0f
                  << " mm, manifold " << (m ? deepest * 1000.0f : 0.0f) << " mm over "
                  << (m ? m->point_count : 0u) << " points; at (" << p.x << ", " << p.y << ", "
                  << p.z << ") rotation (" << q.x << ", " << q.y << ", " << q.z << ", " << q.w
                  << ")";
  }
}

// Random poses of `moving` over a ground whose surface height at (x, z) is
// about `height` (used only to place the body; the oracle measures).
Stats random_poses(World3D& world, BodyId ground, const Moving& moving,
                   const std::function<float(float, float)>& height, Vec3 centre, float spread,
                   const char* what, uint64_t seed, float rel_tolerance = kRelTolerance,
                   const MorePoints& more = {}) {
  test::Rng rng{seed};
  Stats stats;
  for (int k = 0; k < kPoses; ++k) {
    const Quat q = rng.rotation();
    const float x = centre.x + rng.uniform(-spread, spread);
    const float z = centre.z + rng.uniform(-spread, spread);
    const float depth = rng.uniform(0.001f, 0.06f);
    // Lift so the corner lowest against the surface is `depth` under it.
    float lowest = 1e9f;
    for (const Vec3& v : moving.points) {
      const Vec3 w = rotate(q, v);
      lowest = std::fmin(lowest, w.y - height(x + w.x, z + w.z));
    }
    BodyDef def;
    def.shape = moving.shape;
    def.position = {x, -lowest - depth, z};
    def.rotation = q;
    const auto id = world.create_body(def);
    EXPECT_TRUE(id.ok());
    if (!id.ok()) continue;
    std::vector<Vec3> pts = corners(world, *id, moving.points);
    if (more) {
      const std::vector<Vec3> extra = more(pts);
      pts.insert(pts.end(), extra.begin(), extra.end());
    }
    check(world, ground, *id, pts, what, k, stats, rel_tolerance);
    EXPECT_TRUE(world.destroy_body(*id).ok());
  }
  std::printf("[ deepest ] %s: %d of %d overlapping poses failed\n", what, stats.failed,
              stats.checked);
  return stats;
}

Moving make_box_moving() {
  const Vec3 h{0.4f, 0.25f, 0.3f};
  return {Shape::make_box(h), box_points(h)};
}

std::vector<Moving> make_hulls(World3D& world) {
  std::vector<Moving> out;
  for (int kind = 0; kind < 3; ++kind) {
    std::vector<Vec3> pts = hull_points(kind);
    const auto id = world.geometry().add_hull_from_points(pts);
    EXPECT_TRUE(id.ok());
    out.push_back({Shape::make_hull(*id), pts});
  }
  return out;
}

// Random poses of every hull; the failures summed.
int hull_poses(World3D& world, BodyId ground, const std::vector<Moving>& hulls,
               const std::function<float(float, float)>& height, Vec3 centre, float spread,
               const char* what, uint64_t seed, float rel_tolerance = kRelTolerance,
               const MorePoints& more = {}) {
  int failed = 0;
  for (size_t k = 0; k < hulls.size(); ++k) {
    failed += random_poses(world, ground, hulls[k], height, centre, spread, what, seed + 100 * k,
                           rel_tolerance, more)
                  .failed;
  }
  return failed;
}

float flat(float, float) {
  return 0.0f;
}

TEST(ManifoldDeepest, BoxAndHullOnAGroundBox) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const Moving box = make_box_moving();
  const std::vector<Moving> hulls = make_hulls(world);
  EXPECT_EQ(random_poses(world, ground, box, flat, {}, 3.0f, "box on box", 1).failed, 0);
  EXPECT_EQ(hull_poses(world, ground, hulls, flat, {}, 3.0f, "hull on box", 2), 0);
}

TEST(ManifoldDeepest, BoxAndHullOnATriangleAndAMesh) {
  World3D world;
  // One large triangle, facing +y.
  const std::vector<Vec3> tri = {
      {-20.0f, 0.0f, -20.0f}, {0.0f, 0.0f, 20.0f}, {20.0f, 0.0f, -20.0f}};
  const std::vector<uint32_t> tri_index = {0, 1, 2};
  const BodyId lone =
      test::add_static(world, Shape::make_mesh(*world.geometry().add_mesh(tri, tri_index)), {});
  // A flat 4 x 4 grid of 1 m quads, two triangles each, 100 m away.
  std::vector<Vec3> grid;
  std::vector<uint32_t> grid_index;
  for (uint32_t r = 0; r <= 4; ++r) {
    for (uint32_t c = 0; c <= 4; ++c) grid.push_back({c - 2.0f, 0.0f, r - 2.0f});
  }
  for (uint32_t r = 0; r < 4; ++r) {
    for (uint32_t c = 0; c < 4; ++c) {
      const uint32_t i = r * 5 + c;
      grid_index.insert(grid_index.end(), {i, i + 5, i + 1, i + 1, i + 5, i + 6});
    }
  }
  const BodyId mesh = test::add_static(
      world, Shape::make_mesh(*world.geometry().add_mesh(grid, grid_index)), {100.0f, 0.0f, 0.0f});
  const Moving box = make_box_moving();
  const std::vector<Moving> hulls = make_hulls(world);
  EXPECT_EQ(random_poses(world, lone, box, flat, {}, 3.0f, "box on a triangle", 3).failed, 0);
  EXPECT_EQ(hull_poses(world, lone, hulls, flat, {}, 3.0f, "hull on a triangle", 4), 0);
  EXPECT_EQ(
      random_poses(world, mesh, box, flat, {100.0f, 0.0f, 0.0f}, 1.0f, "box on a mesh", 5).failed,
      0);
  EXPECT_EQ(hull_poses(world, mesh, hulls, flat, {100.0f, 0.0f, 0.0f}, 1.0f, "hull on a mesh", 6),
            0);
}

TEST(ManifoldDeepest, BoxAndHullOnHeightFields) {
  World3D world;
  constexpr uint32_t n = 9;
  // Flat, and a plane sloping up 1 in 10 along x and 1 in 20 along z (both
  // planar, so the oracle is exact).
  std::vector<float> level(n * n, 0.0f);
  std::vector<float> slope(n * n);
  for (uint32_t r = 0; r < n; ++r) {
    for (uint32_t c = 0; c < n; ++c) slope[r * n + c] = 0.1f * c + 0.05f * r;
  }
  const BodyId flat_field = test::add_static(
      world, Shape::make_height_field(*world.geometry().add_height_field(n, n, {1, 1, 1}, level)),
      {-4.0f, 0.0f, -4.0f});
  const BodyId sloped_field = test::add_static(
      world, Shape::make_height_field(*world.geometry().add_height_field(n, n, {1, 1, 1}, slope)),
      {96.0f, 0.0f, -4.0f});
  auto sloped = [](float x, float z) { return 0.1f * (x - 96.0f) + 0.05f * (z + 4.0f); };
  const Moving box = make_box_moving();
  const std::vector<Moving> hulls = make_hulls(world);
  EXPECT_EQ(random_poses(world, flat_field, box, flat, {}, 2.5f, "box on a field", 7).failed, 0);
  EXPECT_EQ(hull_poses(world, flat_field, hulls, flat, {}, 2.5f, "hull on a field", 8), 0);
  EXPECT_EQ(random_poses(world, sloped_field, box, sloped, {100.0f, 0.0f, 0.0f}, 2.5f,
                         "box on a sloped field", 9)
                .failed,
            0);
  EXPECT_EQ(hull_poses(world, sloped_field, hulls, sloped, {100.0f, 0.0f, 0.0f}, 2.5f,
                       "hull on a sloped field", 10),
            0);
}

// Where the chords between the body's points (its edges among them, and
// segments through it) cross the cell edges of a field whose cells are
// `cell` apart from (origin.x, origin.z), diagonals (x - z constant, as
// height_field.h splits cells) included. On a folded surface the body's
// deepest point need not be a corner: a ridge pokes into a body's edge
// deeper than either end, at a cell edge.
std::vector<Vec3> fold_crossings(const std::vector<Vec3>& pts, Vec3 origin, float cell) {
  std::vector<Vec3> out;
  auto cross_lines = [&](Vec3 a, Vec3 b, float fa, float fb) {
    const float lo = std::fmin(fa, fb);
    const float hi = std::fmax(fa, fb);
    for (float k = std::ceil(lo); k < hi; k += 1.0f) {
      const float t = (k - fa) / (fb - fa);
      out.push_back(a + (b - a) * t);
    }
  };
  for (size_t i = 0; i < pts.size(); ++i) {
    for (size_t j = i + 1; j < pts.size(); ++j) {
      const Vec3 a = pts[i];
      const Vec3 b = pts[j];
      const float ax = (a.x - origin.x) / cell;
      const float az = (a.z - origin.z) / cell;
      const float bx = (b.x - origin.x) / cell;
      const float bz = (b.z - origin.z) / cell;
      cross_lines(a, b, ax, bx);
      cross_lines(a, b, az, bz);
      cross_lines(a, b, ax - az, bx - bz);
    }
  }
  return out;
}

// A bumpy field (a random terrain, folds of a few degrees between cells).
// The surface is not one plane here, so the oracle is not exact: near a
// fold the manifold measures along one contact normal (blended across the
// fold) and signed_distance to the nearest surface point. The oracle also
// measures the points where the body's chords cross the folds
// (fold_crossings), and the check is looser (kBumpyTolerance of the
// depth): at the time of writing every pose is within 1% (or 1 mm), and
// 5% leaves room while catching a point missed outright, which reads a
// fraction of its depth or nothing.
constexpr float kBumpyTolerance = 0.05f;

// Among them, corners just past a convex fold (a ridge between two
// cells): EPA against the triangle a corner lies under, alone, finds the
// shortest way out sideways across the fold, a fraction of the corner's
// depth (a box corner 48.6 mm deep read 35.6 mm); such a contact now
// takes the neighbour's face across the fold (clamp_to_folds,
// manifold_triangle_contact.cpp). Before that, the box failed 7 of 295
// overlapping poses and the three hulls 4 of 298, 5 of 298 and 8 of 296
// (1, 0, 1 and 1 at a 25% tolerance).
TEST(ManifoldDeepest, BoxAndHullOnABumpyField) {
  World3D world;
  constexpr uint32_t n = 9;
  std::vector<float> bumps(n * n);
  test::Rng rng{31};
  for (float& h : bumps) h = rng.uniform(0.0f, 0.05f);
  const GeometryId id = *world.geometry().add_height_field(n, n, {1, 1, 1}, bumps);
  const BodyId field = test::add_static(world, Shape::make_height_field(id), {-4.0f, 0.0f, -4.0f});
  // Placing only: the surface height under (x, z), read from the signed
  // distance of a point above it (the field is flat enough that the
  // nearest surface point is nearly straight below), the highest of three
  // nearby reads so a corner near a fold is not placed too deep.
  auto height = [&](float x, float z) {
    float best = 0.0f;
    for (float dz : {-0.01f, 0.0f, 0.01f}) {
      const std::optional<PointHit> d = world.signed_distance(field, {x, 1.0f, z + dz});
      if (d) best = std::fmax(best, 1.0f - d->distance);
    }
    return best;
  };
  // The field's samples start at (-4, -4) in x and z (its body's position),
  // 1 m apart.
  const MorePoints crossings = [](const std::vector<Vec3>& pts) {
    return fold_crossings(pts, {-4.0f, 0.0f, -4.0f}, 1.0f);
  };
  const Moving box = make_box_moving();
  const std::vector<Moving> hulls = make_hulls(world);
  EXPECT_EQ(random_poses(world, field, box, height, {}, 2.5f, "box on a bumpy field", 11,
                         kBumpyTolerance, crossings)
                .failed,
            0);
  EXPECT_EQ(hull_poses(world, field, hulls, height, {}, 2.5f, "hull on a bumpy field", 12,
                       kBumpyTolerance, crossings),
            0);
}

// A hull dropped on the ground box and left to settle: at every tick of
// the way, the manifold the solver uses sees the deepest corner.
TEST(ManifoldDeepest, FallingHullKeepsItsDeepestCorner) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const std::vector<Moving> hulls = make_hulls(world);
  Stats stats;
  std::vector<std::pair<BodyId, size_t>> dropped;  // body, its hull
  for (int drop = 0; drop < 6; ++drop) {
    test::Rng rng{100u + static_cast<uint64_t>(drop)};
    BodyDef def;
    def.shape = hulls[static_cast<size_t>(drop) % hulls.size()].shape;
    def.position = {4.0f * static_cast<float>(drop) - 10.0f, 1.0f, 0.0f};
    def.rotation = rng.rotation();
    def.angular_velocity = {rng.uniform(-3.0f, 3.0f), rng.uniform(-3.0f, 3.0f),
                            rng.uniform(-3.0f, 3.0f)};
    const auto id = world.create_body(def);
    ASSERT_TRUE(id.ok());
    dropped.push_back({*id, static_cast<size_t>(drop) % hulls.size()});
  }
  for (int tick = 0; tick < 180; ++tick) {
    world.step();
    for (const auto& [id, hull] : dropped) {
      check(world, ground, id, corners(world, id, hulls[hull].points), "falling hull", tick, stats);
    }
  }
  std::printf("[ deepest ] falling hulls: %d of %d overlapping ticks failed\n", stats.failed,
              stats.checked);
  EXPECT_EQ(stats.failed, 0);
}

}  // namespace
}  // namespace rwd::sim
