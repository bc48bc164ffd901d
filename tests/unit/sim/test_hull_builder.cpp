// SPDX-License-Identifier: MIT
// The hull builder: topology (polygon faces, edges, Euler), planes, mass
// properties against closed forms (cube, turned box, tetrahedron, wedge,
// prisms, a dodecahedron), clouds reduced to their hull, every refusal,
// and bit-identical rebuilds. Tolerance 1e-5 (m, m^2, m^3) unless stated.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "d3/hull_builder.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

constexpr float kTol = 1e-5f;

std::vector<Vec3> box_points(Vec3 half, Vec3 center = {}, Quat rotation = {}) {
  std::vector<Vec3> out;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner{(i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                      (i & 4) ? half.z : -half.z};
    out.push_back(center + rotate(rotation, corner));
  }
  return out;
}

// A regular n-gon prism about the y axis: radius r, half height h.
std::vector<Vec3> prism_points(int n, float r, float h, Vec3 center = {}, Quat rotation = {}) {
  std::vector<Vec3> out;
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * 3.14159265358979323846 * i / n;
      const Vec3 p{r * static_cast<float>(std::cos(a)), side == 0 ? -h : h,
                   r * static_cast<float>(std::sin(a))};
      out.push_back(center + rotate(rotation, p));
    }
  }
  return out;
}

// The loop of face f.
std::vector<uint8_t> loop_of(const Hull& h, uint32_t f) {
  const HullFace& face = h.faces[f];
  return {h.face_vertices.begin() + face.first, h.face_vertices.begin() + face.first + face.count};
}

bool loop_runs(const Hull& h, uint32_t f, uint8_t from, uint8_t to) {
  const std::vector<uint8_t> loop = loop_of(h, f);
  for (size_t k = 0; k < loop.size(); ++k) {
    if (loop[k] == from && loop[(k + 1) % loop.size()] == to) return true;
  }
  return false;
}

// Every property hull.h promises, checked from scratch.
void expect_valid(const Hull& h) {
  const size_t v = h.vertices.size();
  ASSERT_GE(v, kHullMinVertices);
  ASSERT_LE(v, kHullMaxVertices);
  EXPECT_EQ(static_cast<int64_t>(v) - static_cast<int64_t>(h.edges.size()) +
                static_cast<int64_t>(h.faces.size()),
            2);
  EXPECT_EQ(h.face_vertices.size(), 2 * h.edges.size());
  EXPECT_NEAR(length_squared(h.frame.rotation), 1.0f, 1e-6f);
  uint32_t next_first = 0;
  for (uint32_t f = 0; f < h.faces.size(); ++f) {
    const HullFace& face = h.faces[f];
    EXPECT_EQ(face.first, next_first);
    next_first += face.count;
    ASSERT_GE(face.count, 3u);
    EXPECT_NEAR(length(face.normal), 1.0f, 1e-6f);
    const std::vector<uint8_t> loop = loop_of(h, f);
    for (size_t k = 0; k < loop.size(); ++k) {
      ASSERT_LT(loop[k], v);
      const Vec3 p = h.vertices[loop[k]];
      const Vec3 q = h.vertices[loop[(k + 1) % loop.size()]];
      const Vec3 r = h.vertices[loop[(k + 2) % loop.size()]];
      // On the plane, and turning left about the outward normal: convex.
      EXPECT_NEAR(dot(face.normal, p), face.offset, 1e-4f) << "face " << f;
      EXPECT_GT(dot(cross(q - p, r - q), face.normal), 0.0f) << "face " << f << " vertex " << k;
    }
    // Every vertex on or behind every plane; the plane touches the hull.
    float top = -1e30f;
    for (const Vec3& p : h.vertices) {
      EXPECT_LE(dot(face.normal, p), face.offset + 1e-6f) << "face " << f;
      top = std::max(top, dot(face.normal, p));
    }
    EXPECT_EQ(top, face.offset);
  }
  EXPECT_EQ(next_first, h.face_vertices.size());
  // Each edge once, its two faces running it opposite ways.
  for (size_t i = 0; i < h.edges.size(); ++i) {
    const HullEdge& e = h.edges[i];
    ASSERT_LT(e.face_left, h.faces.size());
    ASSERT_LT(e.face_right, h.faces.size());
    EXPECT_NE(e.face_left, e.face_right);
    EXPECT_TRUE(loop_runs(h, e.face_left, e.v0, e.v1)) << "edge " << i;
    EXPECT_TRUE(loop_runs(h, e.face_right, e.v1, e.v0)) << "edge " << i;
    for (size_t j = 0; j < i; ++j) {
      const HullEdge& o = h.edges[j];
      EXPECT_FALSE((o.v0 == e.v0 && o.v1 == e.v1) || (o.v0 == e.v1 && o.v1 == e.v0));
    }
  }
  // The mass frame: the centre of mass at the origin, bounds and extent.
  Vec3 half{};
  float extent = 0.0f;
  for (const Vec3& p : h.vertices) {
    half = max(half, abs(p));
    extent = std::max(extent, length(p));
  }
  EXPECT_EQ(half, h.half_size);
  EXPECT_EQ(extent, h.extent);
  EXPECT_GT(h.volume, 0.0f);
  EXPECT_GT(h.unit_inertia.x, 0.0f);
  EXPECT_GT(h.unit_inertia.y, 0.0f);
  EXPECT_GT(h.unit_inertia.z, 0.0f);
}

