// SPDX-License-Identifier: MIT
// The 2D character controller on small static levels: flat walking,
// walls, sliding, ledges, slopes, ground reports and repeatability.
#include <vector>

#include "rewind/sim2d/character2d.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

constexpr Fx kDt = Fx::from_raw(65536 / 60);  // one 60 Hz tick
constexpr Fx kGravity = -20_fx;

void expect_fx(Fx got, Fx want, int32_t ulps) {
  EXPECT_NEAR(got.raw(), want.raw(), ulps);
}

// The ground's top is y = 0: a wide static box.
World2D flat_world() {
  World2D world;
  add_body(world, BodyKind2D::kStatic, make_box(50_fx, 0.5_fx), {Fx(), -0.5_fx});
  return world;
}

// The capsule's centre standing on ground at height `top`.
Fx standing_y(const CharacterConfig2D& cfg, Fx top) {
  return top + cfg.radius + cfg.half_height + cfg.skin;
}

// One game tick: gravity into the velocity, walk speed sideways.
CharacterMove2D tick(const World2D& world, CharacterState2D& s, Fx walk,
                     const CharacterConfig2D& cfg) {
  s.velocity.y = s.velocity.y + kGravity * kDt;
  return move_character(world, s, {walk * kDt, s.velocity.y * kDt}, cfg);
}

CharacterState2D settled(const World2D& world, const CharacterConfig2D& cfg, Vec2 at) {
  CharacterState2D s;
  s.position = at;
  for (int i = 0; i < 60; ++i) tick(world, s, Fx(), cfg);
  return s;
}

TEST(Character2D, LandsAndWalksAlongFlatGround) {
  const World2D world = flat_world();
  const CharacterConfig2D cfg;
  CharacterState2D s = settled(world, cfg, {Fx(), 2_fx});
  EXPECT_TRUE(s.grounded);
  EXPECT_EQ(s.ground_normal, (Vec2{Fx(), 1_fx}));
  EXPECT_FALSE(s.ground.is_null());
  EXPECT_NEAR(s.position.y.raw(), standing_y(cfg, Fx()).raw(), 64);  // within the skin's 1/10
  EXPECT_EQ(s.velocity.y, Fx());                                     // gravity does not pile up
  const Fx y = s.position.y;
  for (int i = 0; i < 60; ++i) {
    const CharacterMove2D m = tick(world, s, 3_fx, cfg);
    EXPECT_FALSE(m.hit_wall);
    EXPECT_TRUE(s.grounded);
  }
  // 60 ticks of 3/60 m (each rounded to an Fx ulp).
  EXPECT_NEAR(s.position.x.raw(), (3_fx).raw(), 64);
  EXPECT_EQ(s.position.y, y);
}

TEST(Character2D, StopsAtAWallAndSlidesAlongIt) {
  World2D world = flat_world();
  add_body(world, BodyKind2D::kStatic, make_box(0.5_fx, 5_fx), {3.5_fx, 5_fx});  // face x = 3
  const CharacterConfig2D cfg;
  CharacterState2D s = settled(world, cfg, {Fx(), 1_fx});
  bool walled = false;
  for (int i = 0; i < 120; ++i) walled = tick(world, s, 3_fx, cfg).hit_wall || walled;
  EXPECT_TRUE(walled);
  const Fx stop = 3_fx - cfg.radius - cfg.skin;
  EXPECT_LE(s.position.x, stop);
  EXPECT_GE(s.position.x, stop - 0.001_fx);
  EXPECT_TRUE(s.grounded);

  // In the air, a move at 45 degrees into the wall keeps all of its
  // vertical part and none of the push into the wall.
  CharacterState2D air;
  air.position = {2_fx, 3_fx};
  const CharacterMove2D m = move_character(world, air, {1_fx, 1_fx}, cfg);
  EXPECT_TRUE(m.hit_wall);
  EXPECT_NEAR(air.position.x.raw(), stop.raw(), 64);
  EXPECT_EQ(air.position.y, 4_fx);
  EXPECT_FALSE(air.grounded);
  // And a velocity into the wall loses that part.
  air.velocity = {5_fx, 2_fx};
  move_character(world, air, {0.1_fx, Fx()}, cfg);
  EXPECT_EQ(air.velocity.x, Fx());
  EXPECT_EQ(air.velocity.y, 2_fx);
}

TEST(Character2D, SlidesDownA45DegreeSlopeSteeperThanWalkable) {
  // A 45-degree face (y = x - 4, normal (-1, 1) / sqrt 2) under a falling
  // character that walks only up to 30 degrees: it lands on the face and
  // slides down along it instead of stopping.
  World2D world;
  const Vec2 ramp[] = {{Fx(), Fx()}, {4_fx, Fx()}, {4_fx, 4_fx}};
  add_body(world, BodyKind2D::kStatic, make_polygon(ramp), {4_fx, Fx()});
  CharacterConfig2D cfg;
  cfg.half_height = Fx();  // a disc: the contact is on the face itself
  cfg.max_slope_cos = 0.866_fx;
  CharacterState2D s;
  s.position = {6_fx, 3.5_fx};
  const CharacterMove2D m = move_character(world, s, {Fx(), -2_fx}, cfg);
  EXPECT_TRUE(m.hit_wall);
  EXPECT_FALSE(s.grounded);
  // It falls 1.0607 m to the face's offset line y = x - 4 + 0.31 sqrt 2,
  // then slides the remaining 0.9393 m of fall as (-1/2, -1/2) of it.
  expect_fx(s.position.x, 5.5303_fx, 40);
  expect_fx(s.position.y, 1.9697_fx, 40);
}

