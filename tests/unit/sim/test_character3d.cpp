// SPDX-License-Identifier: MIT
// The 3D character controller on small box-built levels: flat walking,
// walls and sliding, creases, ramps, ledges, snapping down, ceilings,
// ground bodies that move, its own body, repeatability across a restored
// world, bad inputs, and a long walk that must never end inside geometry.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/sim/character3d.h"
#include "rewind/sim/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr float kDt = 1.0f / 60.0f;  // one 60 Hz tick
constexpr float kGravity = -20.0f;
constexpr float kWalk = 3.0f;  // m/s

BodyId add_body(World3D& world, BodyKind kind, Vec3 centre, Vec3 half, Quat rotation = {}) {
  BodyDef def;
  def.kind = kind;
  def.shape = Shape::make_box(half);
  def.position = centre;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

BodyId add_static(World3D& world, Vec3 centre, Vec3 half, Quat rotation = {}) {
  return add_body(world, BodyKind::kStatic, centre, half, rotation);
}

Quat about_y(float radians) {
  return {0.0f, det_sin(0.5f * radians), 0.0f, det_cos(0.5f * radians)};
}

// A ramp rising along +x from the ground (y = 0) at x = x0, `degrees`
// steep, `length` m along its slope, 6 m wide about z = 0.
BodyId add_ramp(World3D& world, float x0, float degrees, float length) {
  const float a = degrees * kPi / 180.0f;
  const float s = det_sin(a);
  const float c = det_cos(a);
  const float hx = 0.5f * length;
  const float hy = 0.5f;
  const Vec3 top{x0 + hx * c, hx * s, 0.0f};
  const Vec3 normal{-s, c, 0.0f};
  return add_static(world, top - normal * hy, {hx, hy, 3.0f},
                    {0.0f, 0.0f, det_sin(0.5f * a), det_cos(0.5f * a)});
}

// The capsule's centre standing on ground whose top is at height `top`.
float standing_y(const CharacterConfig3D& cfg, float top) {
  return top + cfg.radius + cfg.half_height + cfg.skin;
}

// One game tick: gravity into the velocity, the walk across it.
CharacterMove3D tick(const World3D& world, CharacterState3D& s, Vec3 walk,
                     const CharacterConfig3D& cfg, const QueryFilter& filter = {}) {
  s.velocity = {walk.x, s.velocity.y + kGravity * kDt, walk.z};
  return move_character(world, s, s.velocity * kDt, cfg, filter);
}

CharacterState3D settled(const World3D& world, const CharacterConfig3D& cfg, Vec3 at) {
  CharacterState3D s;
  s.position = at;
  for (int i = 0; i < 60; ++i) tick(world, s, {}, cfg);
  return s;
}

bool same_bits(Vec3 a, Vec3 b) {
  return std::memcmp(&a, &b, sizeof(Vec3)) == 0;
}

// Whether the capsule, `shrink` m thinner, overlaps any body.
bool inside_geometry(const World3D& world, const CharacterConfig3D& cfg, Vec3 at, float shrink,
                     const QueryFilter& filter = {}) {
  std::vector<BodyId> hits;
  EXPECT_TRUE(world
                  .overlap(Shape::make_capsule(cfg.radius - shrink, cfg.half_height), at, Quat{},
                           filter, hits)
                  .ok());
  return !hits.empty();
}

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