// How far an authored point lies outside the hull (negative inside).
float outside_distance(const Hull& h, Vec3 authored) {
  const Vec3 p = inv_rotate(h.frame.rotation, authored - h.frame.center);
  float d = -1e30f;
  for (const HullFace& f : h.faces) d = std::max(d, dot(f.normal, p) - f.offset);
  return d;
}

// The inertia per kg in the authored frame: R diag(I) R^T.
Mat3 authored_inertia(const Hull& h) {
  return rotate_diagonal(mat3_from_quat(h.frame.rotation), h.unit_inertia);
}

void expect_tensor_near(const Mat3& m, const float expected[3][3], float tol) {
  const Vec3 cols[3] = {m.c0, m.c1, m.c2};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(component(cols[j], i), expected[i][j], tol) << "row " << i << " column " << j;
    }
  }
}

// Builds the authored point of vertex i back from the mass frame.
Vec3 authored_vertex(const Hull& h, uint32_t i) {
  return rotate(h.frame.rotation, h.vertices[i]) + h.frame.center;
}

void append(std::vector<uint8_t>& bytes, const void* p, size_t n) {
  const auto* b = static_cast<const uint8_t*>(p);
  bytes.insert(bytes.end(), b, b + n);
}

// Every field, field by field (no padding bytes).
std::vector<uint8_t> hull_bytes(const Hull& h) {
  std::vector<uint8_t> out;
  for (const Vec3& v : h.vertices) append(out, &v, sizeof v);
  for (const HullFace& f : h.faces) {
    append(out, &f.normal, sizeof f.normal);
    append(out, &f.offset, sizeof f.offset);
    append(out, &f.first, sizeof f.first);
    append(out, &f.count, sizeof f.count);
  }
  append(out, h.face_vertices.data(), h.face_vertices.size());
  for (const HullEdge& e : h.edges) append(out, &e, sizeof e);
  append(out, &h.frame.center, sizeof h.frame.center);
  append(out, &h.frame.rotation, sizeof h.frame.rotation);
  append(out, &h.volume, sizeof h.volume);
  append(out, &h.unit_inertia, sizeof h.unit_inertia);
  append(out, &h.extent, sizeof h.extent);
  append(out, &h.half_size, sizeof h.half_size);
  return out;
}

