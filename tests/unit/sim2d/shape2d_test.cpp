// SPDX-License-Identifier: MIT
// The shape factories: every refusal with its message, winding
// normalization, and the derived normals and centroid.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rewind/fixed/rot2.h"
#include "sim2d_test_util.h"

namespace rwd::sim2d {
namespace {

using namespace rwd::fixed::literals;  // NOLINT: test brevity
using test::ok;

void expect_refused(const Result<Shape2D>& r, const std::string& message) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(r.status().message(), message);
}

Result<Shape2D> polygon(const std::vector<Vec2>& pts, Fx radius = Fx()) {
  return make_polygon(pts, radius);
}

TEST(Shape2DFactory, CircleFieldsAndRefusals) {
  const Shape2D c = ok(make_circle(0.5_fx, {1.0_fx, -2.0_fx}));
  EXPECT_EQ(c.type, ShapeType2D::kCircle);
  EXPECT_EQ(c.count, 1);
  EXPECT_EQ(c.radius, 0.5_fx);
  EXPECT_EQ(c.vertices[0], Vec2(1.0_fx, -2.0_fx));
  EXPECT_EQ(c.centroid, Vec2(1.0_fx, -2.0_fx));
  EXPECT_EQ(c.vertices[1], Vec2());
  EXPECT_EQ(c.normals[0], Vec2());
  expect_refused(make_circle(Fx()), "circle radius must be > 0");
  expect_refused(make_circle(-1.0_fx), "circle radius must be > 0");
  EXPECT_TRUE(validate_shape(c).ok());
}

TEST(Shape2DFactory, CapsuleAndSegment) {
  const Shape2D c = ok(make_capsule({-1.0_fx, 0.0_fx}, {2.0_fx, 1.0_fx}, 0.25_fx));
  EXPECT_EQ(c.type, ShapeType2D::kCapsule);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.centroid, Vec2(0.5_fx, 0.5_fx));
  EXPECT_TRUE(validate_shape(c).ok());
  expect_refused(make_capsule({1.0_fx, 1.0_fx}, {1.0_fx, 1.0_fx}, 0.25_fx),
                 "capsule points 0 and 1 are the same");
  expect_refused(make_capsule({0.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, Fx()),
                 "capsule radius must be > 0");

  const Shape2D s = ok(make_segment({-4.0_fx, 1.0_fx}, {4.0_fx, 3.0_fx}));
  EXPECT_EQ(s.type, ShapeType2D::kSegment);
  EXPECT_EQ(s.count, 2);
  EXPECT_EQ(s.radius, Fx());
  EXPECT_EQ(s.centroid, Vec2(0.0_fx, 2.0_fx));
  EXPECT_TRUE(validate_shape(s).ok());
  expect_refused(make_segment({2.0_fx, 1.0_fx}, {2.0_fx, 1.0_fx}),
                 "segment points 0 and 1 are the same");
}

TEST(Shape2DFactory, AxisAlignedBox) {
  const Shape2D b = ok(make_box(2.0_fx, 0.5_fx));
  EXPECT_EQ(b.type, ShapeType2D::kPolygon);
  ASSERT_EQ(b.count, 4);
  EXPECT_EQ(b.vertices[0], Vec2(-2.0_fx, -0.5_fx));
  EXPECT_EQ(b.vertices[1], Vec2(2.0_fx, -0.5_fx));
  EXPECT_EQ(b.vertices[2], Vec2(2.0_fx, 0.5_fx));
  EXPECT_EQ(b.vertices[3], Vec2(-2.0_fx, 0.5_fx));
  EXPECT_EQ(b.normals[0], Vec2(0.0_fx, -1.0_fx));
  EXPECT_EQ(b.normals[1], Vec2(1.0_fx, 0.0_fx));
  EXPECT_EQ(b.normals[2], Vec2(0.0_fx, 1.0_fx));
  EXPECT_EQ(b.normals[3], Vec2(-1.0_fx, 0.0_fx));
  EXPECT_EQ(b.centroid, Vec2());
  EXPECT_EQ(b.vertices[4], Vec2());
  EXPECT_TRUE(validate_shape(b).ok());
  expect_refused(make_box(Fx(), 1.0_fx), "box half extents must be > 0");
  expect_refused(make_box(1.0_fx, -1.0_fx), "box half extents must be > 0");
}

TEST(Shape2DFactory, RotatedBoxKeepsItsCentre) {
  const Vec2 center(3.0_fx, -1.5_fx);
  const Shape2D b = ok(make_box(1.0_fx, 0.5_fx, center, Fx::half_pi()));
  ASSERT_EQ(b.count, 4);
  EXPECT_EQ(b.centroid, center);
  // A quarter turn maps (-hx, -hy) to (hy, -hx) about the centre.
  const Vec2 v0 = b.vertices[0] - center;
  EXPECT_LE(fixed::abs(v0.x - 0.5_fx).raw(), 2);
  EXPECT_LE(fixed::abs(v0.y + 1.0_fx).raw(), 2);
  // Edge 0 now faces +x.
  EXPECT_LE(fixed::abs(b.normals[0].x - 1.0_fx).raw(), 1);
  EXPECT_LE(fixed::abs(b.normals[0].y).raw(), 1);
  EXPECT_TRUE(validate_shape(b).ok());
}

TEST(Shape2DFactory, PolygonNormalsAndCentroid) {
  const Shape2D t = ok(polygon({{0.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}, {0.0_fx, 1.0_fx}}, 0.125_fx));
  ASSERT_EQ(t.count, 3);
  EXPECT_EQ(t.radius, 0.125_fx);
  EXPECT_EQ(t.normals[0], Vec2(0.0_fx, -1.0_fx));
  // 1/sqrt(2) = 46340.95 raw.
  EXPECT_EQ(t.normals[1], Vec2(Fx::from_raw(46341), Fx::from_raw(46341)));
  EXPECT_EQ(t.normals[2], Vec2(-1.0_fx, 0.0_fx));
  // (1/3, 1/3): 21845.33 raw.
  EXPECT_EQ(t.centroid, Vec2(Fx::from_raw(21845), Fx::from_raw(21845)));
  EXPECT_TRUE(validate_shape(t).ok());
}

TEST(Shape2DFactory, ClockwiseInputIsStoredCounterClockwise) {
  const Shape2D cw =
      ok(polygon({{0.0_fx, 0.0_fx}, {0.0_fx, 2.0_fx}, {2.0_fx, 2.0_fx}, {2.0_fx, 0.0_fx}}));
  const Shape2D ccw =
      ok(polygon({{0.0_fx, 0.0_fx}, {2.0_fx, 0.0_fx}, {2.0_fx, 2.0_fx}, {0.0_fx, 2.0_fx}}));
  EXPECT_EQ(cw, ccw);
  EXPECT_EQ(cw.vertices[0], Vec2(0.0_fx, 0.0_fx));  // point 0 stays first
  EXPECT_EQ(cw.vertices[1], Vec2(2.0_fx, 0.0_fx));
  EXPECT_EQ(cw.centroid, Vec2(1.0_fx, 1.0_fx));
}

TEST(Shape2DFactory, PolygonRefusals) {
  const Vec2 o(0.0_fx, 0.0_fx);
  expect_refused(polygon({o, {1.0_fx, 0.0_fx}}), "polygon needs at least 3 points, got 2");
  std::vector<Vec2> nine;
  for (int i = 0; i < 9; ++i) nine.push_back({Fx(i), Fx(i * i)});
  expect_refused(polygon(nine), "polygon takes at most 8 points, got 9");
  expect_refused(polygon({o, {1.0_fx, 0.0_fx}, {1.0_fx, 1.0_fx}, {1.0_fx, 0.0_fx}}),
                 "polygon points 1 and 3 repeat");
  expect_refused(polygon({o, {1.0_fx, 0.0_fx}, {2.0_fx, 0.0_fx}, {1.0_fx, 1.0_fx}}),
                 "polygon point 1 is collinear with its neighbours");
  // A dart: point 3 turns the wrong way.
  expect_refused(polygon({o, {2.0_fx, 1.0_fx}, {0.0_fx, 2.0_fx}, {1.0_fx, 1.0_fx}}),
                 "polygon is not convex: reflex corner at point 3");
  // A bow-tie encloses zero signed area.
  expect_refused(polygon({o, {1.0_fx, 1.0_fx}, {1.0_fx, 0.0_fx}, {0.0_fx, 1.0_fx}}),
                 "polygon outline crosses itself (zero signed area)");
  // A pentagram turns the same way at every point but winds twice.
  const Vec2 p[5] = {{0.0_fx, 10.0_fx},
                     {9.5106_fx, 3.0902_fx},
                     {5.8779_fx, -8.0902_fx},
                     {-5.8779_fx, -8.0902_fx},
                     {-9.5106_fx, 3.0902_fx}};
  expect_refused(polygon({p[0], p[2], p[4], p[1], p[3]}),
                 "polygon outline crosses itself: point 3 lies outside edge 0");
  // 2^-9 m legs: area 2^-19 m^2.
  const Fx tiny = Fx::from_raw(128);
  expect_refused(polygon({o, {tiny, Fx()}, {Fx(), tiny}}), "polygon area is below 2^-16 m^2");
  expect_refused(polygon({o, {1.0_fx, 0.0_fx}, {0.0_fx, 1.0_fx}}, -0.5_fx),
                 "polygon radius must be >= 0");
  expect_refused(polygon({{-30000.0_fx, 0.0_fx}, {30000.0_fx, 0.0_fx}, {0.0_fx, 1.0_fx}}),
                 "polygon edge 0 spans more than the coordinate range");
}

TEST(Shape2DValidate, RefusesHandBuiltFaults) {
  const Shape2D box = ok(make_box(1.0_fx, 1.0_fx));
  EXPECT_TRUE(validate_shape(box).ok());

  Shape2D cw = box;
  std::swap(cw.vertices[1], cw.vertices[3]);
  EXPECT_EQ(validate_shape(cw).message(), "polygon vertices must be counter-clockwise");

  Shape2D bent = box;
  bent.normals[2] = Vec2(0.0_fx, 0.5_fx);
  EXPECT_EQ(validate_shape(bent).message(), "shape normals do not match its vertices");

  Shape2D moved = box;
  moved.centroid = Vec2(0.25_fx, 0.0_fx);
  EXPECT_EQ(validate_shape(moved).message(), "shape centroid does not match its vertices");

  Shape2D padded = ok(make_circle(1.0_fx));
  padded.vertices[5] = Vec2(1.0_fx, 1.0_fx);
  EXPECT_EQ(validate_shape(padded).message(), "shape has non-zero unused fields");

  Shape2D flat = box;
  flat.radius = -1.0_fx;
  EXPECT_EQ(validate_shape(flat).message(), "polygon radius must be >= 0");

  Shape2D seg = ok(make_segment({0.0_fx, 0.0_fx}, {1.0_fx, 0.0_fx}));
  seg.radius = 0.5_fx;
  EXPECT_EQ(validate_shape(seg).message(), "segment radius must be 0");

  Shape2D bad_type = box;
  bad_type.type = static_cast<ShapeType2D>(9);
  EXPECT_EQ(validate_shape(bad_type).message(), "unknown shape type");

  Shape2D star = box;
  star.count = 9;
  EXPECT_EQ(validate_shape(star).message(), "polygon count must be 3..8");
}

}  // namespace
}  // namespace rwd::sim2d
