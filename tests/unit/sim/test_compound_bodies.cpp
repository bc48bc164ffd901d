// SPDX-License-Identifier: MIT
// Compounds through the public API: mass by child volume and inertia by the
// parallel-axis theorem, a body that balances on its true centre of mass
// (and tips when held under its authored origin instead), a table of five
// boxes standing on its legs, compounds on compounds and on meshes, rays
// and shape casts, refused children, and snapshots restored bit for bit.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "d3/state_rules.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

WorldConfig awake() {
  WorldConfig c;
  c.enable_sleep = false;
  return c;
}

// A table: a 2 x 0.1 x 1 m top on four 0.1 x 0.7 x 0.1 m legs, its origin
// on the floor under the middle of the top.
GeometryId add_table(World3D& world) {
  std::vector<CompoundChild> parts;
  parts.push_back({Shape::make_box({1.0f, 0.05f, 0.5f}), {0.0f, 0.75f, 0.0f}, {}});
  for (float x : {-0.9f, 0.9f}) {
    for (float z : {-0.4f, 0.4f}) {
      parts.push_back({Shape::make_box({0.05f, 0.35f, 0.05f}), {x, 0.35f, z}, {}});
    }
  }
  auto id = world.geometry().add_compound(parts);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

BodyId add_compound_body(World3D& world, GeometryId id, Vec3 position, Quat rotation = {},
                         BodyKind kind = BodyKind::kDynamic) {
  BodyDef def;
  def.kind = kind;
  def.shape = Shape::make_compound(id);
  def.position = position;
  def.rotation = rotation;
  auto body = world.create_body(def);
  EXPECT_TRUE(body.ok()) << body.status().message();
  return *body;
}

TEST(CompoundBodies, MassAndInertiaFollowTheChildren) {
  // A dumbbell of two unit cubes 3 m apart.
  WorldConfig c;
  c.gravity = {};
  World3D world(c);
  const std::vector<CompoundChild> parts = {
      {Shape::make_box({0.5f, 0.5f, 0.5f}), {0.0f, 0.0f, 0.0f}, {}},
      {Shape::make_box({0.5f, 0.5f, 0.5f}), {3.0f, 0.0f, 0.0f}, {}}};
  const GeometryId dumbbell = *world.geometry().add_compound(parts);
  BodyDef def;
  def.shape = Shape::make_compound(dumbbell);
  def.density = 100.0f;
  def.position = {1.0f, 2.0f, 3.0f};
  const BodyId id = *world.create_body(def);
  EXPECT_NEAR(world.mass(id), 200.0f, 1e-3f);
  EXPECT_NEAR(length(world.center_of_mass(id) - Vec3{2.5f, 2.0f, 3.0f}), 0.0f, 1e-5f);
  EXPECT_NEAR(length(world.position(id) - Vec3{1.0f, 2.0f, 3.0f}), 0.0f, 1e-5f);
  // Spun about y: I_y = 2 (m/6 + m 1.5^2) with m = 100 per cube. A torque
  // of 1 N m for one tick gives dw = tau dt / I.
  ASSERT_TRUE(world.apply_torque(id, {0.0f, 1.0f, 0.0f}).ok());
  world.step();
  const float iy = 2.0f * (100.0f / 6.0f + 100.0f * 2.25f);
  EXPECT_NEAR(world.angular_velocity(id).y, c.tick_seconds / iy, 1e-3f * c.tick_seconds / iy);
  // About x only the cubes' own inertia: 2 m / 6.
  ASSERT_TRUE(world.set_angular_velocity(id, {}).ok());
  ASSERT_TRUE(world.apply_torque(id, {1.0f, 0.0f, 0.0f}).ok());
  world.step();
  EXPECT_NEAR(world.angular_velocity(id).x, c.tick_seconds / (200.0f / 6.0f),
              1e-3f * c.tick_seconds / (200.0f / 6.0f));
}

TEST(CompoundBodies, BalancesOnItsTrueCentreOfMass) {
  // A cube with a long arm: its centre of mass is 0.86 m from the cube's
  // centre along x. Set on a thin post under that point it balances; under
  // the cube's centre (the authored origin) it tips over.
  const std::vector<CompoundChild> parts = {
      {Shape::make_box({0.5f, 0.5f, 0.5f}), {0.0f, 0.0f, 0.0f}, {}},
      {Shape::make_box({1.5f, 0.1f, 0.1f}), {2.0f, 0.0f, 0.0f}, {}}};
  for (int under_origin = 0; under_origin < 2; ++under_origin) {
    World3D world(awake());
    test::add_ground(world);
    const GeometryId arm = *world.geometry().add_compound(parts);
    const float com_x = (1.0f * 0.0f + 0.12f * 2.0f) / 1.12f;
    const float post_x = under_origin == 1 ? 0.0f : com_x;
    BodyDef post;
    post.kind = BodyKind::kStatic;
    post.shape = Shape::make_box({0.05f, 1.0f, 0.05f});
    post.position = {post_x, 1.0f, 0.0f};
    (void)*world.create_body(post);
    const BodyId body =
        add_compound_body(world, arm, {post_x - (under_origin ? 0.0f : com_x), 2.5f, 0.0f});
    if (under_origin == 0) {
      EXPECT_NEAR(world.center_of_mass(body).x, post_x, 1e-5f);
    }
    test::step_seconds(world, 3.0f);
    const Quat q = world.rotation(body);
    const float tilt = std::sqrt(q.x * q.x + q.z * q.z);
    if (under_origin == 0) {
      EXPECT_LT(tilt, 0.01f) << "balanced on its centre of mass";
      EXPECT_NEAR(world.center_of_mass(body).y, 2.5f, 0.01f);
    } else {
      EXPECT_GT(tilt, 0.2f) << "held under the cube, it tips toward the arm";
    }
  }
}

TEST(CompoundBodies, ATableStandsOnItsLegsAndCarriesAnother) {
  World3D world(awake());
  test::add_ground(world);
  const GeometryId table = add_table(world);
  const BodyId lower = add_compound_body(world, table, {0.0f, 0.01f, 0.0f});
  const BodyId upper = add_compound_body(world, table, {0.1f, 0.82f, 0.0f});
  const BodyId box = test::add_box(world, {0.3f, 1.9f, 0.1f}, {0.2f, 0.2f, 0.2f});
  test::step_seconds(world, 3.0f);
  const float slop = world.config().linear_slop_m;
  EXPECT_NEAR(world.position(lower).y, 0.0f, slop + 2e-3f);
  EXPECT_NEAR(world.position(upper).y, 0.8f, 2.0f * slop + 4e-3f);
  EXPECT_NEAR(world.position(box).y, 1.8f, 3.0f * slop + 6e-3f);
  for (const BodyId id : {lower, upper}) {
    const Quat q = world.rotation(id);
    EXPECT_LT(std::fabs(q.x) + std::fabs(q.z), 0.005f);
    EXPECT_LT(length(world.linear_velocity(id)), 0.01f);
  }
  // A ray down through the middle meets the upper table's top first.
  auto hit = world.raycast({{0.1f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 10.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NE(hit->body, lower);
  // A sphere swept down between the legs of the lower table meets its top
  // from below... and one swept from above meets the box or a top.
  std::optional<ShapeCastHit> cast;
  ASSERT_TRUE(world
                  .shape_cast(Shape::make_sphere(0.1f), {-0.5f, 0.3f, 0.0f}, {}, {0.0f, 2.0f, 0.0f},
                              {}, cast)
                  .ok());
  ASSERT_TRUE(cast.has_value());
  EXPECT_EQ(cast->body, lower);
  EXPECT_NEAR(cast->distance, 0.7f - 0.1f - 0.3f, 5e-3f);
  // A table swept down beside the stack lands on its legs (its authored
  // origin is at their feet), on the ground.
  ASSERT_TRUE(world
                  .shape_cast(Shape::make_compound(table), {5.0f, 5.0f, 0.0f}, {},
                              {0.0f, -10.0f, 0.0f}, {}, cast)
                  .ok());
  ASSERT_TRUE(cast.has_value());
  EXPECT_NE(cast->body, lower);
  EXPECT_NEAR(cast->distance, 5.0f, 2e-3f);
}

// A box pressed into the corner of one static compound, a floor and a wall:
// the pair touches along two directions, and keeps a contact record for
// each (ContactRecord::part). With one manifold per pair it kept the
// deeper direction only: the box sank into the wall or the floor in turn
// and never came to rest. Events stay one per pair.
TEST(CompoundBodies, ABoxInACompoundCornerKeepsBothContacts) {
  WorldConfig config;
  config.gravity = {-4.0f, -9.81f, 0.0f};  // into the wall and the floor
  World3D world(config);
  const std::vector<CompoundChild> corner = {
      {Shape::make_box({2.0f, 0.1f, 1.0f}), {0.0f, -0.1f, 0.0f}, {}},
      {Shape::make_box({0.1f, 1.0f, 1.0f}), {-2.1f, 1.0f, 0.0f}, {}}};
  const GeometryId id = *world.geometry().add_compound(corner);
  const BodyId fixed = add_compound_body(world, id, {}, {}, BodyKind::kStatic);
  BodyDef def;
  def.shape = Shape::make_box({0.25f, 0.25f, 0.25f});
  def.position = {-1.6f, 0.5f, 0.0f};
  def.material.friction = 0.0f;  // slides into the corner
  def.event_mask = kEventAll;
  const BodyId box = *world.create_body(def);
  int enters = 0;
  int exits = 0;
  uint32_t most_manifolds = 0;
  for (int t = 0; t < 120; ++t) {
    world.step();
    most_manifolds = std::max(most_manifolds, world.stats().touching_manifolds);
    for (const ContactEvent& e : world.events()) {
      if (e.type == ContactEventType::kEnter) ++enters;
      if (e.type == ContactEventType::kExit) ++exits;
      EXPECT_TRUE((e.a == fixed && e.b == box) || (e.a == box && e.b == fixed));
    }
  }
  EXPECT_EQ(most_manifolds, 2u) << "the floor's contact and the wall's";
  EXPECT_EQ(enters, 1) << "one body pair enters once";
  EXPECT_EQ(exits, 0);
  // At rest in the corner: neither face deeper than the slop and a
  // millimetre (the wall's face is at x = -2.0, the floor's at y = 0).
  const float slop = world.config().linear_slop_m;
  const Vec3 p = world.position(box);
  EXPECT_GT(p.x - 0.25f, -2.0f - slop - 1e-3f);
  EXPECT_GT(p.y - 0.25f, -slop - 1e-3f);
  EXPECT_LT(length(world.linear_velocity(box)), 0.01f);
  test::expect_snapshots_restore(world);
}

TEST(CompoundBodies, RefusesBadChildren) {
  World3D world;
  std::vector<float> heights(4, 0.0f);
  const GeometryId field = *world.geometry().add_height_field(2, 2, {1, 1, 1}, heights);
  const std::vector<CompoundChild> surface = {{Shape::make_height_field(field), {}, {}}};
  EXPECT_EQ(world.geometry().add_compound(surface).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(world.geometry().add_compound({}).ok());
  const std::vector<CompoundChild> unknown = {{Shape::make_hull(GeometryId{42}), {}, {}}};
  EXPECT_FALSE(world.geometry().add_compound(unknown).ok());
  const std::vector<CompoundChild> far = {
      {Shape::make_sphere(0.5f), {std::nanf(""), 0.0f, 0.0f}, {}}};
  EXPECT_FALSE(world.geometry().add_compound(far).ok());
  const std::vector<CompoundChild> tiny = {{Shape::make_sphere(-1.0f), {}, {}}};
  const auto r = world.geometry().add_compound(tiny);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("child 0"), std::string::npos) << r.status().message();
  EXPECT_EQ(world.geometry().size(), 1u);  // only the height field
}

TEST(CompoundBodies, SnapshotsRestoreBitForBit) {
  World3D world;
  test::add_ground(world);
  const std::vector<Vec3> wedge = {{0, 0, 0},    {0.6f, 0, 0},    {0, 0.4f, 0},
                                   {0, 0, 0.3f}, {0.6f, 0, 0.3f}, {0, 0.4f, 0.3f}};
  const GeometryId hull = *world.geometry().add_hull(wedge);
  const std::vector<CompoundChild> parts = {
      {Shape::make_capsule(0.15f, 0.3f), {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.7071068f, 0.7071068f}},
      {Shape::make_sphere(0.2f), {0.5f, 0.1f, 0.0f}, {}},
      {Shape::make_hull(hull), {-0.6f, -0.1f, -0.15f}, {}}};
  const GeometryId toy = *world.geometry().add_compound(parts);
  for (int i = 0; i < 6; ++i) {
    add_compound_body(world, toy,
                      {0.2f * static_cast<float>(i), 0.6f + 0.7f * static_cast<float>(i), 0.0f},
                      normalize(Quat{0.1f * static_cast<float>(i), 0.3f, 0.0f, 1.0f}));
  }
  test::step_seconds(world, 0.5f);
  test::expect_snapshots_restore(world);
}

}  // namespace
}  // namespace rwd::sim

namespace rwd::sim {
namespace {

// What a snapshot may hold of a pair's parts (d3::check_contact, which
// deserialize() runs on every record): parts 0, 1, ... in a row, of one
// solid pair of bodies, below kMaxContactParts, and past 0 only with a
// compound.
TEST(CompoundBodies, SnapshotPartsAreCheckedInOrder) {
  World3D world;
  const std::vector<CompoundChild> two = {{Shape::make_box({0.5f, 0.1f, 0.5f}), {}, {}},
                                          {Shape::make_box({0.1f, 0.5f, 0.5f}), {1.0f, 0, 0}, {}}};
  const GeometryId id = *world.geometry().add_compound(two);
  BodyDef compound;
  compound.kind = BodyKind::kStatic;
  compound.shape = Shape::make_compound(id);
  ASSERT_TRUE(world.create_body(compound).ok());  // index 0
  test::add_box(world, {0.0f, 2.0f, 0.0f});       // index 1
  test::add_box(world, {3.0f, 2.0f, 0.0f});       // index 2
  const std::vector<BodyInfo>& infos = world.state().infos;
  const auto record = [&](uint32_t a, uint32_t b, uint8_t part) {
    ContactRecord r;
    r.index_a = a;
    r.index_b = b;
    r.generation_a = infos[a].generation;
    r.generation_b = infos[b].generation;
    r.part = part;
    return r;
  };
  const ContactRecord p0 = record(0, 1, 0);
  const ContactRecord p1 = record(0, 1, 1);
  EXPECT_TRUE(d3::check_contact(infos, p0, nullptr).ok());
  EXPECT_TRUE(d3::check_contact(infos, p1, &p0).ok());
  EXPECT_FALSE(d3::check_contact(infos, p1, nullptr).ok()) << "a pair starts at part 0";
  EXPECT_FALSE(d3::check_contact(infos, record(0, 1, 2), &p0).ok()) << "parts in a row";
  EXPECT_FALSE(d3::check_contact(infos, p0, &p0).ok()) << "a part twice";
  EXPECT_FALSE(d3::check_contact(infos, p0, &p1).ok()) << "parts in order";
  ContactRecord p4 = record(0, 1, 4);
  ContactRecord p3 = record(0, 1, 3);
  EXPECT_FALSE(d3::check_contact(infos, p4, &p3).ok()) << "at most kMaxContactParts";
  ContactRecord sensor = p1;
  sensor.sensor = 1;
  EXPECT_FALSE(d3::check_contact(infos, sensor, &p0).ok()) << "a sensor pair has one record";
  const ContactRecord boxes0 = record(1, 2, 0);
  EXPECT_TRUE(d3::check_contact(infos, boxes0, &p1).ok());
  EXPECT_FALSE(d3::check_contact(infos, record(1, 2, 1), &boxes0).ok()) << "no compound";
}

}  // namespace
}  // namespace rwd::sim