TEST(HullBuilder, CubeHasSixQuadsAndTheBoxInertia) {
  const std::vector<Vec3> pts = box_points({1.0f, 1.0f, 1.0f});
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const Hull& h = *r;
  expect_valid(h);
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_EQ(h.faces.size(), 6u);
  EXPECT_EQ(h.edges.size(), 12u);
  for (const HullFace& f : h.faces) {
    EXPECT_EQ(f.count, 4u);
    EXPECT_NEAR(f.offset, 1.0f, kTol);
  }
  EXPECT_NEAR(h.volume, 8.0f, kTol);
  // Solid box: I = m/3 (b^2 + c^2) with half extents: 2/3 per kg.
  EXPECT_NEAR(h.unit_inertia.x, 2.0f / 3.0f, kTol);
  EXPECT_NEAR(h.unit_inertia.y, 2.0f / 3.0f, kTol);
  EXPECT_NEAR(h.unit_inertia.z, 2.0f / 3.0f, kTol);
  EXPECT_EQ(h.frame.rotation, Quat{});  // equal moments: no arbitrary turn
  EXPECT_NEAR(length(h.frame.center), 0.0f, kTol);
  for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(h.vertices[i], pts[i]);  // same order, same frame
  EXPECT_NEAR(h.extent, std::sqrt(3.0f), kTol);
  EXPECT_EQ(h.half_size, (Vec3{1.0f, 1.0f, 1.0f}));
}

TEST(HullBuilder, AxisAlignedBoxKeepsItsAxes) {
  Result<Hull> r = make_hull(box_points({0.5f, 1.0f, 2.0f}, {1.0f, 2.0f, 3.0f}));
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_EQ(r->frame.rotation, Quat{});
  EXPECT_NEAR(r->frame.center.x, 1.0f, kTol);
  EXPECT_NEAR(r->frame.center.y, 2.0f, kTol);
  EXPECT_NEAR(r->frame.center.z, 3.0f, kTol);
  EXPECT_NEAR(r->unit_inertia.x, (1.0f + 4.0f) / 3.0f, kTol);
  EXPECT_NEAR(r->unit_inertia.y, (0.25f + 4.0f) / 3.0f, kTol);
  EXPECT_NEAR(r->unit_inertia.z, (0.25f + 1.0f) / 3.0f, kTol);
  EXPECT_NEAR(r->half_size.x, 0.5f, kTol);
  EXPECT_NEAR(r->half_size.y, 1.0f, kTol);
  EXPECT_NEAR(r->half_size.z, 2.0f, kTol);
}

TEST(HullBuilder, TurnedAndMovedBoxRecoversItsFrame) {
  const Vec3 half{0.5f, 1.0f, 2.0f};
  const Vec3 center{3.0f, -2.0f, 5.0f};
  const Quat turn = normalize(Quat{0.3f, -0.5f, 0.2f, 0.8f});
  const std::vector<Vec3> pts = box_points(half, center, turn);
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const Hull& h = *r;
  expect_valid(h);
  EXPECT_EQ(h.faces.size(), 6u);
  EXPECT_EQ(h.edges.size(), 12u);
  EXPECT_NEAR(h.volume, 8.0f * 0.5f * 1.0f * 2.0f, 1e-4f);
  EXPECT_NEAR(h.frame.center.x, center.x, kTol);
  EXPECT_NEAR(h.frame.center.y, center.y, kTol);
  EXPECT_NEAR(h.frame.center.z, center.z, kTol);
  for (uint32_t i = 0; i < 8; ++i) {
    const Vec3 back = authored_vertex(h, i);
    EXPECT_NEAR(back.x, pts[i].x, kTol);
    EXPECT_NEAR(back.y, pts[i].y, kTol);
    EXPECT_NEAR(back.z, pts[i].z, kTol);
  }
  // Each principal axis is one of the box's axes, with that axis' moment.
  const Mat3 box_axes = mat3_from_quat(turn);
  const Mat3 axes = mat3_from_quat(h.frame.rotation);
  const Vec3 box_axis[3] = {box_axes.c0, box_axes.c1, box_axes.c2};
  const Vec3 axis[3] = {axes.c0, axes.c1, axes.c2};
  const float moment[3] = {(1.0f + 4.0f) / 3.0f, (0.25f + 4.0f) / 3.0f, (0.25f + 1.0f) / 3.0f};
  for (int k = 0; k < 3; ++k) {
    int match = -1;
    for (int j = 0; j < 3; ++j) {
      if (std::fabs(std::fabs(dot(axis[k], box_axis[j])) - 1.0f) < 1e-5f) match = j;
    }
    ASSERT_GE(match, 0) << "axis " << k;
    EXPECT_NEAR(component(h.unit_inertia, k), moment[match], kTol);
  }
  // And the tensor in the authored frame is the turned box's.
  const Mat3 expected = rotate_diagonal(box_axes, Vec3{moment[0], moment[1], moment[2]});
  const float e[3][3] = {{expected.c0.x, expected.c1.x, expected.c2.x},
                         {expected.c0.y, expected.c1.y, expected.c2.y},
                         {expected.c0.z, expected.c1.z, expected.c2.z}};
  expect_tensor_near(authored_inertia(h), e, kTol);
}

