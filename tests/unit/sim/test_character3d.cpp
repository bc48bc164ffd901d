// SPDX-License-Identifier: MIT
// The 3D character controller's moves on small box-built levels: flat
// walking, walls and sliding, creases, ramps, ledges, snapping down and
// ceilings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "character3d_levels.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using namespace character_test;  // NOLINT: test brevity

TEST(Character3D, LandsAndWalksAlongFlatGround) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const CharacterConfig3D cfg;
  CharacterState3D s = settled(world, cfg, {0.0f, 2.0f, 0.0f});
  EXPECT_TRUE(s.grounded);
  EXPECT_EQ(s.ground, ground);
  EXPECT_NEAR(s.ground_normal.y, 1.0f, 1e-5f);
  EXPECT_NEAR(s.position.y, standing_y(cfg, 0.0f), 1e-3f);  // within a tenth of the skin
  EXPECT_EQ(s.velocity.y, 0.0f);                            // gravity does not pile up
  const float y = s.position.y;
  // Diagonally, 3 m/s along (2, 0, -1) / sqrt 5, for a second.
  const Vec3 walk = Vec3{2.0f, 0.0f, -1.0f} * (kWalk / std::sqrt(5.0f));
  for (int i = 0; i < 60; ++i) {
    const CharacterMove3D m = tick(world, s, walk, cfg);
    EXPECT_FALSE(m.hit_wall);
    EXPECT_FALSE(m.stepped_up);
    EXPECT_TRUE(s.grounded);
  }
  EXPECT_NEAR(s.position.x, walk.x, 1e-4f);
  EXPECT_NEAR(s.position.z, walk.z, 1e-4f);
  EXPECT_NEAR(s.position.y, y, 1e-5f);
}

TEST(Character3D, StopsAtAWallAndSlidesAlongIt) {
  World3D world;
  test::add_ground(world);
  add_static(world, {3.5f, 5.0f, 0.0f}, {0.5f, 5.0f, 20.0f});  // face x = 3
  const CharacterConfig3D cfg;
  CharacterState3D s = settled(world, cfg, {0.0f, 1.0f, 0.0f});
  bool walled = false;
  for (int i = 0; i < 90; ++i) walled = tick(world, s, {kWalk, 0.0f, 0.0f}, cfg).hit_wall || walled;
  EXPECT_TRUE(walled);
  const float stop = 3.0f - cfg.radius - cfg.skin;
  EXPECT_LE(s.position.x, stop + 1e-4f);
  EXPECT_GE(s.position.x, stop - 1e-3f);
  EXPECT_TRUE(s.grounded);
  EXPECT_NEAR(s.velocity.x, 0.0f, 1e-5f);  // the push into the wall is gone

  // At 60 degrees to the wall's normal: the part along the wall (z) goes
  // on at full speed, the part into it stops.
  const Vec3 walk{kWalk * 0.5f, 0.0f, kWalk * 0.8660254f};
  const float z0 = s.position.z;
  for (int i = 0; i < 60; ++i) {
    EXPECT_TRUE(tick(world, s, walk, cfg).hit_wall);
    EXPECT_LE(s.position.x, stop + 1e-4f);
    EXPECT_GE(s.position.x, stop - 1e-3f);
  }
  const float along_mps = s.position.z - z0;  // over one second
  EXPECT_NEAR(along_mps, walk.z, 0.01f * walk.z);
  EXPECT_NEAR(s.velocity.z, walk.z, 1e-5f);
  EXPECT_NEAR(s.velocity.x, 0.0f, 1e-5f);

  // In the air, a move up and into the wall keeps all of its rise.
  CharacterState3D air;
  air.position = {2.0f, 3.0f, 0.0f};
  const CharacterMove3D m = move_character(world, air, {1.0f, 1.0f, 0.0f}, cfg);
  EXPECT_TRUE(m.hit_wall);
  EXPECT_NEAR(air.position.x, stop, 1e-3f);
  EXPECT_NEAR(air.position.y, 4.0f, 1e-5f);
  EXPECT_FALSE(air.grounded);
}

