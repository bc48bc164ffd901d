// SPDX-License-Identifier: MIT
// The chain segment factory, its validation, and make_chain's ghosts.
#include "rewind/sim2d/chain2d.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "rewind/fixed/fx_literal.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::sim2d {
namespace {

using namespace rwd::fixed::literals;  // NOLINT: test brevity

bool refused_with(const Status& s, const std::string& words) {
  return !s.ok() && s.code() == ErrorCode::kInvalidArgument &&
         s.message().find(words) != std::string::npos;
}

TEST(Shape2DChain, SegmentStoresPointsThenGhosts) {
  const Result<Shape2D> s =
      make_chain_segment({2_fx, 1_fx}, {1_fx, Fx()}, {-1_fx, Fx()}, {-2_fx, 1_fx});
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->type, ShapeType2D::kChainSegment);
  EXPECT_EQ(s->count, 2);
  EXPECT_EQ(s->radius, Fx());
  EXPECT_EQ(s->vertices[0], (Vec2{1_fx, Fx()}));
  EXPECT_EQ(s->vertices[1], (Vec2{-1_fx, Fx()}));
  EXPECT_EQ(s->vertices[2], (Vec2{2_fx, 1_fx}));
  EXPECT_EQ(s->vertices[3], (Vec2{-2_fx, 1_fx}));
  EXPECT_EQ(s->centroid, Vec2());
  EXPECT_TRUE(validate_shape(*s).ok());
}

TEST(Shape2DChain, SegmentRefusalsNameTheFault) {
  const Vec2 a{1_fx, Fx()};
  const Vec2 b{-1_fx, Fx()};
  const Vec2 g{3_fx, Fx()};
  EXPECT_TRUE(refused_with(make_chain_segment(g, a, a, g).status(), "points 0 and 1"));
  EXPECT_TRUE(refused_with(make_chain_segment(a, a, b, g).status(), "ghost1"));
  EXPECT_TRUE(refused_with(make_chain_segment(g, a, b, b).status(), "ghost2"));
  const Vec2 far{Fx::from_raw(INT32_MIN), Fx()};
  const Vec2 other_far{Fx::from_raw(INT32_MAX), Fx()};
  EXPECT_TRUE(refused_with(make_chain_segment(g, far, other_far, g).status(), "range"));
  EXPECT_TRUE(refused_with(make_chain_segment(other_far, far, b, g).status(), "ghost1 edge"));
}

TEST(Shape2DChain, ValidateShapeChecksAHandBuiltChainSegment) {
  Shape2D s = *make_chain_segment({2_fx, Fx()}, {1_fx, Fx()}, {-1_fx, Fx()}, {-2_fx, Fx()});
  Shape2D bad = s;
  bad.vertices[2] = bad.vertices[0];
  EXPECT_TRUE(refused_with(validate_shape(bad), "ghost1"));
  bad = s;
  bad.count = 4;
  EXPECT_TRUE(refused_with(validate_shape(bad), "count"));
  bad = s;
  bad.radius = 1_fx;
  EXPECT_TRUE(refused_with(validate_shape(bad), "radius"));
  bad = s;
  bad.centroid = {1_fx, Fx()};
  EXPECT_TRUE(refused_with(validate_shape(bad), "centroid"));
  bad = s;
  bad.vertices[4] = {1_fx, 1_fx};
  EXPECT_TRUE(refused_with(validate_shape(bad), "unused"));
}

TEST(Shape2DChain, OnlyStaticAndKinematicBodiesTakeChainSegments) {
  World2D world;
  BodyDef2D def;
  def.shape = *make_chain_segment({2_fx, Fx()}, {1_fx, Fx()}, {-1_fx, Fx()}, {-2_fx, Fx()});
  def.kind = BodyKind2D::kDynamic;
  EXPECT_TRUE(refused_with(world.create_body(def).status(), "chain segment has no area"));
  def.kind = BodyKind2D::kStatic;
  EXPECT_TRUE(world.create_body(def).ok());
  def.kind = BodyKind2D::kKinematic;
  EXPECT_TRUE(world.create_body(def).ok());
}

