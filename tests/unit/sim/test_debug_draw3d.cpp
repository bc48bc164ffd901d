// SPDX-License-Identifier: MIT
// Debug draw of the 3D lane: every drawn outline lies on its body's surface
// (by the world's own signed distance), solids face outward, bodies take the
// colour of their state, contacts and joints sit where the state says, and
// drawing changes nothing in the world.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "draw_colours.h"
#include "rewind/sim/debug_draw3d.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

Vec3 at(const DrawVertex& v) {
  return {v.x, v.y, v.z};
}

// A hull (a slanted wedge), a compound of two boxes apart and a height
// field with a hole, beside the primitives: one of each body shape.
struct ShapeZoo {
  std::vector<BodyId> bodies;
  BodyId field;
};

ShapeZoo add_zoo(World3D& world) {
  ShapeZoo zoo;
  GeometryStore& store = world.geometry();
  const std::vector<Vec3> wedge = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                   {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.6f}, {0.3f, 0.8f, 0.7f}};
  const GeometryId hull = *store.add_hull_from_points(wedge);
  const CompoundChild children[2] = {
      {Shape::make_box({0.3f, 0.2f, 0.2f}), {-0.6f, 0.0f, 0.0f}, {}},
      {Shape::make_hull(hull), {0.5f, 0.1f, 0.0f}, normalize(Quat{0.2f, 0.1f, 0.0f, 1.0f})}};
  const GeometryId compound = *store.add_compound(children);
  const Shape shapes[] = {Shape::make_sphere(0.4f), Shape::make_box({0.5f, 0.3f, 0.2f}),
                          Shape::make_capsule(0.25f, 0.4f), Shape::make_hull(hull),
                          Shape::make_compound(compound)};
  test::Rng rng{7};
  float x = -6.0f;
  for (const Shape& shape : shapes) {
    BodyDef def;
    def.shape = shape;
    def.position = {x, 3.0f, rng.uniform(-1.0f, 1.0f)};
    def.rotation = rng.rotation();
    zoo.bodies.push_back(*world.create_body(def));
    x += 2.5f;
  }
  std::vector<float> heights(6 * 5);
  for (uint32_t i = 0; i < heights.size(); ++i) heights[i] = 0.1f * static_cast<float>(i % 7);
  std::vector<uint8_t> holes(5 * 4, 0);
  holes[6] = 1;  // row 1, column 2
  const GeometryId hf = *store.add_height_field(6, 5, {1.0f, 1.0f, 1.0f}, heights, holes);
  zoo.field = test::add_static(world, Shape::make_height_field(hf), {-2.0f, -1.0f, -2.0f});
  zoo.bodies.push_back(zoo.field);
  return zoo;
}

// The body a drawn point belongs to: the one it lies nearest the surface of.
float nearest_surface(const World3D& world, const std::vector<BodyId>& bodies, Vec3 p) {
  float best = 1e9f;
  for (BodyId b : bodies) {
    const auto d = world.signed_distance(b, p);
    if (d) best = std::min(best, std::fabs(d->distance));
  }
  return best;
}

TEST(DebugDraw3D, EveryOutlineVertexLiesOnABodySurface) {
  World3D world;
  const ShapeZoo zoo = add_zoo(world);
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.contacts = false;
  debug_draw(world, options, out);
  ASSERT_GT(out.lines.size(), 100u);
  EXPECT_EQ(out.lines.size() % 2, 0u);
  EXPECT_TRUE(out.triangles.empty());
  for (const DrawVertex& v : out.lines) {
    // Curved outlines are drawn through points on the surface, so every
    // vertex is on it to float precision (2e-5 m at these sizes).
    EXPECT_LT(nearest_surface(world, zoo.bodies, at(v)), 2e-5f) << v.x << " " << v.y << " " << v.z;
  }
}

