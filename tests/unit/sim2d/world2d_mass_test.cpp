// SPDX-License-Identifier: MIT
// Heavy bodies: masses and inertias past what an Fx holds are computed,
// reported and simulated; bodies beyond the lane's documented range are
// refused at creation and in snapshots; heavy scenes restore and reload
// bit for bit.
#include <cmath>
#include <string>
#include <vector>

#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using fixed::FxWide;
using testing::add_body;

double to_double(Fx f) {
  return f.raw() / 65536.0;
}
double to_double(FxWide w) {
  return static_cast<double>(w.raw()) / 4294967296.0;
}

World2DConfig sleep_off() {
  World2DConfig config;
  config.enable_sleep = false;
  return config;
}

// A static ground 2 km wide whose top is y = 0.
void add_ground(World2D& world) {
  add_body(world, BodyKind2D::kStatic, make_box(1000_fx, 10_fx), {Fx(), -10_fx});
}

Result<BodyId2D> add_box(World2D& world, Fx half_width, Fx half_height, Fx density, Vec2 position,
                         Fx angle = Fx()) {
  BodyDef2D def;
  def.shape = *make_box(half_width, half_height);
  def.density = density;
  def.position = position;
  def.angle = angle;
  return world.create_body(def);
}

// The distance of an angle from the nearest multiple of a quarter turn: a
// square lying on any face.
// The documented precision of a mass or inertia read back through its
// Q32.32 inverse: a fraction below value / 2^32 of it.
double inverse_tolerance(double value) {
  return value * value / 4294967296.0;
}

double off_flat(Fx angle) {
  const double quarter = 1.5707963267948966;
  const double a = to_double(angle);
  return std::fabs(a - quarter * std::round(a / quarter));
}

TEST(World2DMass, MassAndInertiaPastTheFxRange) {
  World2D world;
  // A plate 200 m square of density 1: 40 t and 40000 (200^2 + 200^2) / 12
  // = 2.667e8 kg m^2 (an Fx stops at 32,768).
  const BodyId2D plate = *add_box(world, 100_fx, 100_fx, 1_fx, {});
  EXPECT_NEAR(to_double(world.mass(plate)), 40000.0, inverse_tolerance(40000.0));
  // Its inverse is 16 steps of 2^-32: read back within 1% (body2d.h
  // promises 6%), and never zero.
  const double plate_inertia = 40000.0 * 80000.0 / 12.0;
  EXPECT_NEAR(to_double(world.rotational_inertia(plate)), plate_inertia, 0.01 * plate_inertia);
  // A dense body: 4 m square at 10000 kg/m^2.
  const BodyId2D dense = *add_box(world, 2_fx, 2_fx, 10000_fx, {300_fx, Fx()});
  EXPECT_NEAR(to_double(world.mass(dense)), 160000.0, inverse_tolerance(160000.0));
  EXPECT_NEAR(to_double(world.rotational_inertia(dense)), 160000.0 * 32 / 12,
              inverse_tolerance(160000.0 * 32 / 12));
  // Small bodies keep their Fx-exact values.
  const BodyId2D unit = *add_box(world, 0.5_fx, 0.5_fx, 1_fx, {-300_fx, Fx()});
  EXPECT_EQ(world.mass(unit), FxWide(1_fx));
  EXPECT_EQ(world.rotational_inertia(unit).to_fx(), Fx::ratio(1, 6));
  // Static bodies and locked rotations report zero.
  const BodyId2D wall = add_body(world, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {Fx(), 300_fx});
  EXPECT_EQ(world.mass(wall), FxWide());
  BodyDef2D locked;
  locked.shape = *make_circle(1_fx);
  locked.position = {Fx(), -300_fx};
  locked.lock_rotation = true;
  const BodyId2D disc = *world.create_body(locked);
  EXPECT_EQ(world.rotational_inertia(disc), FxWide());
  EXPECT_GT(world.mass(disc), FxWide());
}