TEST(HullBuilder, TetrahedronVolumeCentroidAndInertia) {
  const std::vector<Vec3> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const Hull& h = *r;
  expect_valid(h);
  EXPECT_EQ(h.faces.size(), 4u);
  EXPECT_EQ(h.edges.size(), 6u);
  EXPECT_NEAR(h.volume, 1.0f / 6.0f, kTol);
  EXPECT_NEAR(h.frame.center.x, 0.25f, kTol);
  EXPECT_NEAR(h.frame.center.y, 0.25f, kTol);
  EXPECT_NEAR(h.frame.center.z, 0.25f, kTol);
  // About the centroid, per unit volume: integral x^2 = 1/60 and xy = 1/120
  // about the origin give var = 6/60 - 1/16 = 0.0375 and cov = 6/120 -
  // 1/16 = -0.0125; I = trace(cov) - cov. Moments 0.1 (along (1,1,1)) and
  // 0.0625 twice: a degenerate pair in a tensor that is not diagonal.
  const float e[3][3] = {
      {0.075f, 0.0125f, 0.0125f}, {0.0125f, 0.075f, 0.0125f}, {0.0125f, 0.0125f, 0.075f}};
  expect_tensor_near(authored_inertia(h), e, kTol);
  float sum = h.unit_inertia.x + h.unit_inertia.y + h.unit_inertia.z;
  EXPECT_NEAR(sum, 0.1f + 2.0f * 0.0625f, kTol);
}

TEST(HullBuilder, WedgeInertiaMatchesTheClosedForm) {
  // A right-triangle prism: legs a along x and b along y, length L along z.
  const float a = 2.0f;
  const float b = 1.0f;
  const float len = 3.0f;
  const std::vector<Vec3> pts = {{0, 0, 0},   {a, 0, 0},   {0, b, 0},
                                 {0, 0, len}, {a, 0, len}, {0, b, len}};
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const Hull& h = *r;
  expect_valid(h);
  EXPECT_EQ(h.faces.size(), 5u);
  EXPECT_EQ(h.edges.size(), 9u);
  EXPECT_NEAR(h.volume, a * b * len / 2.0f, kTol);
  EXPECT_NEAR(h.frame.center.x, a / 3.0f, kTol);
  EXPECT_NEAR(h.frame.center.y, b / 3.0f, kTol);
  EXPECT_NEAR(h.frame.center.z, len / 2.0f, kTol);
  // Per unit mass about the centroid, by hand: the triangle gives var_x =
  // a^2/18, var_y = b^2/18, cov_xy = -ab/36; the length var_z = L^2/12.
  const float vx = a * a / 18.0f;
  const float vy = b * b / 18.0f;
  const float vz = len * len / 12.0f;
  const float cxy = -a * b / 36.0f;
  const float e[3][3] = {{vy + vz, -cxy, 0.0f}, {-cxy, vx + vz, 0.0f}, {0.0f, 0.0f, vx + vy}};
  expect_tensor_near(authored_inertia(h), e, kTol);
  // The axis along the length stays the third axis; the other two turn.
  const Mat3 axes = mat3_from_quat(h.frame.rotation);
  EXPECT_NEAR(std::fabs(axes.c2.z), 1.0f, kTol);
}

