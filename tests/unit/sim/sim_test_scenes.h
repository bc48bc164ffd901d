// SPDX-License-Identifier: MIT
#pragma once
// Small scene builders shared by the 3D lane's tests.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rewind/core/splitmix64.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::test {

/// A static ground box whose top face is at y = 0.
inline BodyId add_ground(World3D& world, float friction = 0.6f) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_box({50.0f, 0.5f, 50.0f});
  def.position = {0.0f, -0.5f, 0.0f};
  def.material.friction = friction;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

/// A static body of `shape` at the pose given.
inline BodyId add_static(World3D& world, Shape shape, Vec3 position, Quat rotation = {}) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = shape;
  def.position = position;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return *id;
}

inline BodyId add_box(World3D& world, Vec3 position, Vec3 half = {0.5f, 0.5f, 0.5f},
                      float restitution = 0.0f, float friction = 0.6f) {
  BodyDef def;
  def.shape = Shape::make_box(half);
  def.position = position;
  def.material.restitution = restitution;
  def.material.friction = friction;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

inline BodyId add_sphere(World3D& world, Vec3 position, float radius = 0.5f,
                         float restitution = 0.0f) {
  BodyDef def;
  def.shape = Shape::make_sphere(radius);
  def.position = position;
  def.material.restitution = restitution;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

/// SplitMix64: the same sequence on every platform (std distributions are
/// not specified bit for bit), for reproducible random scenes and queries.
struct Rng : SplitMix64 {
  float uniform(float lo, float hi) { return lo + (hi - lo) * unit(); }
  Quat rotation() {
    return normalize(Quat{uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f),
                          uniform(-1.0f, 1.0f)});
  }
};

inline void step_seconds(World3D& world, float seconds) {
  int steps = static_cast<int>(seconds / world.config().tick_seconds + 0.5f);
  for (int i = 0; i < steps; ++i) world.step();
}

/// Saves and serializes `world`, steps it 60 ticks, then checks that a
/// restore, and a world sharing its geometry store that loads the bytes,
/// both step alike bit for bit, and that a world without that geometry
/// refuses the bytes.
inline void expect_snapshots_restore(World3D& world) {
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  for (int t = 0; t < 60; ++t) {
    world.step();
    sums.push_back(world.checksum());
  }
  world.restore(saved);
  for (int t = 0; t < 60; ++t) {
    world.step();
    ASSERT_EQ(world.checksum(), sums[static_cast<size_t>(t)]) << "restored, tick " << t;
  }
  World3D loaded({}, world.shared_geometry());
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  for (int t = 0; t < 60; ++t) {
    loaded.step();
    ASSERT_EQ(loaded.checksum(), sums[static_cast<size_t>(t)]) << "loaded, tick " << t;
  }
  World3D other;
  EXPECT_EQ(other.deserialize(bytes).code(), ErrorCode::kCorrupt);
}

}  // namespace rwd::sim::test
