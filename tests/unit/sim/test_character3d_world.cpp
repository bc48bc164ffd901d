// SPDX-License-Identifier: MIT
// The 3D character controller among other bodies and over time: ground
// bodies that move, its own body, repeatability across a restored world,
// bad inputs, and a long walk that must never end inside geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "character3d_levels.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using namespace character_test;  // NOLINT: test brevity

TEST(Character3D, ReportsTheGroundBodyOnAMovingPlatformAndADynamicBox) {
  World3D world;
  test::add_ground(world);
  // A kinematic platform 1 m up moving along x at 1 m/s and up at 0.5 m/s.
  const BodyId platform =
      add_body(world, BodyKind::kKinematic, {0.0f, 0.75f, 0.0f}, {2.0f, 0.25f, 2.0f});
  const Vec3 platform_v{1.0f, 0.5f, 0.0f};
  ASSERT_TRUE(world.set_linear_velocity(platform, platform_v).ok());
  const BodyId box = test::add_box(world, {6.0f, 0.5f, 0.0f});
  const CharacterConfig3D cfg;
  CharacterState3D rider;
  rider.position = {0.0f, 2.5f, 0.0f};
  CharacterState3D sitter;
  sitter.position = {6.0f, 3.0f, 0.0f};
  int on_platform = 0;
  float offset_x = 0.0f;  // the rider's x on the platform once it stands there
  for (int i = 0; i < 90; ++i) {
    world.step();
    // The game carries the rider with the ground it stands on.
    const Vec3 carry = rider.grounded ? world.linear_velocity(rider.ground) * kDt : Vec3{};
    rider.velocity.y += kGravity * kDt;
    move_character(world, rider, rider.velocity * kDt + carry, cfg);
    tick(world, sitter, {}, cfg);
    if (i >= 30) {
      EXPECT_TRUE(rider.grounded) << i;
      EXPECT_EQ(rider.ground, platform) << i;
      EXPECT_EQ(sitter.ground, box) << i;
      on_platform += rider.ground == platform ? 1 : 0;
    }
    if (i == 30) offset_x = rider.position.x - world.position(platform).x;
  }
  EXPECT_EQ(on_platform, 60);
  // On the platform's top, a skin above it.
  const float platform_top = world.position(platform).y + 0.25f;
  EXPECT_NEAR(rider.position.y, standing_y(cfg, platform_top), 2e-3f);
  // Carried along: it keeps its place on the platform over the last second.
  EXPECT_NEAR(rider.position.x - world.position(platform).x, offset_x, 1e-3f);
  EXPECT_NEAR(sitter.position.y, standing_y(cfg, world.position(box).y + 0.5f), 2e-3f);
}

TEST(Character3D, IgnoresItsOwnKinematicBody) {
  const CharacterConfig3D cfg;
  std::vector<Vec3> paths[2];
  for (const bool with_body : {false, true}) {
    World3D world;
    test::add_ground(world);
    add_static(world, {3.5f, 2.0f, 0.0f}, {0.5f, 2.0f, 10.0f});
    QueryFilter filter;
    BodyId own;
    if (with_body) {
      BodyDef def;
      def.kind = BodyKind::kKinematic;
      def.shape = Shape::make_capsule(cfg.radius, cfg.half_height);
      def.position = {0.0f, 2.0f, 0.0f};
      own = *world.create_body(def);
      filter.ignore = own;
    }
    CharacterState3D s;
    s.position = {0.0f, 2.0f, 0.0f};
    for (int i = 0; i < 150; ++i) {
      tick(world, s, {kWalk, 0.0f, 1.0f}, cfg, filter);
      if (with_body) {
        ASSERT_TRUE(world.set_transform(own, s.position, Quat{}).ok());
        world.step();
      }
      paths[with_body ? 1 : 0].push_back(s.position);
    }
    EXPECT_TRUE(s.grounded);
    EXPECT_FALSE(s.ground == own);
  }
  // Its own capsule, always where it stands, changes nothing.
  ASSERT_EQ(paths[0].size(), paths[1].size());
  for (size_t i = 0; i < paths[0].size(); ++i) {
    EXPECT_TRUE(same_bits(paths[0][i], paths[1][i])) << "tick " << i;
  }
  EXPECT_GT(paths[1].back().x, 2.6f);
  EXPECT_GT(paths[1].back().z, 2.0f);
}

