// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the 3D joint tests (test_joints.cpp,
// test_joint_state.cpp).
#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim::joint_test {

inline constexpr Vec3 kX{1.0f, 0.0f, 0.0f};
inline constexpr Vec3 kY{0.0f, 1.0f, 0.0f};
inline constexpr Vec3 kZ{0.0f, 0.0f, 1.0f};

inline BodyId add_capsule(World3D& world, Vec3 position, float radius, float half_height,
                          Quat rotation = {}) {
  BodyDef def;
  def.shape = Shape::make_capsule(radius, half_height);
  def.position = position;
  def.rotation = rotation;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

inline BodyId add_static_box(World3D& world, Vec3 position, Vec3 half = {0.2f, 0.2f, 0.2f}) {
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_box(half);
  def.position = position;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok());
  return *id;
}

inline JointId make(World3D& world, const JointDef& def) {
  auto id = world.create_joint(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : JointId{};
}

// The world anchors of a joint built with joint_at (both anchors on one
// point at creation): how far apart they are now.
inline float anchor_gap(const World3D& world, BodyId a, Vec3 local_a, BodyId b, Vec3 local_b) {
  const Vec3 pa = a.is_null() ? local_a : world.position(a) + rotate(world.rotation(a), local_a);
  const Vec3 pb = world.position(b) + rotate(world.rotation(b), local_b);
  return length(pb - pa);
}

}  // namespace rwd::sim::joint_test