TEST(HullBuilder, PrismCapsMergeIntoPolygons) {
  for (const Quat turn : {Quat{}, normalize(Quat{0.1f, 0.7f, -0.3f, 0.5f})}) {
    Result<Hull> r = make_hull(prism_points(16, 1.0f, 0.5f, {10.0f, 1.0f, -4.0f}, turn));
    ASSERT_TRUE(r.ok()) << r.status().message();
    const Hull& h = *r;
    expect_valid(h);
    EXPECT_EQ(h.vertices.size(), 32u);
    EXPECT_EQ(h.faces.size(), 18u);
    EXPECT_EQ(h.edges.size(), 48u);
    int caps = 0;
    for (const HullFace& f : h.faces) {
      if (f.count == 16)
        ++caps;
      else
        EXPECT_EQ(f.count, 4u);
    }
    EXPECT_EQ(caps, 2);
    // The two moments across the axis are equal (any regular polygon).
    const Mat3 axes = mat3_from_quat(h.frame.rotation);
    const Vec3 axis[3] = {axes.c0, axes.c1, axes.c2};
    const Vec3 along = rotate(turn, Vec3{0.0f, 1.0f, 0.0f});
    int k_along = -1;
    for (int k = 0; k < 3; ++k) {
      if (std::fabs(std::fabs(dot(axis[k], along)) - 1.0f) < 1e-4f) k_along = k;
    }
    ASSERT_GE(k_along, 0);
    const float across[2] = {component(h.unit_inertia, (k_along + 1) % 3),
                             component(h.unit_inertia, (k_along + 2) % 3)};
    EXPECT_NEAR(across[0], across[1], kTol);
  }
}

TEST(HullBuilder, TurnedDodecahedronHasTwelvePentagons) {
  // Irrational corners, turned and snapped to the 2^-20 m grid: the
  // pentagons are coplanar only to rounding, and must still merge. Its
  // inertia is isotropic, so the frame stays the identity.
  const float phi = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> pts = box_points({1.0f, 1.0f, 1.0f});
  for (float a : {-1.0f, 1.0f}) {
    for (float b : {-1.0f, 1.0f}) {
      pts.push_back({0.0f, a / phi, b * phi});
      pts.push_back({a / phi, b * phi, 0.0f});
      pts.push_back({a * phi, 0.0f, b / phi});
    }
  }
  const Quat turn = normalize(Quat{0.3f, -0.2f, 0.7f, 0.4f});
  for (Vec3& p : pts) {
    const Vec3 q = Vec3{12.5f, -3.0f, 100.0f} + rotate(turn, p);
    p = {std::round(q.x * 1048576.0f) / 1048576.0f, std::round(q.y * 1048576.0f) / 1048576.0f,
         std::round(q.z * 1048576.0f) / 1048576.0f};
  }
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_EQ(r->vertices.size(), 20u);
  EXPECT_EQ(r->faces.size(), 12u);
  EXPECT_EQ(r->edges.size(), 30u);
  for (const HullFace& f : r->faces) EXPECT_EQ(f.count, 5u);
  EXPECT_EQ(r->frame.rotation, Quat{});
  EXPECT_NEAR(r->unit_inertia.x, r->unit_inertia.y, kTol);
  EXPECT_NEAR(r->unit_inertia.x, r->unit_inertia.z, kTol);
}

TEST(HullBuilder, SixtyFourCornersAreTheLimit) {
  const std::vector<Vec3> pts = prism_points(32, 1.0f, 0.5f);
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_EQ(r->vertices.size(), 64u);
  EXPECT_EQ(r->faces.size(), 34u);
  std::vector<Vec3> more = pts;
  more.push_back({0.0f, 2.0f, 0.0f});
  Result<Hull> too_many = make_hull(more);
  ASSERT_FALSE(too_many.ok());
  EXPECT_EQ(too_many.status().code(), ErrorCode::kInvalidArgument);
}