// A level of boxes: a walled yard with ledges, ramps, pillars, a low
// roof and loose crates.
void build_level(World3D& world) {
  test::add_ground(world);
  add_static(world, {0.0f, 2.0f, 12.5f}, {13.0f, 2.0f, 0.5f});
  add_static(world, {0.0f, 2.0f, -12.5f}, {13.0f, 2.0f, 0.5f});
  add_static(world, {12.5f, 2.0f, 0.0f}, {0.5f, 2.0f, 13.0f});
  add_static(world, {-12.5f, 2.0f, 0.0f}, {0.5f, 2.0f, 13.0f});
  add_static(world, {4.0f, 0.1f, 4.0f}, {2.0f, 0.1f, 2.0f});     // 0.2 m ledge
  add_static(world, {4.5f, 0.3f, 4.5f}, {1.0f, 0.1f, 1.0f});     // and one more on it
  add_static(world, {-5.0f, 0.25f, 3.0f}, {1.5f, 0.25f, 3.0f});  // 0.5 m block
  add_ramp(world, -2.0f, 25.0f, 5.0f);
  add_ramp(world, 6.0f, 60.0f, 3.0f);
  add_static(world, {-4.0f, 2.6f, -6.0f}, {3.0f, 0.3f, 3.0f});  // a low roof
  for (int i = 0; i < 6; ++i) {
    const float a = 0.7f * static_cast<float>(i);
    add_static(world, {-8.0f + 3.0f * static_cast<float>(i), 1.5f, -3.0f + det_sin(a) * 4.0f},
               {0.4f, 1.5f, 0.4f}, about_y(a));
  }
  for (int i = 0; i < 4; ++i) {
    test::add_box(world, {2.0f * static_cast<float>(i) - 3.0f, 0.5f, 8.0f});
  }
}

// A walker with scripted turns and jumps.
struct Walker {
  test::Rng rng;
  Vec3 walk;
  void input(int t, CharacterState3D& s) {
    if (t % 40 == 0) {
      const float a = rng.uniform(-kPi, kPi);
      walk = Vec3{det_cos(a), 0.0f, det_sin(a)} * rng.uniform(1.0f, 5.0f);
    }
    if (t % 97 == 50 && s.grounded) s.velocity.y = 6.0f;
  }
};

TEST(Character3D, SameMovesBitForBitAfterTheWorldIsRestored) {
  World3D world;
  build_level(world);
  const CharacterConfig3D cfg;
  CharacterState3D s;
  s.position = {8.0f, 1.5f, 8.0f};
  Walker walker{{7}, {}};
  for (int t = 0; t < 60; ++t) {
    world.step();
    walker.input(t, s);
    tick(world, s, walker.walk, cfg);
  }
  WorldState saved;
  world.save(saved);
  const CharacterState3D saved_state = s;
  const Walker saved_walker = walker;
  std::vector<CharacterState3D> states;
  std::vector<CharacterMove3D> moves;
  for (int t = 60; t < 300; ++t) {
    world.step();
    walker.input(t, s);
    moves.push_back(tick(world, s, walker.walk, cfg));
    states.push_back(s);
  }
  world.restore(saved);
  s = saved_state;
  walker = saved_walker;
  for (int t = 60; t < 300; ++t) {
    world.step();
    walker.input(t, s);
    const CharacterMove3D m = tick(world, s, walker.walk, cfg);
    const size_t k = static_cast<size_t>(t - 60);
    ASSERT_TRUE(same_bits(s.position, states[k].position)) << "tick " << t;
    ASSERT_TRUE(same_bits(s.velocity, states[k].velocity)) << "tick " << t;
    ASSERT_TRUE(same_bits(s.ground_normal, states[k].ground_normal)) << "tick " << t;
    ASSERT_TRUE(same_bits(m.translation, moves[k].translation)) << "tick " << t;
    ASSERT_EQ(s.grounded, states[k].grounded) << "tick " << t;
    ASSERT_EQ(s.ground, states[k].ground) << "tick " << t;
    ASSERT_EQ(m.hit_wall, moves[k].hit_wall) << "tick " << t;
    ASSERT_EQ(m.stepped_up, moves[k].stepped_up) << "tick " << t;
  }
}