TEST(Character3D, CornersAndCreasesNeitherTunnelNorJitter) {
  const CharacterConfig3D cfg;
  // A square corner (faces x = 3 and z = 3), and a 60 degree wedge whose
  // crease line is the vertical through (3, 0, 0).
  for (const bool wedge : {false, true}) {
    World3D world;
    test::add_ground(world);
    Vec3 walk;
    if (!wedge) {
      add_static(world, {3.5f, 2.0f, 0.0f}, {0.5f, 2.0f, 10.0f});
      add_static(world, {0.0f, 2.0f, 3.5f}, {10.0f, 2.0f, 0.5f});
      walk = Vec3{1.0f, 0.0f, 1.2f} * kWalk;
    } else {
      // Faces running from the crease toward -x at +-30 degrees to it.
      for (const float side : {1.0f, -1.0f}) {
        const Vec3 along{-0.8660254f, 0.0f, 0.5f * side};    // the face, away from the crease
        const Vec3 inward{-0.5f, 0.0f, -0.8660254f * side};  // its normal, into the wedge
        add_static(world, Vec3{3.0f, 2.0f, 0.0f} + along * 5.0f - inward * 0.5f, {5.0f, 2.0f, 0.5f},
                   about_y(-side * 5.0f * kPi / 6.0f));
      }
      walk = Vec3{1.0f, 0.0f, 0.1f} * kWalk;
    }
    CharacterState3D s = settled(world, cfg, {0.0f, 1.0f, 0.0f});
    std::vector<Vec3> trail;
    for (int i = 0; i < 150; ++i) {
      tick(world, s, walk, cfg);
      ASSERT_FALSE(inside_geometry(world, cfg, s.position, 1e-3f)) << "tick " << i;
      trail.push_back(s.position);
    }
    // Wedged in: the last 30 ticks do not move it by more than 10 microns.
    for (size_t i = trail.size() - 30; i < trail.size(); ++i) {
      EXPECT_LT(length(trail[i] - trail.back()), 1e-5f) << "wedge " << wedge;
    }
    EXPECT_TRUE(s.grounded);
    if (!wedge) {
      EXPECT_NEAR(s.position.x, 3.0f - cfg.radius - cfg.skin, 1e-3f);
      EXPECT_NEAR(s.position.z, 3.0f - cfg.radius - cfg.skin, 1e-3f);
    } else {
      // The capsule's axis sits on the crease's bisector, a skin off both faces.
      EXPECT_NEAR(s.position.z, 0.0f, 2e-3f);
      EXPECT_NEAR(s.position.x, 3.0f - (cfg.radius + cfg.skin) / 0.5f, 5e-3f);
    }
  }
}

// Walking up a 30 degree ramp into a wall that crosses it at an angle:
// the ramp's and the wall's normals are not perpendicular, so sliding
// along one pushes into the other; the move follows their crease line
// uphill at the speed of the walk's part along that line.
TEST(Character3D, SlidesUpTheCreaseOfARampAndAWallAcrossIt) {
  World3D world;
  test::add_ground(world);
  add_ramp(world, 0.0f, 30.0f, 20.0f);
  const Vec3 wall_normal{0.5f, 0.0f, -0.8660254f};
  add_static(world, Vec3{4.0f, 3.0f, 1.0f} - wall_normal * 0.5f, {6.0f, 5.0f, 0.5f},
             about_y(5.0f * kPi / 6.0f));
  CharacterConfig3D cfg;
  // The slide alone: with stepping on, the blocked character also tries a
  // step, which here lands on the same ramp further up and carries it
  // along the crease about 25% faster than the slide (a known limit).
  cfg.step_height = 0.0f;
  CharacterState3D s = settled(world, cfg, {3.0f, 3.5f, -2.0f});
  ASSERT_TRUE(s.grounded);
  const Vec3 walk = Vec3{0.2f, 0.0f, 1.0f} * (kWalk / std::sqrt(1.04f));
  int t = 0;
  while (t < 120 && !tick(world, s, walk, cfg).hit_wall) ++t;
  ASSERT_LT(t, 120);
  const Vec3 from = s.position;
  for (int i = 0; i < 30; ++i) {
    tick(world, s, walk, cfg);
    ASSERT_FALSE(inside_geometry(world, cfg, s.position, 1e-3f)) << "tick " << i;
    EXPECT_TRUE(s.grounded) << "tick " << i;
  }
  const Vec3 ramp_normal{-0.5f, 0.8660254f, 0.0f};
  Vec3 line = normalize_or_zero(cross(ramp_normal, wall_normal));
  if (line.y < 0.0f) line = -line;  // uphill
  const Vec3 moved = s.position - from;
  EXPECT_GT(dot(moved, line), 0.999f * length(moved));
  const float expected = 30.0f * kDt * dot(walk, line);  // m in half a second
  EXPECT_NEAR(length(moved), expected, 0.02f * expected);
  std::printf("[ measured ] along the crease %.4f m in 30 ticks (expected %.4f m)\n", length(moved),
              expected);
}

