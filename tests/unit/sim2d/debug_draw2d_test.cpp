// SPDX-License-Identifier: MIT
// Debug draw of the 2D lane: outlines on each body's surface (by the
// world's own signed distance), fans counter-clockwise, colours by state,
// contacts and joints where the state has them, nothing in the world
// changed.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "draw_colours.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/sim2d/debug_draw2d.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using namespace rwd::fixed::literals;  // NOLINT: test brevity
using rwd::DebugDrawBuffers;
using rwd::DebugDrawOptions;
using rwd::DrawVertex;
using testing::add_body;

Vec2 fx2(float x, float y) {
  return {Fx::from_raw(static_cast<int32_t>(std::lround(x * 65536.0f))),
          Fx::from_raw(static_cast<int32_t>(std::lround(y * 65536.0f)))};
}
float fl(Fx f) {
  return static_cast<float>(f.raw()) / 65536.0f;
}

struct Zoo {
  std::vector<BodyId2D> bodies;
};

// One body of each shape, turned, apart from each other.
Zoo add_zoo(World2D& world) {
  Zoo zoo;
  const Vec2 quad[4] = {fx2(-0.5f, -0.3f), fx2(0.6f, -0.4f), fx2(0.4f, 0.5f), fx2(-0.3f, 0.3f)};
  const Result<Shape2D> shapes[] = {make_circle(0.5_fx, fx2(0.1f, 0.0f)),
                                    make_capsule(fx2(-0.4f, 0.0f), fx2(0.4f, 0.1f), 0.2_fx),
                                    make_box(0.6_fx, 0.3_fx), make_polygon(quad, 0.1_fx),
                                    make_segment(fx2(-1.0f, 0.0f), fx2(1.0f, 0.5f))};
  float x = -6.0f;
  for (const Result<Shape2D>& shape : shapes) {
    const BodyKind2D kind =
        shape->type == ShapeType2D::kSegment ? BodyKind2D::kStatic : BodyKind2D::kDynamic;
    zoo.bodies.push_back(add_body(world, kind, shape, fx2(x, 2.0f), Fx::ratio(7, 10) * Fx(3)));
    x += 3.0f;
  }
  return zoo;
}

float nearest_surface(const World2D& world, const Zoo& zoo, float x, float y) {
  float best = 1e9f;
  for (BodyId2D b : zoo.bodies) {
    best = std::min(best, std::fabs(fl(world.signed_distance(b, fx2(x, y)))));
  }
  return best;
}

TEST(DebugDraw2D, EveryOutlineVertexLiesOnABodySurface) {
  World2D world;
  const Zoo zoo = add_zoo(world);
  DebugDrawBuffers out;
  DebugDrawOptions options;
  debug_draw(world, options, out);
  ASSERT_GT(out.lines.size(), 60u);
  for (size_t i = 0; i < out.lines.size(); ++i) {
    const DrawVertex& v = out.lines[i];
    EXPECT_EQ(v.z, 0.0f);
    // The circle's radius line starts at its centre; every other vertex is
    // on the surface to within the Q16.16 grid and float rounding.
    const float d = nearest_surface(world, zoo, v.x, v.y);
    const bool circle_centre = std::fabs(v.x - (-6.0f + 0.1f * std::cos(2.1f))) < 1e-3f &&
                               std::fabs(v.y - (2.0f + 0.1f * std::sin(2.1f))) < 1e-3f;
    if (!circle_centre) {
      EXPECT_LT(d, 2e-4f) << v.x << " " << v.y;
    }
  }
}

TEST(DebugDraw2D, SolidFansAreCounterClockwiseAndInside) {
  World2D world;
  const Zoo zoo = add_zoo(world);
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  options.solid_shapes = true;
  debug_draw(world, options, out);
  ASSERT_GT(out.triangles.size(), 60u);
  EXPECT_TRUE(out.lines.size() == 2u);  // the segment has no surface: its line
  for (size_t i = 0; i < out.triangles.size(); i += 3) {
    const DrawVertex& a = out.triangles[i];
    const DrawVertex& b = out.triangles[i + 1];
    const DrawVertex& c = out.triangles[i + 2];
    const float area2 = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    EXPECT_GT(area2, 0.0f);
    const float cx = (a.x + b.x + c.x) / 3.0f;
    const float cy = (a.y + b.y + c.y) / 3.0f;
    float inside = 1e9f;
    for (BodyId2D body : zoo.bodies) {
      inside = std::min(inside, fl(world.signed_distance(body, fx2(cx, cy))));
    }
    EXPECT_LT(inside, 1e-4f) << cx << " " << cy;
  }
}