TEST(Character2D, StepsUpALowLedgeButNotAHighOne) {
  const CharacterConfig2D cfg;  // step_height 0.3
  for (const Fx height : {0.25_fx, 0.45_fx}) {
    World2D world = flat_world();
    add_body(world, BodyKind2D::kStatic, make_box(5_fx, height / 2), {7_fx, height / 2});
    CharacterState2D s = settled(world, cfg, {Fx(), 1_fx});
    bool stepped = false;
    for (int i = 0; i < 90; ++i) stepped = tick(world, s, 3_fx, cfg).stepped_up || stepped;
    if (height < cfg.step_height) {
      EXPECT_TRUE(stepped);
      EXPECT_GT(s.position.x, 3_fx);
      EXPECT_NEAR(s.position.y.raw(), standing_y(cfg, height).raw(), 64);
      EXPECT_TRUE(s.grounded);
    } else {
      EXPECT_FALSE(stepped);
      EXPECT_LE(s.position.x, 2_fx - cfg.radius);
      EXPECT_NEAR(s.position.y.raw(), standing_y(cfg, Fx()).raw(), 64);
    }
  }
}

TEST(Character2D, ClimbsAGentleSlopeAndRefusesASteepOne) {
  const CharacterConfig2D cfg;  // walks up to 45 degrees
  // Ramps of 20 and 60 degrees rising from x = 2 (rise over run 0.364, 1.732).
  for (const Fx rise : {0.364_fx, 1.732_fx}) {
    World2D world = flat_world();
    const Vec2 ramp[] = {{Fx(), Fx()}, {10_fx, Fx()}, {10_fx, rise * 10}};
    add_body(world, BodyKind2D::kStatic, make_polygon(ramp), {2_fx, Fx()});
    CharacterState2D s = settled(world, cfg, {Fx(), 1_fx});
    for (int i = 0; i < 120; ++i) tick(world, s, 3_fx, cfg);
    if (rise < 1_fx) {
      // Uphill at a fraction of the walk speed, on the slope.
      EXPECT_GT(s.position.x, 4_fx);
      EXPECT_GT(s.position.y, standing_y(cfg, Fx()) + 0.5_fx);
      EXPECT_TRUE(s.grounded);
      // The slope's normal (-sin 20, cos 20).
      EXPECT_NEAR(s.ground_normal.x.raw(), (-0.342_fx).raw(), 64);
      EXPECT_NEAR(s.ground_normal.y.raw(), (0.9397_fx).raw(), 64);
    } else {
      EXPECT_LT(s.position.x, 2.2_fx);
      EXPECT_LT(s.position.y, standing_y(cfg, Fx()) + 0.4_fx);
      EXPECT_TRUE(s.grounded);
    }
  }
}

TEST(Character2D, FollowsTheGroundDownAndLeavesItWhenJumping) {
  World2D world = flat_world();
  add_body(world, BodyKind2D::kStatic, make_box(2_fx, 0.1_fx), {Fx(), 0.1_fx});  // 0.2 high
  const CharacterConfig2D cfg;
  CharacterState2D s = settled(world, cfg, {Fx(), 2_fx});
  EXPECT_NEAR(s.position.y.raw(), standing_y(cfg, 0.2_fx).raw(), 64);
  // Walking off the 0.2 m edge: the round bottom rolls over the corner
  // (briefly airborne), then it stands on the lower ground.
  int airborne = 0;
  for (int i = 0; i < 60; ++i) {
    EXPECT_FALSE(tick(world, s, 3_fx, cfg).hit_wall);
    airborne += s.grounded ? 0 : 1;
  }
  EXPECT_LE(airborne, 10);
  EXPECT_TRUE(s.grounded);
  EXPECT_NEAR(s.position.y.raw(), standing_y(cfg, Fx()).raw(), 64);
  // A jump leaves the ground.
  s.velocity.y = 5_fx;
  tick(world, s, Fx(), cfg);
  EXPECT_FALSE(s.grounded);
  EXPECT_EQ(s.ground_normal, Vec2{});
  EXPECT_TRUE(s.ground.is_null());
}

TEST(Character2D, SameInputsGiveTheSameBits) {
  World2D world = flat_world();
  add_body(world, BodyKind2D::kStatic, make_box(5_fx, 0.125_fx), {7_fx, 0.125_fx});
  const Vec2 ramp[] = {{Fx(), Fx()}, {6_fx, Fx()}, {6_fx, 2_fx}};
  add_body(world, BodyKind2D::kStatic, make_polygon(ramp), {12_fx, 0.25_fx});
  const CharacterConfig2D cfg;
  auto run = [&] {
    std::vector<CharacterState2D> trace;
    CharacterState2D s;
    s.position = {Fx(), 1_fx};
    for (int i = 0; i < 300; ++i) {
      if (i == 100) s.velocity.y = 6_fx;
      tick(world, s, i < 250 ? 4_fx : -2_fx, cfg);
      trace.push_back(s);
    }
    return trace;
  };
  const std::vector<CharacterState2D> a = run();
  const std::vector<CharacterState2D> b = run();
  EXPECT_EQ(a, b);
  // Replaying from a mid-run state (a rollback) gives the same tail.
  CharacterState2D s = a[149];
  for (int i = 150; i < 300; ++i) {
    tick(world, s, i < 250 ? 4_fx : -2_fx, cfg);
    ASSERT_EQ(s, a[static_cast<size_t>(i)]) << i;
  }
}

}  // namespace
}  // namespace rwd::sim2d