TEST(World2DMass, RefusesBodiesBeyondTheLimitsAndChangesNothing) {
  World2D world;
  const uint64_t empty = world.checksum();
  // Exactly 2^20 kg (32 m square at 1024 kg/m^2) is the heaviest body.
  const Result<BodyId2D> heaviest = add_box(world, 16_fx, 16_fx, 1024_fx, {});
  ASSERT_TRUE(heaviest.ok()) << heaviest.status().message();
  EXPECT_EQ(world.mass(*heaviest), kMaxBodyMass2D);
  ASSERT_TRUE(world.destroy_body(*heaviest).ok());
  World2D fresh;
  // One density step more, and a 1,200 t plate, are refused by mass.
  for (const Result<BodyId2D>& r : {add_box(fresh, 16_fx, 16_fx, 1024_fx + Fx::epsilon(), {}),
                                    add_box(fresh, 100_fx, 100_fx, 30_fx, {})}) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("mass"), std::string::npos) << r.status().message();
  }
  // A 300 m plate of density 1 weighs 90 t but has 1.35e9 kg m^2: refused
  // by its inertia, accepted when it never turns.
  const Result<BodyId2D> wide = add_box(fresh, 150_fx, 150_fx, 1_fx, {});
  ASSERT_FALSE(wide.ok());
  EXPECT_NE(wide.status().message().find("inertia"), std::string::npos);
  BodyDef2D def;
  def.shape = *make_box(150_fx, 150_fx);
  def.lock_rotation = true;
  EXPECT_TRUE(World2D().create_body(def).ok());
  // A disc of density 1 and 4 mm radius has an inertia (4e-10 kg m^2) whose
  // inverse does not fit; locked, its mass (5e-5 kg) is fine.
  def.shape = *make_circle(0.004_fx);
  def.lock_rotation = false;
  const Result<BodyId2D> tiny = fresh.create_body(def);
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.status().message().find("inertia"), std::string::npos);
  def.lock_rotation = true;
  EXPECT_TRUE(World2D().create_body(def).ok());
  EXPECT_EQ(fresh.body_count(), 0u);
  EXPECT_EQ(fresh.checksum(), empty);
  // Static and kinematic bodies have no mass to limit.
  add_body(fresh, BodyKind2D::kStatic, make_box(150_fx, 150_fx), {});
  EXPECT_EQ(fresh.body_count(), 1u);
}

TEST(World2DMass, ASnapshotWithABodyBeyondTheLimitsIsRefused) {
  World2D world;
  const BodyId2D box = *add_box(world, 1_fx, 1_fx, 1_fx, {});
  World2DState state;
  world.save(state);
  std::vector<uint8_t> bytes;
  World2D target;
  for (int field = 0; field < 3; ++field) {
    World2DState bad = state;
    BodyRecord2D& body = bad.bodies[box.index];
    if (field == 0) body.inv_mass = 1;      // 2^32 kg
    if (field == 1) body.inv_inertia = 0;   // a turning body with infinite inertia
    if (field == 2) body.inv_inertia = 15;  // just past kMaxBodyInertia2D
    world.restore(bad);
    world.serialize(bytes);
    EXPECT_EQ(target.deserialize(bytes).code(), ErrorCode::kCorrupt) << field;
  }
  world.restore(state);
  world.serialize(bytes);
  EXPECT_TRUE(target.deserialize(bytes).ok());
}

// Without the inertia a 200 m plate used to get (the sum overflowed, and
// the body was left unable to turn) it landed on a corner and stayed
// tilted; a 4 m, 40 t box lands and tips flat too.
TEST(World2DMass, HeavyBoxesLandAndTipFlat) {
  struct Case {
    Fx half;
    Fx density;
  };
  for (const Case c : {Case{100_fx, 1_fx}, Case{2_fx, 2500_fx}}) {
    World2D world(sleep_off());
    add_ground(world);
    // Dropped turned 0.3 rad, its lowest corner 1 m up.
    const BodyId2D box =
        *add_box(world, c.half, c.half, c.density, {Fx(), c.half * 2 + 1_fx}, 0.3_fx);
    EXPECT_NEAR(to_double(world.mass(box)), 40000.0, inverse_tolerance(40000.0));
    for (int t = 0; t < 600; ++t) world.step();
    SCOPED_TRACE(to_double(c.half));
    EXPECT_LT(off_flat(world.angle(box)), 0.001);
    EXPECT_NEAR(to_double(world.center_of_mass(box).y), to_double(c.half), 0.01);
    EXPECT_LT(std::fabs(to_double(world.linear_velocity(box).y)), 0.01);
    EXPECT_LT(std::fabs(to_double(world.angular_velocity(box))), 0.01);
  }
}

// Friction stops a sliding box after v^2 / (2 mu g) = 25 / 12 m whatever
// its mass: a 40 t box slides as far as a 1 kg one.
TEST(World2DMass, AHeavyBoxSlidesItsStopDistance) {
  double stops[2] = {};
  const Fx densities[2] = {1_fx, 2500_fx};
  const Fx halves[2] = {0.5_fx, 2_fx};
  for (int i = 0; i < 2; ++i) {
    World2D world(sleep_off());
    add_ground(world);
    BodyDef2D def;
    def.shape = *make_box(halves[i], halves[i]);
    def.density = densities[i];
    def.position = {Fx(), halves[i]};
    def.linear_velocity = {5_fx, Fx()};
    const BodyId2D box = *world.create_body(def);
    for (int t = 0; t < 120; ++t) world.step();
    EXPECT_EQ(world.linear_velocity(box).x, Fx());
    stops[i] = to_double(world.position(box).x);
  }
  EXPECT_NEAR(stops[1], 25.0 / 12.0, 0.03);
  EXPECT_NEAR(stops[1], stops[0], 0.001);
}