TEST(DebugDraw3D, SolidTrianglesLieOnTheSurfaceAndFaceOutward) {
  World3D world;
  const ShapeZoo zoo = add_zoo(world);
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  options.solid_shapes = true;
  options.contacts = false;
  debug_draw(world, options, out);
  ASSERT_GT(out.triangles.size(), 100u);
  EXPECT_TRUE(out.lines.empty());
  ASSERT_EQ(out.triangles.size() % 3, 0u);
  uint32_t checked = 0;
  for (size_t i = 0; i < out.triangles.size(); i += 3) {
    const Vec3 a = at(out.triangles[i]);
    const Vec3 b = at(out.triangles[i + 1]);
    const Vec3 c = at(out.triangles[i + 2]);
    const Vec3 n = cross(b - a, c - a);
    if (length(n) < 1e-6f) continue;
    const Vec3 centre = (a + b + c) * (1.0f / 3.0f);
    const Vec3 step = normalize_or_zero(n) * 1e-3f;
    // Curved surfaces are cut by flat facets: a facet's centre lies inside
    // a sphere or capsule of radius r by up to r (1 - cos(pi / 12)) ~ 3.4%.
    EXPECT_LT(nearest_surface(world, zoo.bodies, centre), 1.5e-2f);
    // Outward: a millimetre along the facet's normal is farther out of the
    // body than a millimetre against it (the field's side is "up").
    float out_d = 1e9f;
    float in_d = 1e9f;
    for (BodyId body : zoo.bodies) {
      const auto d0 = world.signed_distance(body, centre);
      if (!d0 || std::fabs(d0->distance) > 1.5e-2f) continue;
      out_d = std::min(out_d, world.signed_distance(body, centre + step)->distance);
      in_d = std::min(in_d, world.signed_distance(body, centre - step)->distance);
    }
    EXPECT_GT(out_d, in_d) << "facet at " << centre.x << " " << centre.y << " " << centre.z;
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

TEST(DebugDraw3D, HeightFieldHolesAreLeftOut) {
  World3D world;
  const std::vector<float> heights(9, 0.0f);
  std::vector<uint8_t> holes = {0, 1, 0, 0};  // cell (0, 1): x in [1, 2], z in [0, 1]
  const GeometryId hf =
      *world.geometry().add_height_field(3, 3, {1.0f, 1.0f, 1.0f}, heights, holes);
  test::add_static(world, Shape::make_height_field(hf), {});
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.solid_shapes = true;
  debug_draw(world, options, out);
  EXPECT_EQ(out.triangles.size(), 3u * 2u * 3u);  // three cells of two
  for (size_t i = 0; i < out.triangles.size(); i += 3) {
    const Vec3 c = (at(out.triangles[i]) + at(out.triangles[i + 1]) + at(out.triangles[i + 2])) *
                   (1.0f / 3.0f);
    EXPECT_FALSE(c.x > 1.0f && c.x < 2.0f && c.z > 0.0f && c.z < 1.0f);
  }
  // Each edge once: 3 cells of 3 edges each, plus the outline's closing
  // edges where the hole or the border is.
  for (size_t i = 0; i < out.lines.size(); i += 2) {
    const Vec3 mid = (at(out.lines[i]) + at(out.lines[i + 1])) * 0.5f;
    for (size_t j = i + 2; j < out.lines.size(); j += 2) {
      const Vec3 other = (at(out.lines[j]) + at(out.lines[j + 1])) * 0.5f;
      EXPECT_GT(length(mid - other), 1e-4f) << "an edge drawn twice at " << mid.x << " " << mid.z;
    }
  }
}

TEST(DebugDraw3D, BodiesTakeTheColourOfTheirState) {
  World3D world;
  test::add_ground(world);
  const BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  BodyDef kinematic_def;
  kinematic_def.kind = BodyKind::kKinematic;
  kinematic_def.position = {5.0f, 2.0f, 0.0f};
  const BodyId kinematic = *world.create_body(kinematic_def);
  DebugDrawOptions options;
  options.contacts = false;
  const DrawColors& c = options.colors;
  auto colours = [&](const DebugDrawOptions& o) {
    DebugDrawBuffers out;
    debug_draw(world, o, out);
    return test_support::line_colours(out);
  };
  using test_support::sorted;
  EXPECT_EQ(colours(options), sorted({c.static_body, c.awake_body, c.kinematic_body}));
  test::step_seconds(world, 3.0f);
  ASSERT_FALSE(world.is_awake(box));
  EXPECT_EQ(colours(options), sorted({c.static_body, c.asleep_body, c.kinematic_body}));
  const uint32_t highlight[] = {kinematic.index};
  options.highlight_bodies = highlight;
  EXPECT_EQ(colours(options), sorted({c.static_body, c.asleep_body, c.highlight}));
  options.static_shapes = false;
  EXPECT_EQ(colours(options), sorted({c.asleep_body, c.highlight}));
  ASSERT_TRUE(world.set_enabled(box, false).ok());
  options.highlight_bodies = {};
  EXPECT_EQ(colours(options), sorted({c.disabled_body, c.kinematic_body}));
}

TEST(DebugDraw3D, ContactsOfARestingBoxAreOnTheGroundWithUpwardNormals) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  test::add_box(world, {0.3f, 0.6f, -0.2f});
  test::step_seconds(world, 1.0f);
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  options.normal_length_m = 0.5f;
  debug_draw(world, options, out);
  ASSERT_EQ(out.points.size(), 4u);
  ASSERT_EQ(out.lines.size(), 8u);  // a normal per point
  for (size_t k = 0; k < 4; ++k) {
    const DrawPoint& p = out.points[k];
    EXPECT_NEAR(p.y, 0.0f, 0.01f);
    EXPECT_NEAR(std::fabs(p.x - 0.3f), 0.5f, 0.02f);
    EXPECT_NEAR(std::fabs(p.z + 0.2f), 0.5f, 0.02f);
    EXPECT_EQ(p.color, options.colors.contact_touching);
    EXPECT_EQ(p.size_px, options.contact_point_px);
    const Vec3 a = at(out.lines[2 * k]);
    const Vec3 b = at(out.lines[2 * k + 1]);
    EXPECT_EQ(a.x, p.x);
    EXPECT_EQ(a.y, p.y);
    // From the first body of the pair (the ground, created first) up.
    ASSERT_LT(ground.index, 1u);
    EXPECT_NEAR(b.y - a.y, 0.5f, 1e-4f);
    EXPECT_NEAR(length(b - a), 0.5f, 1e-4f);
  }
  options.contact_normals = false;
  out.clear();
  debug_draw(world, options, out);
  EXPECT_EQ(out.points.size(), 4u);
  EXPECT_TRUE(out.lines.empty());
}

TEST(DebugDraw3D, AJointLinksItsAnchors) {
  World3D world;
  const BodyId a = test::add_box(world, {0.0f, 5.0f, 0.0f});
  const BodyId b = test::add_box(world, {1.5f, 5.0f, 0.0f});
  JointDef def;
  def.type = JointType::kBall;
  def.body_a = a;
  def.body_b = b;
  def.anchor_a = {0.75f, 0.0f, 0.0f};
  def.anchor_b = {-0.75f, 0.0f, 0.0f};
  ASSERT_TRUE(world.create_joint(def).ok());
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.shapes = false;
  debug_draw(world, options, out);
  // Centre to anchor on each side, anchor to anchor, and a cross at each.
  ASSERT_EQ(out.lines.size(), 2u * (3u + 6u));
  for (const DrawVertex& v : out.lines) EXPECT_EQ(v.color, options.colors.joint);
  EXPECT_NEAR(out.lines[4].x, 0.75f, 1e-5f);  // the anchors, A's then B's
  EXPECT_NEAR(out.lines[5].x, 0.75f, 1e-5f);
  EXPECT_NEAR(out.lines[4].y, 5.0f, 1e-5f);
}

TEST(DebugDraw3D, DrawingChangesNothingAndAWarmFrameKeepsItsBuffers) {
  World3D world;
  test::add_ground(world);
  add_zoo(world);
  test::step_seconds(world, 0.5f);
  const uint64_t before = world.checksum();
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.solid_shapes = true;
  options.bounds = true;
  options.centers_of_mass = true;
  debug_draw(world, options, out);
  EXPECT_EQ(world.checksum(), before);
  const size_t lines = out.lines.size();
  const DrawVertex* data = out.lines.data();
  out.clear();
  debug_draw(world, options, out);
  EXPECT_EQ(out.lines.size(), lines);
  EXPECT_EQ(out.lines.data(), data);  // the same storage: no allocation
  debug_draw(world, options, out);    // a call appends
  EXPECT_EQ(out.lines.size(), 2 * lines);
  world.step();
  test::step_seconds(world, 0.1f);
  EXPECT_NE(world.checksum(), before);
}

TEST(DebugDraw3D, BoundsEncloseTheOutlines) {
  World3D world;
  const ShapeZoo zoo = add_zoo(world);
  DebugDrawBuffers shapes;
  DebugDrawOptions options;
  options.contacts = false;
  debug_draw(world, options, shapes);
  DebugDrawBuffers boxes;
  options.shapes = false;
  options.bounds = true;
  debug_draw(world, options, boxes);
  ASSERT_EQ(boxes.lines.size(), zoo.bodies.size() * 24u);
  Vec3 lo{1e9f, 1e9f, 1e9f};
  Vec3 hi = -lo;
  for (const DrawVertex& v : boxes.lines) {
    lo = min(lo, at(v));
    hi = max(hi, at(v));
  }
  for (const DrawVertex& v : shapes.lines) {
    EXPECT_GE(v.x, lo.x - 1e-5f);
    EXPECT_LE(v.y, hi.y + 1e-5f);
  }
}

TEST(DebugDraw3D, AShapeAtAPoseAndBadInput) {
  World3D world;
  DebugDrawBuffers out;
  DebugDrawOptions options;
  options.circle_segments = 1000;  // clamped to 64
  draw_shape(world.geometry(), Shape::make_sphere(1.0f), {1.0f, 2.0f, 3.0f}, {}, 0x112233FFu,
             options, out);
  EXPECT_EQ(out.lines.size(), 3u * 64u * 2u);
  for (const DrawVertex& v : out.lines) {
    EXPECT_NEAR(length(at(v) - Vec3{1.0f, 2.0f, 3.0f}), 1.0f, 1e-5f);
    EXPECT_EQ(v.color, 0x112233FFu);
  }
  out.clear();
  const float nan = std::nanf("");
  draw_shape(world.geometry(), Shape::make_box({1.0f, 1.0f, 1.0f}), {nan, 0.0f, 0.0f}, {},
             0xFFFFFFFFu, options, out);
  draw_shape(world.geometry(), Shape::make_box({1.0f, 1.0f, 1.0f}), {}, Quat{0, 0, 0, 0},
             0xFFFFFFFFu, options, out);
  draw_shape(world.geometry(), Shape::make_hull(GeometryId{42}), {}, {}, 0xFFFFFFFFu, options, out);
  const std::vector<float> heights(4, 0.0f);
  const GeometryId field = *world.geometry().add_height_field(2, 2, {1, 1, 1}, heights);
  draw_shape(world.geometry(), Shape::make_hull(field), {}, {}, 0xFFFFFFFFu, options, out);
  EXPECT_TRUE(out.empty());
  // A hull at its authored pose: its corners where the points were given.
  const std::vector<Vec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const GeometryId hull = *world.geometry().add_hull(tetra);
  draw_shape(world.geometry(), Shape::make_hull(hull), {10.0f, 0.0f, 0.0f}, {}, 0xFFFFFFFFu,
             options, out);
  ASSERT_EQ(out.lines.size(), 12u);
  for (const DrawVertex& v : out.lines) {
    const Vec3 p = at(v) - Vec3{10.0f, 0.0f, 0.0f};
    const bool corner =
        std::any_of(tetra.begin(), tetra.end(), [&](Vec3 c) { return length(p - c) < 1e-5f; });
    EXPECT_TRUE(corner) << p.x << " " << p.y << " " << p.z;
  }
}

}  // namespace
}  // namespace rwd::sim