TEST(Character3D, ClimbsA30DegreeRampAndRefusesA60DegreeOne) {
  const CharacterConfig3D cfg;  // walks up to 45 degrees
  for (const float degrees : {30.0f, 60.0f}) {
    World3D world;
    test::add_ground(world);
    const BodyId ramp = add_ramp(world, 2.0f, degrees, 12.0f);
    CharacterState3D s = settled(world, cfg, {0.0f, 1.0f, 0.0f});
    const float y0 = s.position.y;
    float highest = y0;
    bool walled = false;
    for (int i = 0; i < 120; ++i) {
      walled = tick(world, s, {kWalk, 0.0f, 0.0f}, cfg).hit_wall || walled;
      highest = std::fmax(highest, s.position.y);
    }
    if (degrees < 45.0f) {
      // Up the slope: the capsule's bottom sphere rides it, so its centre is
      // a radius plus a skin off the face: y = (x - 2) tan 30 + 0.31 / cos 30
      // + half height.
      EXPECT_GT(s.position.x, 4.0f);
      EXPECT_TRUE(s.grounded);
      EXPECT_EQ(s.ground, ramp);
      EXPECT_NEAR(s.ground_normal.x, -0.5f, 1e-3f);
      EXPECT_NEAR(s.ground_normal.y, 0.8660254f, 1e-3f);
      const float on_face =
          (s.position.x - 2.0f) * 0.57735f + (cfg.radius + cfg.skin) / 0.8660254f + cfg.half_height;
      EXPECT_NEAR(s.position.y, on_face, 2e-3f);
      EXPECT_GT(s.position.y, y0 + 1.0f);
    } else {
      EXPECT_TRUE(walled);
      EXPECT_LT(s.position.x, 2.0f);
      EXPECT_LT(highest, y0 + 1e-3f);  // never lifted
      EXPECT_TRUE(s.grounded);
      EXPECT_FALSE(s.ground == ramp);
    }
  }
}

TEST(Character3D, StepsUpALowLedgeButNotAHighOne) {
  const CharacterConfig3D cfg;  // step_height 0.3
  for (const float height : {0.25f, 0.4f}) {
    World3D world;
    test::add_ground(world);
    add_static(world, {7.0f, height * 0.5f, 0.0f}, {5.0f, height * 0.5f, 5.0f});  // from x = 2
    CharacterState3D s = settled(world, cfg, {0.0f, 1.0f, 0.0f});
    bool stepped = false;
    float highest = s.position.y;
    for (int i = 0; i < 90; ++i) {
      stepped = tick(world, s, {kWalk, 0.0f, 0.0f}, cfg).stepped_up || stepped;
      highest = std::fmax(highest, s.position.y);
    }
    if (height < cfg.step_height) {
      EXPECT_TRUE(stepped);
      EXPECT_GT(s.position.x, 3.5f);
      EXPECT_NEAR(s.position.y, standing_y(cfg, height), 1e-3f);
      EXPECT_TRUE(s.grounded);
    } else {
      EXPECT_FALSE(stepped);
      EXPECT_LE(s.position.x, 2.0f - cfg.radius);
      EXPECT_NEAR(s.position.y, standing_y(cfg, 0.0f), 1e-3f);
      EXPECT_LT(highest, standing_y(cfg, 0.0f) + 1e-3f);
    }
  }
}