// A 1 kg box on a 40 t box, and a 40 t box on a 4 t box, stand for 10 s.
TEST(World2DMass, HeavyAndLightStacksStand) {
  {
    World2D world(sleep_off());
    add_ground(world);
    const BodyId2D heavy = *add_box(world, 2_fx, 2_fx, 2500_fx, {Fx(), 2_fx});
    const BodyId2D light = *add_box(world, 0.5_fx, 0.5_fx, 1_fx, {Fx(), 4.5_fx});
    for (int t = 0; t < 600; ++t) world.step();
    EXPECT_NEAR(to_double(world.center_of_mass(heavy).y), 2.0, 0.005);
    EXPECT_NEAR(to_double(world.center_of_mass(light).y), 4.5, 0.005);
    EXPECT_LT(std::fabs(to_double(world.center_of_mass(light).x)), 0.001);
    EXPECT_LT(off_flat(world.angle(light)), 0.001);
  }
  {
    World2D world(sleep_off());
    add_ground(world);
    const BodyId2D light = *add_box(world, 1_fx, 1_fx, 1000_fx, {Fx(), 1_fx});
    const BodyId2D heavy = *add_box(world, 1_fx, 1_fx, 10000_fx, {Fx(), 3_fx});
    EXPECT_NEAR(to_double(world.mass(heavy)), 40000.0, inverse_tolerance(40000.0));
    for (int t = 0; t < 600; ++t) world.step();
    EXPECT_NEAR(to_double(world.center_of_mass(light).y), 1.0, 0.01);
    EXPECT_NEAR(to_double(world.center_of_mass(heavy).y), 3.0, 0.02);
    EXPECT_LT(std::fabs(to_double(world.center_of_mass(heavy).x)), 0.001);
    EXPECT_LT(off_flat(world.angle(heavy)), 0.001);
  }
}

// A 40 t box at 10 m/s pushes a 0.8 kg ball ahead of it in free space:
// the momentum before is the momentum after.
TEST(World2DMass, AHeavyHitKeepsMomentum) {
  World2DConfig config = sleep_off();
  config.gravity = {};
  World2D world(config);
  BodyDef2D heavy;
  heavy.shape = *make_box(1_fx, 1_fx);
  heavy.density = 10000_fx;
  heavy.linear_velocity = {10_fx, Fx()};
  const BodyId2D box = *world.create_body(heavy);
  BodyDef2D light;
  light.shape = *make_circle(0.5_fx);
  light.position = {3_fx, Fx()};
  const BodyId2D ball = *world.create_body(light);
  const double before = to_double(world.mass(box)) * 10.0;
  for (int t = 0; t < 60; ++t) world.step();
  const double after = to_double(world.mass(box)) * to_double(world.linear_velocity(box).x) +
                       to_double(world.mass(ball)) * to_double(world.linear_velocity(ball).x);
  EXPECT_NEAR(after, before, before * 1e-5);
  EXPECT_GE(world.linear_velocity(ball).x, world.linear_velocity(box).x);
}

TEST(World2DMass, HeavyScenesRestoreAndReloadBitForBit) {
  World2D world;
  add_ground(world);
  const BodyId2D plate = *add_box(world, 100_fx, 100_fx, 1_fx, {Fx(), 230_fx}, 0.3_fx);
  ASSERT_TRUE(add_box(world, 2_fx, 2_fx, 2500_fx, {-150_fx, 3_fx}, 0.2_fx).ok());
  ASSERT_TRUE(add_box(world, 0.5_fx, 0.5_fx, 1_fx, {-150_fx, 8_fx}).ok());
  for (int t = 0; t < 60; ++t) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> expected;
  for (int t = 0; t < 120; ++t) {
    world.step();
    expected.push_back(world.checksum());
  }
  world.restore(saved);
  World2D copy;
  ASSERT_TRUE(copy.deserialize(bytes).ok());
  EXPECT_EQ(copy.mass(plate), world.mass(plate));
  EXPECT_EQ(copy.rotational_inertia(plate), world.rotational_inertia(plate));
  for (size_t t = 0; t < expected.size(); ++t) {
    world.step();
    copy.step();
    ASSERT_EQ(world.checksum(), expected[t]) << t;
    ASSERT_EQ(copy.checksum(), expected[t]) << t;
  }
}

}  // namespace
}  // namespace rwd::sim2d