TEST(HullBuilder, VeryLowConeKeepsExactFacesOnly) {
  // 40 points on a 1 m circle and an apex 30 um above it: the side
  // triangles lie within the merge band of each other, but merged they
  // would leave rim corners on two faces. The hull falls back to merging
  // exactly coplanar triangles: the base and 40 side triangles.
  std::vector<Vec3> pts = prism_points(40, 1.0f, 0.0f);
  pts.resize(40);
  pts.push_back({0.0f, 3e-5f, 0.0f});
  Result<Hull> r = make_hull(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_EQ(r->vertices.size(), 41u);
  EXPECT_EQ(r->faces.size(), 41u);
}

TEST(HullBuilder, CloudKeepsOnlyCorners) {
  // A box's corners among points inside it, on its faces and edges, and
  // near-duplicates of its corners.
  std::vector<Vec3> pts;
  test::Rng rng{7};
  for (int i = 0; i < 200; ++i) {
    pts.push_back({rng.uniform(-1, 1), rng.uniform(-0.5f, 0.5f), rng.uniform(-2, 2)});
  }
  for (const Vec3& c : box_points({1.0f, 0.5f, 2.0f})) {
    pts.push_back(c);
    pts.push_back(c * 0.99999f);  // within 1e-4 m: the same point
    pts.push_back({c.x, 0.0f, c.z});
    pts.push_back({c.x, c.y, 0.3f});
    pts.push_back({0.2f, c.y, 0.7f * c.z});
  }
  Result<Hull> r = hull_from_points(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_EQ(r->vertices.size(), 8u);
  EXPECT_EQ(r->faces.size(), 6u);
  EXPECT_NEAR(r->volume, 8.0f, 1e-4f);
  for (const Vec3& p : pts) EXPECT_LE(outside_distance(*r, p), kTol);
}

TEST(HullBuilder, SphereCloudEnclosesEveryPoint) {
  // 48 points on the unit sphere among 800 inside radius 0.5.
  test::Rng rng{12345};
  auto on_sphere = [&]() {
    while (true) {
      const Vec3 p{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
      const float l = length(p);
      if (l > 0.1f && l <= 1.0f) return p * (1.0f / l);
    }
  };
  std::vector<Vec3> pts;
  for (int i = 0; i < 848; ++i) {
    const Vec3 p = on_sphere();
    pts.push_back(i % 17 == 3 ? p : p * rng.uniform(0.0f, 0.5f));
  }
  Result<Hull> r = hull_from_points(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid(*r);
  EXPECT_LE(r->vertices.size(), 50u);
  EXPECT_GE(r->vertices.size(), 40u);
  for (const Vec3& p : pts) EXPECT_LE(outside_distance(*r, p), kTol);
  // Built again: the same bits.
  Result<Hull> again = hull_from_points(pts);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(hull_bytes(*r), hull_bytes(*again));
}

TEST(HullBuilder, DenseSphereIsReducedToSixtyFourPoints) {
  test::Rng rng{99};
  std::vector<Vec3> pts;
  while (pts.size() < 2000) {
    const Vec3 p{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const float l = length(p);
    if (l > 0.1f && l <= 1.0f) pts.push_back(p * (2.0f / l) + Vec3{5.0f, 0.0f, 0.0f});
  }
  Result<Hull> r = hull_from_points(pts);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const Hull& h = *r;
  expect_valid(h);
  EXPECT_LE(h.vertices.size(), 64u);
  EXPECT_GE(h.vertices.size(), 60u);
  // Every vertex is one of the points, and no point is far outside: the
  // farthest-first reduction keeps the hull close to the sphere.
  for (uint32_t i = 0; i < h.vertices.size(); ++i) {
    const Vec3 v = authored_vertex(h, i);
    float nearest = 1e30f;
    for (const Vec3& p : pts) nearest = std::min(nearest, length(p - v));
    EXPECT_LT(nearest, kTol);
  }
  float worst = 0.0f;
  for (const Vec3& p : pts) worst = std::max(worst, outside_distance(h, p));
  EXPECT_LT(worst, 0.2f);  // radius 2 m
}

TEST(HullBuilder, BuildingTwiceGivesTheSameBits) {
  const std::vector<Vec3> pts =
      prism_points(12, 0.7f, 1.3f, {-3.0f, 4.0f, 0.5f}, normalize(Quat{0.2f, 0.1f, 0.9f, 0.3f}));
  Result<Hull> a = make_hull(pts);
  Result<Hull> b = make_hull(pts);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(hull_bytes(*a), hull_bytes(*b));
}

void expect_refused(Result<Hull> r, const char* needle) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find(needle), std::string::npos) << r.status().message();
}

TEST(HullBuilder, MakeHullRefusals) {
  const std::vector<Vec3> cube = box_points({1.0f, 1.0f, 1.0f});
  auto with = [&](Vec3 extra) {
    std::vector<Vec3> p = cube;
    p.push_back(extra);
    return p;
  };
  expect_refused(make_hull(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), "4 to 64");
  expect_refused(make_hull(std::vector<Vec3>(65, Vec3{})), "4 to 64");
  std::vector<Vec3> bad = cube;
  bad[2].y = std::nanf("");
  expect_refused(make_hull(bad), "point 2");
  bad = cube;
  bad[5].z = INFINITY;
  expect_refused(make_hull(bad), "point 5");
  bad = cube;
  bad[3].x = 1000.5f;
  expect_refused(make_hull(bad), "point 3");
  expect_refused(make_hull(with({1.0f, 1.0f, 1.00005f})), "duplicates point 7");
  expect_refused(make_hull(std::vector<Vec3>{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}), "line");
  expect_refused(make_hull(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), "plane");
  // Interior, the middle of a face, the middle of an edge, and just off a
  // face (0.1 um: well within the tolerance).
  expect_refused(make_hull(with({0.1f, 0.2f, 0.3f})), "point 8");
  expect_refused(make_hull(with({0.0f, 0.0f, 1.0f})), "point 8");
  expect_refused(make_hull(with({1.0f, 0.0f, 1.0f})), "point 8");
  expect_refused(make_hull(with({0.25f, 0.5f, 1.0000001f})), "point 8");
  // A plate 0.12 mm thick: thinner than the 0.2 mm tolerance of a 20 m hull.
  expect_refused(make_hull(box_points({10.0f, 10.0f, 6e-5f})), "of a plane");
  // A tetrahedron of 0.5 mm legs: 2e-11 m^3.
  expect_refused(
      make_hull(std::vector<Vec3>{{0, 0, 0}, {5e-4f, 0, 0}, {0, 5e-4f, 0}, {0, 0, 5e-4f}}),
      "volume");
  // Not refused: a point 1 cm out of a face is a corner (a low pyramid).
  Result<Hull> pyramid = make_hull(with({0.0f, 0.0f, 1.01f}));
  ASSERT_TRUE(pyramid.ok()) << pyramid.status().message();
  expect_valid(*pyramid);
  EXPECT_EQ(pyramid->faces.size(), 9u);
}

TEST(HullBuilder, HullFromPointsRefusals) {
  expect_refused(hull_from_points(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), "4 to 4096");
  expect_refused(hull_from_points(std::vector<Vec3>(4097, Vec3{})), "4 to 4096");
  std::vector<Vec3> bad = box_points({1.0f, 1.0f, 1.0f});
  bad[6].x = std::nanf("");
  expect_refused(hull_from_points(bad), "point 6");
  expect_refused(hull_from_points(std::vector<Vec3>(10, Vec3{1, 2, 3})), "distinct");
  std::vector<Vec3> flat;
  test::Rng rng{3};
  for (int i = 0; i < 100; ++i) flat.push_back({rng.uniform(-1, 1), 0.5f, rng.uniform(-1, 1)});
  expect_refused(hull_from_points(flat), "plane");
  // Within the tolerance of a plane is no volume either.
  flat[17].y = 0.5f + 2e-6f;
  Result<Hull> thin = hull_from_points(flat);
  ASSERT_FALSE(thin.ok());
  EXPECT_EQ(thin.status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace rwd::sim::d3
