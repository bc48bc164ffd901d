// SPDX-License-Identifier: MIT
#pragma once
// Small scenes the 2D world tests share, built only through the public API.
#include <gtest/gtest.h>

#include "rewind/sim2d/world2d.h"

namespace rwd::sim2d::testing {

inline BodyId2D add_body(World2D& world, BodyKind2D kind, const Result<Shape2D>& shape,
                         Vec2 position, Fx angle = Fx()) {
  EXPECT_TRUE(shape.ok()) << shape.status().message();
  BodyDef2D def;
  def.kind = kind;
  def.shape = *shape;
  def.position = position;
  def.angle = angle;
  auto id = world.create_body(def);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : BodyId2D{};
}

/// A static ground: the top of a huge circle at y = 0 (flat to 1e-6 m over
/// the few metres the tests use).
inline BodyId2D add_round_ground(World2D& world) {
  return add_body(world, BodyKind2D::kStatic, make_circle(10000_fx), {Fx(), -10000_fx});
}

}  // namespace rwd::sim2d::testing