TEST(Character3D, SnapsDownWhenGroundedAndFallsWhenAirborne) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const CharacterConfig3D cfg;
  const float stand = standing_y(cfg, 0.0f);
  // 0.2 m above the ground (as just off a step's edge): a grounded
  // character snaps down onto it, an airborne one does not.
  for (const bool was_grounded : {true, false}) {
    CharacterState3D s;
    s.position = {0.0f, stand + 0.2f, 0.0f};
    s.grounded = was_grounded;
    move_character(world, s, {0.05f, 0.0f, 0.0f}, cfg);
    EXPECT_EQ(s.grounded, was_grounded);
    EXPECT_NEAR(s.position.y, was_grounded ? stand : stand + 0.2f, 1e-4f);
    EXPECT_EQ(s.ground, was_grounded ? ground : BodyId{});
  }
  // Walking off a 0.2 m platform: the round bottom rolls over the edge
  // (briefly airborne), then it stands on the lower ground.
  add_static(world, {0.0f, 0.1f, 0.0f}, {2.0f, 0.1f, 2.0f});
  CharacterState3D s = settled(world, cfg, {0.0f, 2.0f, 0.0f});
  EXPECT_NEAR(s.position.y, standing_y(cfg, 0.2f), 1e-3f);
  int airborne = 0;
  for (int i = 0; i < 60; ++i) {
    EXPECT_FALSE(tick(world, s, {kWalk, 0.0f, 0.0f}, cfg).hit_wall);
    airborne += s.grounded ? 0 : 1;
  }
  EXPECT_LE(airborne, 10);
  EXPECT_TRUE(s.grounded);
  EXPECT_NEAR(s.position.y, stand, 1e-3f);
  // Dropped from 2 m: a free fall of 2 - 0.81 m at 20 m/s^2 takes about
  // 0.345 s (21 ticks of the game's Euler steps), then it stands.
  CharacterState3D fall;
  fall.position = {10.0f, 2.0f, 0.0f};
  int ticks = 0;
  while (!fall.grounded && ticks < 120) {
    tick(world, fall, {}, cfg);
    ++ticks;
  }
  EXPECT_GE(ticks, 20);
  EXPECT_LE(ticks, 22);
  EXPECT_NEAR(fall.position.y, stand, 1e-3f);
  EXPECT_EQ(fall.velocity.y, 0.0f);
}

TEST(Character3D, StopsAtACeilingWhenJumping) {
  World3D world;
  test::add_ground(world);
  const CharacterConfig3D cfg;
  const float head = cfg.half_height + cfg.radius;
  const float ceiling = standing_y(cfg, 0.0f) + head + 0.5f;  // 0.5 m of headroom
  add_static(world, {0.0f, ceiling + 0.5f, 0.0f}, {5.0f, 0.5f, 5.0f});
  CharacterState3D s = settled(world, cfg, {0.0f, 1.0f, 0.0f});
  s.velocity.y = 6.0f;  // would rise 0.9 m
  bool hit = false;
  float top = 0.0f;
  for (int i = 0; i < 60; ++i) {
    const CharacterMove3D m = tick(world, s, {}, cfg);
    if (m.hit_ceiling && !hit) {
      hit = true;
      EXPECT_LE(s.velocity.y, 1e-5f);  // the rise into the ceiling is gone
      EXPECT_NEAR(s.position.y + head, ceiling - cfg.skin, 1e-3f);
    }
    top = std::fmax(top, s.position.y + head);
  }
  EXPECT_TRUE(hit);
  EXPECT_LE(top, ceiling - cfg.skin + 1e-4f);
  EXPECT_TRUE(s.grounded);
  EXPECT_NEAR(s.position.y, standing_y(cfg, 0.0f), 1e-3f);
}

}  // namespace
}  // namespace rwd::sim