TEST(DebugDraw2D, BodiesTakeTheColourOfTheirState) {
  World2D world;
  testing::add_round_ground(world);
  const BodyId2D box =
      add_body(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.5_fx), {Fx(), 0.5_fx});
  const BodyId2D mover =
      add_body(world, BodyKind2D::kKinematic, make_circle(0.3_fx), {Fx(5), Fx(3)});
  DebugDrawOptions options;
  options.contacts = false;
  const rwd::DrawColors& c = options.colors;
  auto colours = [&](const DebugDrawOptions& o) {
    DebugDrawBuffers out;
    debug_draw(world, o, out);
    return test_support::line_colours(out);
  };
  using test_support::sorted;
  EXPECT_EQ(colours(options), sorted({c.static_body, c.awake_body, c.kinematic_body}));
  for (int i = 0; i < 240 && world.is_awake(box); ++i) world.step();
  ASSERT_FALSE(world.is_awake(box));
  EXPECT_EQ(colours(options), sorted({c.static_body, c.asleep_body, c.kinematic_body}));
  const uint32_t highlight[] = {mover.index};
  options.highlight_bodies = highlight;
  options.static_shapes = false;
  EXPECT_EQ(colours(options), sorted({c.asleep_body, c.highlight}));
}

TEST(DebugDraw2D, ContactsOfARestingBoxAreOnTheGround) {
  World2D world;
  add_body(world, BodyKind2D::kStatic, make_box(Fx(10), 0.5_fx), {Fx(), -0.5_fx});
  add_body(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.5_fx), {0.25_fx, 0.55_fx});
  for (int i = 0; i < 60; ++i) world.step();
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  debug_draw(world, options, out);
  ASSERT_EQ(out.points.size(), 2u);
  ASSERT_EQ(out.lines.size(), 4u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(out.points[k].y, 0.0f, 0.01f);
    EXPECT_NEAR(std::fabs(out.points[k].x - 0.25f), 0.5f, 0.01f);
    // From the ground (body 0) up to the box.
    EXPECT_NEAR(out.lines[2 * k + 1].y - out.lines[2 * k].y, options.normal_length_m, 1e-4f);
  }
}

TEST(DebugDraw2D, AJointLinksItsAnchorsAndAGrabItsTarget) {
  World2D world;
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {Fx(), Fx()});
  const BodyId2D arm =
      add_body(world, BodyKind2D::kDynamic, make_box(1_fx, 0.1_fx), {Fx(2), Fx(3)});
  JointDef2D hinge;
  hinge.type = JointType2D::kRevolute;
  hinge.body_a = ground;
  hinge.body_b = arm;
  hinge.anchor_a = {Fx(1), Fx(3)};
  hinge.anchor_b = {Fx(1), Fx(3)};
  ASSERT_TRUE(world.create_joint(hinge).ok());
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  debug_draw(world, options, out);
  ASSERT_EQ(out.lines.size(), 2u * (3u + 4u));
  EXPECT_NEAR(out.lines[4].x, 1.0f, 1e-4f);  // anchor to anchor: (1, 3) twice
  EXPECT_NEAR(out.lines[4].y, 3.0f, 1e-4f);
  EXPECT_NEAR(out.lines[5].x, 1.0f, 1e-4f);
  EXPECT_NEAR(out.lines[5].y, 3.0f, 1e-4f);

  JointDef2D grab;
  grab.type = JointType2D::kGrab;
  grab.body_a = ground;
  grab.body_b = arm;
  grab.anchor_b = {Fx(2), Fx(3)};
  grab.target = {Fx(4), Fx(5)};
  grab.max_force = Fx(100);
  ASSERT_TRUE(world.create_joint(grab).ok());
  out.clear();
  debug_draw(world, options, out);
  ASSERT_EQ(out.lines.size(), 2u * (3u + 4u) + 2u * (1u + 4u));
  EXPECT_NEAR(out.lines[14].x, 2.0f, 1e-4f);
  EXPECT_NEAR(out.lines[15].x, 4.0f, 1e-4f);
  EXPECT_NEAR(out.lines[15].y, 5.0f, 1e-4f);
}

TEST(DebugDraw2D, DrawingChangesNothingAndBadShapesDrawNothing) {
  World2D world;
  add_zoo(world);
  for (int i = 0; i < 10; ++i) world.step();
  const uint64_t before = world.checksum();
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.solid_shapes = true;
  options.bounds = true;
  options.centers_of_mass = true;
  debug_draw(world, options, out);
  EXPECT_EQ(world.checksum(), before);
  EXPECT_FALSE(out.empty());
  out.clear();
  Shape2D bad = *make_box(1_fx, 1_fx);
  bad.count = 9;
  draw_shape(bad, {}, {}, {}, 0xFFFFFFFFu, options, out);
  EXPECT_TRUE(out.empty());
  options.circle_segments = 0;  // clamped to 8
  draw_shape(*make_circle(1_fx), {Fx(3), Fx()}, {}, Fx(2), 0x123456FFu, options, out);
  EXPECT_EQ(out.lines.size(), 2u * (8u + 1u));
  EXPECT_EQ(out.triangles.size(), 3u * 6u);
  for (const DrawVertex& v : out.lines) EXPECT_EQ(v.z, 2.0f);
}

}  // namespace
}  // namespace rwd::sim2d
