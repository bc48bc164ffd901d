// SPDX-License-Identifier: MIT
#pragma once
// Small box-built levels and a game tick for the 3D character controller's
// tests (test_character3d*.cpp).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "rewind/core/det_math.h"
#include "rewind/sim/character3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::character_test {

inline constexpr float kDt = 1.0f / 60.0f;  // one 60 Hz tick
inline constexpr float kGravity = -20.0f;
inline constexpr float kWalk = 3.0f;  // m/s

inline BodyId add_body(World3D& world, BodyKind kind, Vec3 centre, Vec3 half, Quat rotation = {}) {
  BodyDef def;
  def.kind = kind;
  def.shape = Shape::make_box(half);
  def.position = centre;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

inline BodyId add_static(World3D& world, Vec3 centre, Vec3 half, Quat rotation = {}) {
  return add_body(world, BodyKind::kStatic, centre, half, rotation);
}

inline Quat about_y(float radians) {
  return {0.0f, det_sin(0.5f * radians), 0.0f, det_cos(0.5f * radians)};
}

// A ramp rising along +x from the ground (y = 0) at x = x0, `degrees`
// steep, `length` m along its slope, 6 m wide about z = 0.
inline BodyId add_ramp(World3D& world, float x0, float degrees, float length) {
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
inline float standing_y(const CharacterConfig3D& cfg, float top) {
  return top + cfg.radius + cfg.half_height + cfg.skin;
}

// One game tick: gravity into the velocity, the walk across it.
inline CharacterMove3D tick(const World3D& world, CharacterState3D& s, Vec3 walk,
                            const CharacterConfig3D& cfg, const QueryFilter& filter = {}) {
  s.velocity = {walk.x, s.velocity.y + kGravity * kDt, walk.z};
  return move_character(world, s, s.velocity * kDt, cfg, filter);
}

inline CharacterState3D settled(const World3D& world, const CharacterConfig3D& cfg, Vec3 at) {
  CharacterState3D s;
  s.position = at;
  for (int i = 0; i < 60; ++i) tick(world, s, {}, cfg);
  return s;
}

inline bool same_bits(Vec3 a, Vec3 b) {
  return std::memcmp(&a, &b, sizeof(Vec3)) == 0;
}

// Whether the capsule, `shrink` m thinner, overlaps any body.
inline bool inside_geometry(const World3D& world, const CharacterConfig3D& cfg, Vec3 at,
                            float shrink, const QueryFilter& filter = {}) {
  std::vector<BodyId> hits;
  EXPECT_TRUE(world
                  .overlap(Shape::make_capsule(cfg.radius - shrink, cfg.half_height), at, Quat{},
                           filter, hits)
                  .ok());
  return !hits.empty();
}

}  // namespace rwd::sim::character_test