TEST(Character3D, NonFiniteInputsGiveAFiniteState) {
  World3D world;
  test::add_ground(world);
  const CharacterConfig3D cfg;
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const CharacterState3D start = settled(world, cfg, {0.0f, 1.0f, 0.0f});
  for (const Vec3 desired : {Vec3{nan, 0.0f, 0.0f}, Vec3{0.0f, -inf, 0.0f}, Vec3{inf, inf, -inf},
                             Vec3{1e30f, -1e30f, 1e30f}}) {
    CharacterState3D s = start;
    move_character(world, s, desired, cfg);
    EXPECT_TRUE(is_finite(s.position));
    EXPECT_TRUE(is_finite(s.velocity));
    EXPECT_TRUE(is_finite(s.ground_normal));
    if (!is_finite(desired)) {
      EXPECT_TRUE(same_bits(s.position, start.position));
    }
    EXPECT_FALSE(inside_geometry(world, cfg, s.position, 1e-3f));
  }
  // A non-finite velocity becomes zero; a bad config is clamped.
  CharacterState3D s = start;
  s.velocity = {nan, 1.0f, 0.0f};
  CharacterConfig3D bad;
  bad.radius = nan;
  bad.half_height = -1.0f;
  bad.skin = inf;
  bad.max_slope_cos = 7.0f;
  bad.step_height = -inf;
  bad.max_slides = 1000;
  bad.up = {0.0f, 0.0f, 0.0f};
  move_character(world, s, {0.1f, -0.1f, 0.0f}, bad);
  EXPECT_TRUE(is_finite(s.position));
  EXPECT_TRUE(is_finite(s.velocity));
  EXPECT_EQ(s.velocity.x, 0.0f);
}

TEST(Character3D, WalksABoxLevelFor600TicksAndNeverEndsInsideGeometry) {
  const CharacterConfig3D cfg;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    World3D world;
    build_level(world);
    CharacterState3D s;
    s.position = {8.0f, 1.5f, 8.0f};
    Walker walker{{seed}, {}};
    float path = 0.0f;
    int grounded = 0;
    int walls = 0;
    int ceilings = 0;
    int stepped = 0;
    int close = 0;
    for (int t = 0; t < 600; ++t) {
      world.step();
      walker.input(t, s);
      const CharacterMove3D m = tick(world, s, walker.walk, cfg);
      path += length(m.translation);
      grounded += s.grounded ? 1 : 0;
      walls += m.hit_wall ? 1 : 0;
      ceilings += m.hit_ceiling ? 1 : 0;
      stepped += m.stepped_up ? 1 : 0;
      ASSERT_TRUE(is_finite(s.position)) << "seed " << seed << " tick " << t;
      ASSERT_FALSE(inside_geometry(world, cfg, s.position, 1e-3f))
          << "seed " << seed << " tick " << t;
      // Closer than half the skin to a surface (informative).
      close += inside_geometry(world, cfg, s.position, -0.5f * cfg.skin) ? 1 : 0;
    }
    EXPECT_GT(path, 15.0f) << "seed " << seed;
    EXPECT_GT(grounded, 300) << "seed " << seed;
    std::printf(
        "[ measured ] seed %d: path %.2f m, grounded %d, walls %d, ceilings %d, "
        "step-ups %d, closer than half a skin %d (of 600 ticks)\n",
        static_cast<int>(seed), path, grounded, walls, ceilings, stepped, close);
  }
}

}  // namespace
}  // namespace rwd::sim