TEST(Shape2DChain, LoopGhostsAreTheNeighboursFarPoints) {
  const std::array<Vec2, 4> p{{{-1_fx, -1_fx}, {-1_fx, 1_fx}, {1_fx, 1_fx}, {1_fx, -1_fx}}};
  const Result<std::vector<Shape2D>> chain = make_chain(p, true);
  ASSERT_TRUE(chain.ok()) << chain.status().message();
  ASSERT_EQ(chain->size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const Shape2D& s = (*chain)[i];
    EXPECT_EQ(s.vertices[0], p[i]);
    EXPECT_EQ(s.vertices[1], p[(i + 1) % 4]);
    EXPECT_EQ(s.vertices[2], p[(i + 3) % 4]);
    EXPECT_EQ(s.vertices[3], p[(i + 2) % 4]);
    EXPECT_TRUE(validate_shape(s).ok());
  }
}

TEST(Shape2DChain, OpenEndsGetSquareGhosts) {
  // A floor open upwards (right to left): the ends' ghosts drop straight
  // below the end points by the edge's length.
  const std::array<Vec2, 3> p{{{4_fx, Fx()}, {1_fx, Fx()}, {-1_fx, Fx()}}};
  const Result<std::vector<Shape2D>> chain = make_chain(p, false);
  ASSERT_TRUE(chain.ok()) << chain.status().message();
  ASSERT_EQ(chain->size(), 2u);
  EXPECT_EQ((*chain)[0].vertices[2], (Vec2{4_fx, -3_fx}));
  EXPECT_EQ((*chain)[0].vertices[3], p[2]);
  EXPECT_EQ((*chain)[1].vertices[2], p[0]);
  EXPECT_EQ((*chain)[1].vertices[3], (Vec2{-1_fx, -2_fx}));
  // One edge: both ends square.
  const Result<std::vector<Shape2D>> one = make_chain(std::span(p).first(2), false);
  ASSERT_TRUE(one.ok());
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ((*one)[0].vertices[2], (Vec2{4_fx, -3_fx}));
  EXPECT_EQ((*one)[0].vertices[3], (Vec2{1_fx, -3_fx}));
  // Near the coordinate limit the ghost offset is halved until it fits.
  const std::array<Vec2, 2> edge{{{Fx::from_raw(-100), Fx::from_raw(INT32_MIN + 5)},
                                  {Fx::from_raw(-100 - (1 << 20)), Fx::from_raw(INT32_MIN + 5)}}};
  const Result<std::vector<Shape2D>> low = make_chain(edge, false);
  ASSERT_TRUE(low.ok()) << low.status().message();
  EXPECT_EQ((*low)[0].vertices[2].x, edge[0].x);
  EXPECT_LT((*low)[0].vertices[2].y, edge[0].y);
}

TEST(Shape2DChain, MakeChainRefusals) {
  const std::array<Vec2, 3> p{{{Fx(), Fx()}, {1_fx, Fx()}, {1_fx, Fx()}}};
  EXPECT_TRUE(refused_with(make_chain(std::span(p).first(1), false).status(), "at least 2"));
  EXPECT_TRUE(refused_with(make_chain(std::span(p).first(2), true).status(), "at least 3"));
  EXPECT_TRUE(refused_with(make_chain(p, false).status(), "points 1 and 2 repeat"));
  const std::array<Vec2, 3> back{{{Fx(), Fx()}, {1_fx, Fx()}, {Fx(), Fx()}}};
  EXPECT_TRUE(make_chain(back, false).ok());
  EXPECT_TRUE(refused_with(make_chain(back, true).status(), "points 2 and 0 repeat"));
}

}  // namespace
}  // namespace rwd::sim2d
