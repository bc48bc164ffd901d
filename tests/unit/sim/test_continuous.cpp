// SPDX-License-Identifier: MIT
// Continuous collision (BodyDef::continuous): a 5 cm sphere at 500 m/s
// never crosses a 1 cm wall, static or dynamic (and the dynamic wall takes
// the blow), a box, a hull and a compound bullet likewise, a body sliding on the ground
// is not held back by it, the flag survives snapshots, and a restored world
// re-steps bit for bit.
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

WorldConfig no_gravity() {
  WorldConfig c;
  c.gravity = {};
  c.enable_sleep = false;
  return c;
}

// A wall 1 cm thick whose near face is the plane x = 0.
BodyId add_wall(World3D& world, BodyKind kind) {
  BodyDef wall;
  wall.kind = kind;
  wall.shape = Shape::make_box({0.005f, 2.0f, 2.0f});
  wall.position = {0.005f, 0.0f, 0.0f};
  wall.density = 2000.0f;
  auto id = world.create_body(wall);
  EXPECT_TRUE(id.ok());
  return *id;
}

BodyId add_bullet(World3D& world, Shape shape, Vec3 from, Vec3 velocity) {
  BodyDef b;
  b.shape = shape;
  b.position = from;
  b.linear_velocity = velocity;
  b.continuous = true;
  b.density = 8000.0f;
  auto id = world.create_body(b);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

TEST(Continuous, ASphereAt500MpsNeverCrossesAThinStaticWall) {
  // From several distances, so the wall falls at every point of a tick's
  // path (500 m/s covers 8.3 m a tick), head on and at an angle (37 and 74
  // m/s upward: without the flag, speculative contacts alone let a fifth of
  // these through the wall on the first tick). A ball may leave over the
  // wall's top edge (y = 2 m) after sliding up its face, never through it.
  for (int k = 0; k < 24; ++k) {
    World3D world(no_gravity());
    add_wall(world, BodyKind::kStatic);
    const float start = -1.0f - 0.21f * static_cast<float>(k);
    const Vec3 velocity{500.0f, 37.0f * static_cast<float>(k % 3), 0.0f};
    const BodyId ball =
        add_bullet(world, Shape::make_sphere(0.025f), {start, 0.1f, 0.0f}, velocity);
    ASSERT_TRUE(world.is_continuous(ball));
    for (int t = 0; t < 30; ++t) {
      world.step();
      const Vec3 p = world.position(ball);
      ASSERT_TRUE(p.x < 0.0f || p.y > 2.0f)
          << "start " << start << " tick " << t << ": " << p.x << ", " << p.y;
    }
  }
}

TEST(Continuous, ADynamicWallTakesTheBlow) {
  World3D world(no_gravity());
  const BodyId wall = add_wall(world, BodyKind::kDynamic);
  const BodyId ball =
      add_bullet(world, Shape::make_sphere(0.025f), {-3.0f, 0.0f, 0.0f}, {500.0f, 0.0f, 0.0f});
  for (int t = 0; t < 20; ++t) {
    world.step();
    ASSERT_LT(world.position(ball).x, world.position(wall).x) << "tick " << t;
  }
  // Momentum went into the wall (the ball bounced back or stopped).
  EXPECT_GT(world.linear_velocity(wall).x, 0.1f);
  EXPECT_LT(world.linear_velocity(ball).x, world.linear_velocity(wall).x + 1e-3f);
}

TEST(Continuous, BoxAndHullBulletsStopToo) {
  World3D world(no_gravity());
  add_wall(world, BodyKind::kStatic);
  const std::vector<Vec3> dart = {
      {0.0f, 0.0f, 0.0f}, {0.1f, 0.02f, 0.0f}, {0.0f, 0.04f, 0.0f}, {0.0f, 0.02f, 0.03f}};
  const GeometryId hull = *world.geometry().add_hull(dart);
  const BodyId box = add_bullet(world, Shape::make_box({0.02f, 0.02f, 0.02f}), {-4.0f, 0.5f, 0.0f},
                                {480.0f, 0.0f, 0.0f});
  const BodyId h =
      add_bullet(world, Shape::make_hull(hull), {-5.0f, -0.5f, 0.0f}, {450.0f, 0.0f, 0.0f});
  for (int t = 0; t < 30; ++t) {
    world.step();
    ASSERT_LT(world.center_of_mass(box).x, 0.0f) << "tick " << t;
    ASSERT_LT(world.center_of_mass(h).x, 0.0f) << "tick " << t;
  }
}

TEST(Continuous, ACompoundBulletStopsByItsChildren) {
  // A dart of two 3 cm balls on a thin rod, flying at 400 m/s along its
  // length at the wall from several distances, head on and at an angle:
  // its nose never crosses (it may leave over the wall's top edge).
  for (int k = 0; k < 24; ++k) {
    World3D world(no_gravity());
    add_wall(world, BodyKind::kStatic);
    const std::vector<CompoundChild> parts = {{Shape::make_sphere(0.03f), {0.15f, 0.0f, 0.0f}, {}},
                                              {Shape::make_sphere(0.03f), {-0.15f, 0.0f, 0.0f}, {}},
                                              {Shape::make_capsule(0.01f, 0.15f),
                                               {0.0f, 0.0f, 0.0f},
                                               Quat{0.0f, 0.0f, 0.70710678f, 0.70710678f}}};
    const GeometryId dart = *world.geometry().add_compound(parts);
    const float start = -1.0f - 0.27f * static_cast<float>(k);
    const Vec3 velocity{400.0f, 37.0f * static_cast<float>(k % 3), 0.0f};
    const BodyId id = add_bullet(world, Shape::make_compound(dart), {start, 0.1f, 0.0f}, velocity);
    for (int t = 0; t < 20; ++t) {
      world.step();
      // Neither ball's centre is past the wall's near face (a contact may
      // turn the dart, so each ball is placed by the dart's rotation).
      const Vec3 p = world.position(id);
      const Quat q = world.rotation(id);
      for (const float end : {-0.15f, 0.15f}) {
        const Vec3 ball = p + rotate(q, {end, 0.0f, 0.0f});
        ASSERT_TRUE(ball.x < 0.0f || ball.y > 2.0f)
            << "start " << start << " tick " << t << ": " << ball.x << ", " << ball.y;
      }
    }
  }
}

TEST(Continuous, SlidingOnTheGroundIsNotHeldBack) {
  WorldConfig c;
  c.enable_sleep = false;
  // The same box sliding fast on frictionless ground, with and without the
  // flag: the ground it touches is a contact's business, never a "hit".
  float x[2] = {};
  for (int on = 0; on < 2; ++on) {
    World3D world(c);
    test::add_ground(world, 0.0f);
    BodyDef b;
    b.shape = Shape::make_box({0.5f, 0.5f, 0.5f});
    b.position = {-40.0f, 0.5f, 0.0f};
    b.linear_velocity = {40.0f, 0.0f, 0.0f};
    b.material.friction = 0.0f;
    b.continuous = on == 1;
    const BodyId id = *world.create_body(b);
    test::step_seconds(world, 1.0f);
    x[on] = world.position(id).x;
  }
  EXPECT_NEAR(x[0], 0.0f, 0.05f);
  EXPECT_EQ(x[0], x[1]);
}

// A plank 2 m long spinning at 40 rad/s (its ends sweep 0.67 m a tick)
// about a pole of `radius` standing 0.6 m from its centre: its end must
// strike the pole, whatever the phase of the spin (24 phases across one
// tick's turn). Tunnelling is the pole passing from one side of the plank's
// long axis to the other while within its length, both seen from above (the
// axis flattened onto the ground: a plank knocked into a tumble and flung
// away, its axis steep, is not passing the pole when that axis's line swings
// across it). Per phase, whether it tunnelled within 30 ticks.
std::vector<bool> spinning_plank_tunnels(float radius, bool continuous) {
  constexpr int kLanes = 24;
  std::vector<bool> tunnelled;
  for (int lane = 0; lane < kLanes; ++lane) {
    World3D world(no_gravity());
    BodyDef pole;
    pole.kind = BodyKind::kStatic;
    pole.shape = Shape::make_capsule(radius, 1.0f);
    pole.position = {0.6f, 0.0f, 0.0f};
    EXPECT_TRUE(world.create_body(pole).ok());
    const float angle = -0.9f - 0.667f * static_cast<float>(lane) / kLanes;
    BodyDef plank;
    plank.shape = Shape::make_box({1.0f, 0.05f, 0.02f});
    plank.rotation = {0.0f, det_sin(0.5f * angle), 0.0f, det_cos(0.5f * angle)};
    plank.continuous = continuous;
    auto id = world.create_body(plank);
    EXPECT_TRUE(id.ok());
    EXPECT_TRUE(world.set_angular_velocity(*id, {0.0f, 40.0f, 0.0f}).ok());
    // The pole's offset across the flattened axis, and along it in half
    // lengths of the flattened plank (far beyond its end when it stands
    // on end).
    const auto side = [&] {
      const Vec3 axis = rotate(world.rotation(*id), {1.0f, 0.0f, 0.0f});
      const Vec3 flat{axis.x, 0.0f, axis.z};
      const float flat_sq = dot(flat, flat);
      if (flat_sq < 1e-6f) return std::pair{1.0f, 1e6f};
      const Vec3 to_pole = Vec3{0.6f, 0.0f, 0.0f} - world.position(*id);
      return std::pair{cross(flat, to_pole).y, std::fabs(dot(flat, to_pole)) / flat_sq};
    };
    auto [was, along] = side();
    bool through = false;
    for (int tick = 0; tick < 30 && !through; ++tick) {
      world.step();
      const auto [now, reach] = side();
      through = (now > 0.0f) != (was > 0.0f) && reach < 1.0f && along < 1.0f;
      was = now;
      along = reach;
    }
    tunnelled.push_back(through);
  }
  return tunnelled;
}

// Continuous collision sweeps a spinning body through its turn, not at its
// end rotation: no phase passes a pole that the body without it strikes,
// and from a pole 5 cm thick up none passes at all. (Without it, 20, 20, 9,
// 0 and 0 of the 24 phases pass poles of 2, 5, 10, 20 and 40 cm.)
TEST(Continuous, ASpinningPlankNeverPassesAPoleItWouldHitWithoutIt) {
  for (const float radius : {0.01f, 0.025f, 0.05f, 0.1f, 0.2f}) {
    SCOPED_TRACE(radius);
    const std::vector<bool> with = spinning_plank_tunnels(radius, true);
    const std::vector<bool> without = spinning_plank_tunnels(radius, false);
    int through_with = 0;
    int through_without = 0;
    for (size_t lane = 0; lane < with.size(); ++lane) {
      EXPECT_FALSE(with[lane] && !without[lane]) << "phase " << lane;
      through_with += with[lane] ? 1 : 0;
      through_without += without[lane] ? 1 : 0;
    }
    EXPECT_LE(through_with, through_without);
    if (radius >= 0.025f) {
      EXPECT_EQ(through_with, 0);
    }
  }
}

TEST(Continuous, TheFlagIsStateAndRestoresBitForBit) {
  World3D world;
  test::add_ground(world);
  add_wall(world, BodyKind::kStatic);
  std::vector<BodyId> balls;
  for (int i = 0; i < 6; ++i) {
    balls.push_back(
        add_bullet(world, Shape::make_sphere(0.025f),
                   {-2.0f - static_cast<float>(i), 0.3f + 0.2f * static_cast<float>(i), 0.0f},
                   {300.0f + 30.0f * static_cast<float>(i), 5.0f, 0.0f}));
  }
  ASSERT_TRUE(world.set_continuous(balls[5], false).ok());
  EXPECT_FALSE(world.is_continuous(balls[5]));
  EXPECT_EQ(world.set_continuous(BodyId{99, 1}, true).code(), ErrorCode::kNotFound);
  world.step();
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  for (int t = 0; t < 40; ++t) {
    world.step();
    sums.push_back(world.checksum());
  }
  world.restore(saved);
  for (int t = 0; t < 40; ++t) {
    world.step();
    ASSERT_EQ(world.checksum(), sums[static_cast<size_t>(t)]) << "tick " << t;
  }
  World3D loaded({}, world.shared_geometry());
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  EXPECT_TRUE(loaded.is_continuous(balls[0]));
  EXPECT_FALSE(loaded.is_continuous(balls[5]));
  for (int t = 0; t < 40; ++t) {
    loaded.step();
    ASSERT_EQ(loaded.checksum(), sums[static_cast<size_t>(t)]) << "loaded, tick " << t;
  }
}

}  // namespace
}  // namespace rwd::sim
