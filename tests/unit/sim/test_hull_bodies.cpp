// SPDX-License-Identifier: MIT
// Hull bodies through the public API: the geometry store (errors, ids,
// hashes), a hull body's two frames (authored origin vs centre of mass),
// mass from volume, resting, sliding and tumbling hulls, queries against
// hulls, and snapshots that name their geometry (a world holding other
// geometry refuses them) and restore bit for bit.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

// A triangular prism (a wedge): right angle at the origin, 0.8 m along x,
// 0.5 m up y, 0.6 m deep along z. Its centre of mass is at (0.8/3, 0.5/3,
// 0.3).
std::vector<Vec3> wedge_points() {
  return {{0.0f, 0.0f, 0.0f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
          {0.0f, 0.0f, 0.6f}, {0.8f, 0.0f, 0.6f}, {0.0f, 0.5f, 0.6f}};
}

// The eight corners of a box with the given half sizes, about `center`.
std::vector<Vec3> box_points(Vec3 half, Vec3 center = {}) {
  std::vector<Vec3> out;
  for (float x : {-1.0f, 1.0f}) {
    for (float y : {-1.0f, 1.0f}) {
      for (float z : {-1.0f, 1.0f})
        out.push_back(center + Vec3{x * half.x, y * half.y, z * half.z});
    }
  }
  return out;
}

BodyId add_hull_body(World3D& world, GeometryId hull, Vec3 position, Quat rotation = {}) {
  BodyDef def;
  def.shape = Shape::make_hull(hull);
  def.position = position;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

TEST(GeometryStore, RefusesBadHullsWithAReason) {
  GeometryStore store;
  const std::vector<Vec3> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  auto r = store.add_hull(three);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(r.status().message().empty());
  std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  EXPECT_FALSE(store.add_hull(flat).ok());
  std::vector<Vec3> inner = box_points({1, 1, 1});
  inner.push_back({0.1f, 0.2f, 0.3f});
  EXPECT_FALSE(store.add_hull(inner).ok());
  std::vector<Vec3> nan = box_points({1, 1, 1});
  nan[3].y = std::nanf("");
  EXPECT_FALSE(store.add_hull(nan).ok());
  std::vector<Vec3> far = box_points({1, 1, 1}, {2000.0f, 0.0f, 0.0f});
  EXPECT_FALSE(store.add_hull(far).ok());
  EXPECT_EQ(store.size(), 0u);  // nothing refused was kept
}

TEST(GeometryStore, SameHullSameIdAndHashAcrossStores) {
  GeometryStore a;
  GeometryStore b;
  const GeometryId wa = *a.add_hull(wedge_points());
  const GeometryId wb = *b.add_hull(wedge_points());
  EXPECT_EQ(wa.value, 0u);
  EXPECT_EQ(wa.value, wb.value);
  EXPECT_EQ(a.hash(wa), b.hash(wb));
  EXPECT_NE(a.hash(wa), 0u);
  // Registering it again gives the same id; another hull a new one.
  EXPECT_EQ(a.add_hull(wedge_points())->value, wa.value);
  const GeometryId box = *a.add_hull(box_points({0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(box.value, 1u);
  EXPECT_NE(a.hash(box), a.hash(wa));
  EXPECT_EQ(a.digest(1), b.digest(1));
  EXPECT_NE(a.digest(2), a.digest(1));
  EXPECT_EQ(a.kind(box), GeometryKind::kHull);
  EXPECT_FALSE(a.kind(GeometryId{7}).has_value());
}

TEST(GeometryStore, HullInfoHasTheAnalyticMassProperties) {
  GeometryStore store;
  const GeometryId w = *store.add_hull(wedge_points());
  const auto info = store.hull_info(w);
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->vertex_count, 6u);
  EXPECT_EQ(info->face_count, 5u);  // two triangles, three quads
  EXPECT_EQ(info->edge_count, 9u);
  EXPECT_NEAR(info->volume, 0.5f * 0.8f * 0.5f * 0.6f, 1e-5f);
  EXPECT_NEAR(info->center_of_mass.x, 0.8f / 3.0f, 1e-5f);
  EXPECT_NEAR(info->center_of_mass.y, 0.5f / 3.0f, 1e-5f);
  EXPECT_NEAR(info->center_of_mass.z, 0.3f, 1e-5f);
  std::vector<Vec3> corners;
  store.hull_vertices(w, corners);
  ASSERT_EQ(corners.size(), 6u);
  for (const Vec3& c : corners) {
    bool found = false;
    for (const Vec3& p : wedge_points()) {
      if (length(c - p) < 1e-5f) found = true;
    }
    EXPECT_TRUE(found) << c.x << " " << c.y << " " << c.z;
  }
}

TEST(HullBody, ReportsItsAuthoredOriginAndTurnsAboutItsCentreOfMass) {
  World3D world;
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  const Quat turn{0.0f, det_sin(0.3f), 0.0f, det_cos(0.3f)};  // 0.6 rad about y
  BodyDef def;
  def.shape = Shape::make_hull(w);
  def.position = {1.0f, 2.0f, 3.0f};
  def.rotation = turn;
  def.density = 500.0f;
  const BodyId id = *world.create_body(def);
  const Vec3 p = world.position(id);
  EXPECT_NEAR(p.x, 1.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  EXPECT_NEAR(p.z, 3.0f, 1e-5f);
  const Quat q = world.rotation(id);
  EXPECT_NEAR(std::fabs(q.x * turn.x + q.y * turn.y + q.z * turn.z + q.w * turn.w), 1.0f, 1e-5f);
  const Vec3 com = world.center_of_mass(id);
  const Vec3 expected = Vec3{1.0f, 2.0f, 3.0f} + rotate(turn, Vec3{0.8f / 3.0f, 0.5f / 3.0f, 0.3f});
  EXPECT_NEAR(length(com - expected), 0.0f, 1e-5f);
  EXPECT_NEAR(world.mass(id), 500.0f * 0.12f, 1e-3f);
  // Spinning in free fall about its centre of mass: the centre follows the
  // parabola whatever the spin, while the authored origin circles it.
  WorldConfig c;
  c.gravity = {};
  World3D space(c);
  const GeometryId w2 = *space.geometry().add_hull(wedge_points());
  def.shape = Shape::make_hull(w2);
  def.angular_velocity = {0.0f, 3.0f, 0.0f};
  const BodyId spinning = *space.create_body(def);
  const Vec3 com0 = space.center_of_mass(spinning);
  const float arm = length(space.position(spinning) - com0);
  test::step_seconds(space, 1.0f);
  EXPECT_NEAR(length(space.center_of_mass(spinning) - com0), 0.0f, 1e-4f);
  EXPECT_NEAR(length(space.position(spinning) - com0), arm, 1e-4f);
  EXPECT_GT(length(space.position(spinning) - p), 0.1f);  // it did turn
}

TEST(HullBody, TeleportTakesTheAuthoredPose) {
  World3D world;
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  const BodyId id = add_hull_body(world, w, {0.0f, 5.0f, 0.0f});
  const Quat turn{det_sin(0.2f), 0.0f, 0.0f, det_cos(0.2f)};
  ASSERT_TRUE(world.set_transform(id, {2.0f, 3.0f, 4.0f}, turn).ok());
  EXPECT_NEAR(length(world.position(id) - Vec3{2.0f, 3.0f, 4.0f}), 0.0f, 1e-5f);
  std::vector<BodyRecord> records;
  world.dump_bodies(records);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_NEAR(length(records[0].position - Vec3{2.0f, 3.0f, 4.0f}), 0.0f, 1e-5f);
}

TEST(HullBody, AHullShapeNeedsItsGeometry) {
  World3D world;
  BodyDef def;
  def.shape = Shape::make_hull(GeometryId{0});  // nothing registered
  auto r = world.create_body(def);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.body_count(), 0u);
}

TEST(HullBody, ABoxHullRestsLikeABox) {
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  test::add_ground(world);
  const GeometryId cube = *world.geometry().add_hull(box_points({0.5f, 0.5f, 0.5f}));
  const BodyId hull = add_hull_body(world, cube, {0.0f, 0.6f, 0.0f});
  const BodyId box = test::add_box(world, {3.0f, 0.6f, 0.0f});
  test::step_seconds(world, 2.0f);
  EXPECT_NEAR(world.position(hull).y, world.position(box).y, 1e-3f);
  EXPECT_NEAR(world.position(hull).y, 0.5f, c.linear_slop_m + 1e-3f);
  EXPECT_LT(length(world.linear_velocity(hull)), 1e-3f);
  EXPECT_NEAR(world.position(hull).x, 0.0f, 1e-3f);
}

TEST(HullBody, AWedgeSettlesOnItsBase) {
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  test::add_ground(world);
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  // Dropped turned a little about x and z: it must come to rest flat on its
  // largest face (the base) or one of its other faces, never sunk in.
  const Quat tilt = normalize(Quat{0.05f, 0.0f, 0.04f, 1.0f});
  const BodyId id = add_hull_body(world, w, {0.0f, 0.5f, 0.0f}, tilt);
  test::step_seconds(world, 3.0f);
  std::vector<Vec3> corners = wedge_points();
  float lowest = 1e9f;
  for (const Vec3& corner : corners) {
    const Vec3 at = world.position(id) + rotate(world.rotation(id), corner);
    lowest = std::min(lowest, at.y);
  }
  EXPECT_NEAR(lowest, 0.0f, c.linear_slop_m + 1e-3f);
  EXPECT_LT(length(world.linear_velocity(id)), 1e-2f);
  EXPECT_LT(length(world.angular_velocity(id)), 1e-2f);
}

TEST(HullBody, HullsStackAndMeetEveryShape) {
  World3D world;
  test::add_ground(world);
  const GeometryId cube = *world.geometry().add_hull(box_points({0.4f, 0.4f, 0.4f}));
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  std::vector<BodyId> ids;
  for (int i = 0; i < 4; ++i) {
    ids.push_back(add_hull_body(world, cube, {0.0f, 0.41f + 0.81f * static_cast<float>(i), 0.0f}));
  }
  // A sphere, a capsule, a box and a wedge dropped on the column.
  test::add_sphere(world, {0.0f, 4.0f, 0.0f}, 0.3f);
  BodyDef cap;
  cap.shape = Shape::make_capsule(0.2f, 0.3f);
  cap.position = {0.1f, 5.0f, 0.0f};
  (void)*world.create_body(cap);
  test::add_box(world, {0.0f, 6.0f, 0.1f}, {0.3f, 0.2f, 0.3f});
  add_hull_body(world, w, {-0.3f, 7.0f, -0.3f});
  test::step_seconds(world, 4.0f);
  for (size_t i = 0; i < ids.size(); ++i) {
    const Vec3 p = world.position(ids[i]);
    EXPECT_LT(std::fabs(p.x) + std::fabs(p.z), 0.1f) << "hull " << i;
    EXPECT_NEAR(p.y, 0.4f + 0.8f * static_cast<float>(i), 0.03f) << "hull " << i;
  }
}

TEST(HullBody, RaysAndOverlapsFindHulls) {
  World3D world;
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_hull(w);
  def.position = {0.0f, 0.0f, 0.0f};
  const BodyId id = *world.create_body(def);
  // Straight down onto the slope at x = 0.4: the hypotenuse is at y = 0.25.
  auto hit = world.raycast({{0.4f, 5.0f, 0.3f}, {0.0f, -1.0f, 0.0f}, 10.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, id);
  EXPECT_NEAR(hit->point.y, 0.25f, 1e-5f);
  const Vec3 slope_normal = normalize_or_zero(Vec3{0.5f, 0.8f, 0.0f});
  EXPECT_NEAR(dot(hit->normal, slope_normal), 1.0f, 1e-5f);
  // Along x at y = 0.1: enters the x = 0 face.
  hit = world.raycast({{-3.0f, 0.1f, 0.3f}, {1.0f, 0.0f, 0.0f}, 10.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 3.0f, 1e-5f);
  EXPECT_NEAR(hit->normal.x, -1.0f, 1e-5f);
  // Past the slope: no hit.
  EXPECT_FALSE(world.raycast({{0.7f, 5.0f, 0.3f}, {0.0f, -1.0f, 0.0f}, 4.9f}).has_value());
  // Overlap: a small sphere under the slope overlaps; one above it does not.
  std::vector<BodyId> out;
  ASSERT_TRUE(world.overlap(Shape::make_sphere(0.05f), {0.4f, 0.2f, 0.3f}, {}, {}, out).ok());
  EXPECT_EQ(out.size(), 1u);
  ASSERT_TRUE(world.overlap(Shape::make_sphere(0.05f), {0.4f, 0.4f, 0.3f}, {}, {}, out).ok());
  EXPECT_TRUE(out.empty());
  // A hull as the query shape, placed by its authored origin.
  ASSERT_TRUE(world.overlap(Shape::make_hull(w), {0.7f, 0.0f, 0.0f}, {}, {}, out).ok());
  EXPECT_EQ(out.size(), 1u);
  ASSERT_TRUE(world.overlap(Shape::make_hull(w), {0.9f, 0.0f, 0.0f}, {}, {}, out).ok());
  EXPECT_TRUE(out.empty());
  // Signed distance to the slope from above.
  const auto d = world.signed_distance(id, Vec3{0.4f, 0.25f, 0.3f} + slope_normal * 0.2f);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->distance, 0.2f, 1e-4f);
}

// A heap of hulls and primitives, stepped, saved, serialized: every form of
// the state steps on bit for bit.
TEST(HullBody, SnapshotsCarryHullsAndNameTheirGeometry) {
  World3D world;
  test::add_ground(world);
  const GeometryId w = *world.geometry().add_hull(wedge_points());
  const GeometryId cube = *world.geometry().add_hull(box_points({0.3f, 0.3f, 0.3f}));
  for (int i = 0; i < 12; ++i) {
    const Vec3 p{0.3f * static_cast<float>(i % 3), 0.5f + 0.7f * static_cast<float>(i),
                 0.2f * static_cast<float>(i % 2)};
    if (i % 3 == 2) {
      test::add_box(world, p, {0.2f, 0.2f, 0.2f});
    } else {
      add_hull_body(world, i % 3 == 0 ? w : cube, p,
                    normalize(Quat{0.1f * static_cast<float>(i), 0.2f, 0.0f, 1.0f}));
    }
  }
  test::step_seconds(world, 1.0f);
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  for (int i = 0; i < 60; ++i) {
    world.step();
    sums.push_back(world.checksum());
  }
  // Restore.
  world.restore(saved);
  for (int i = 0; i < 60; ++i) {
    world.step();
    ASSERT_EQ(world.checksum(), sums[static_cast<size_t>(i)]) << "restore, tick " << i;
  }
  // A world sharing the store loads the bytes and steps alike.
  World3D shared({}, world.shared_geometry());
  ASSERT_TRUE(shared.deserialize(bytes).ok());
  for (int i = 0; i < 60; ++i) {
    shared.step();
    ASSERT_EQ(shared.checksum(), sums[static_cast<size_t>(i)]) << "shared store, tick " << i;
  }
  // So does one that registered the same hulls in the same order.
  World3D same;
  (void)*same.geometry().add_hull(wedge_points());
  (void)*same.geometry().add_hull(box_points({0.3f, 0.3f, 0.3f}));
  ASSERT_TRUE(same.deserialize(bytes).ok());
  same.step();
  EXPECT_EQ(same.checksum(), sums[0]);
  // A world without the hulls, or with other ones, refuses the snapshot
  // and keeps what it had.
  World3D none;
  test::add_ground(none);
  const uint64_t before = none.checksum();
  const Status s = none.deserialize(bytes);
  EXPECT_EQ(s.code(), ErrorCode::kCorrupt);
  EXPECT_EQ(none.checksum(), before);
  World3D other;
  (void)*other.geometry().add_hull(box_points({0.3f, 0.3f, 0.3f}));
  (void)*other.geometry().add_hull(wedge_points());
  EXPECT_EQ(other.deserialize(bytes).code(), ErrorCode::kCorrupt);
}

}  // namespace
}  // namespace rwd::sim
