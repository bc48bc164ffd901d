// SPDX-License-Identifier: MIT
// Hull-sphere and hull-capsule manifolds. A box built by hand as a Hull
// must give what box-sphere and box-capsule give for the same poses (same
// normals, depths and points within 1e-5 m); a tetrahedron checks slanted
// and triangular faces against hand-computed values; and each routine
// gives the same bits when called twice.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "d3/gjk.h"
#include "d3/manifold.h"
#include "d3/manifold_hull.h"
#include "hull_round_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace hull_round_test;
TEST(HullTestHelper, BoxHullIsWellFormed) {
  const Hull h = make_box_hull({1.0f, 2.0f, 3.0f});
  ASSERT_EQ(h.faces.size(), 6u);
  ASSERT_EQ(h.edges.size(), 12u);
  const Vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  const float offsets[6] = {1, 1, 2, 2, 3, 3};
  for (int f = 0; f < 6; ++f) {
    EXPECT_EQ(h.faces[f].normal, normals[f]);
    EXPECT_EQ(h.faces[f].offset, offsets[f]);
  }
  for (const HullEdge& e : h.edges) EXPECT_NE(e.face_left, e.face_right);
}
// ---- Hull-sphere -------------------------------------------------------------

struct SphereCase {
  Vec3 center;
  float radius;
};

TEST(HullSphere, MatchesBoxSphereInEveryRegion) {
  const Vec3 half{0.5f, 0.75f, 1.0f};
  const Hull hull = make_box_hull(half);
  const Quat q = turn(Quat{0.1f, 0.3f, -0.2f, 0.9f});
  const Mat3 axes = mat3_from_quat(q);
  const Vec3 pos{1.0f, -2.0f, 0.5f};
  const BoxPose box{pos, q, half};
  // Local centres: over a face, beside an edge, beyond a corner, inside
  // near each face, and a few just within reach.
  const SphereCase cases[] = {
      {{0.0f, 0.0f, 1.2f}, 0.25f},                   // over +z: 0.05 overlap
      {{0.7f, 0.1f, -0.2f}, 0.25f},                  // beside +x: 0.05 apart (speculative)
      {{0.1f, -0.9f, 0.3f}, 0.2f},                   // under -y: 0.05 overlap
      {{0.6f, 0.85f, 0.2f}, 0.2f},                   // by the +x +y edge
      {{-0.6f, 0.3f, -1.1f}, 0.2f},                  // by the -x -z edge
      {{0.6f, -0.85f, 1.1f}, 0.3f},                  // beyond the (+, -, +) corner
      {{0.3f, 0.1f, 0.2f}, 0.1f},                    // inside, nearest +x
      {{-0.1f, 0.6f, -0.3f}, 0.1f},                  // inside, nearest +y
      {{0.05f, -0.1f, -0.85f}, 0.4f},                // inside, nearest -z
      {{0.0f, 0.0f, 1.0f + 0.25f + 0.015f}, 0.25f},  // 0.015 apart: kept
      {{0.0f, 0.0f, 1.0f + 0.25f + 0.03f}, 0.25f},   // 0.03 apart: dropped
      {{0.9f, 1.2f, 1.5f}, 0.25f},                   // far off the corner: dropped
  };
  int n = 0;
  for (const SphereCase& c : cases) {
    const Vec3 center = pos + axes * c.center;
    Manifold mh;
    Manifold mb;
    collide_hull_sphere(hull, pos, axes, center, c.radius, kSpec, mh);
    collide_box_sphere(box, center, c.radius, kSpec, mb);
    expect_same(mh, mb, "sphere", n);
    ++n;
  }
}

TEST(HullSphere, RandomPosesMatchBoxSphere) {
  test::Rng rng{31};
  int compared = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 half{rng.uniform(0.2f, 1.5f), rng.uniform(0.2f, 1.5f), rng.uniform(0.2f, 1.5f)};
    const Hull hull = make_box_hull(half);
    const Quat q = rng.rotation();
    const Mat3 axes = mat3_from_quat(q);
    const Vec3 pos{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    const Vec3 local{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    const float radius = rng.uniform(0.05f, 1.0f);
    // Skip what is ill-posed for a comparison: centres within 1 mm of the
    // surface (GJK's normal is rounding there; both fall back to faces
    // differently) and centres inside where two faces nearly tie.
    const Vec3 clamped = min(max(local, -half), half);
    const float outside = length(local - clamped);
    const Vec3 depth = half - abs(local);
    const float d0 = std::min(depth.x, std::min(depth.y, depth.z));
    const float d1 = depth.x + depth.y + depth.z - d0 -
                     std::max(depth.x, std::max(depth.y, depth.z));  // second smallest
    if (outside > 0.0f ? outside < 1e-3f : (d0 < 1e-3f || d1 - d0 < 1e-4f)) continue;
    const Vec3 center = pos + axes * local;
    Manifold mh;
    Manifold mb;
    collide_hull_sphere(hull, pos, axes, center, radius, kSpec, mh);
    collide_box_sphere(BoxPose{pos, q, half}, center, radius, kSpec, mb);
    expect_same(mh, mb, "random sphere", n);
    ++compared;
  }
  EXPECT_GT(compared, 1500);
}

TEST(HullSphere, FeatureIds) {
  const Hull hull = make_box_hull({1.0f, 1.0f, 1.0f});
  const Mat3 id;
  Manifold m;
  // Over the +y face (face 3), inside nearest -x (face 0).
  collide_hull_sphere(hull, {}, id, {0.2f, 1.3f, 0.1f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (1u << 16) | (3u << 8));
  collide_hull_sphere(hull, {}, id, {-0.8f, 0.1f, 0.3f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (1u << 16) | (0u << 8));
  // Beyond the edge between vertices 3 (+,+,-) and 7 (+,+,+).
  collide_hull_sphere(hull, {}, id, {1.2f, 1.2f, 0.1f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (2u << 16) | (7u << 8) | 3u);
  // Beyond vertex 5 (+,-,+), and the same id a little way off.
  collide_hull_sphere(hull, {}, id, {1.2f, -1.25f, 1.3f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (3u << 16) | 5u);
  collide_hull_sphere(hull, {}, id, {1.25f, -1.2f, 1.2f}, 0.5f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, (3u << 16) | 5u);
}

TEST(HullSphere, SlantedFace) {
  const Hull hull = make_tetra_hull();
  ASSERT_NEAR(hull.faces[3].normal.x, 1.0f / std::sqrt(3.0f), 1e-6f);
  const Mat3 id;
  const Vec3 n = Vec3{1.0f, 1.0f, 1.0f} * (1.0f / std::sqrt(3.0f));
  // The face's centre (1/3, 1/3, 1/3) less the centroid, 0.3 out, r 0.31.
  const Vec3 face_center = Vec3{1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f} - Vec3{0.25f, 0.25f, 0.25f};
  Manifold m;
  collide_hull_sphere(hull, {}, id, face_center + n * 0.3f, 0.31f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, -0.01f, kTol);
  EXPECT_NEAR(m.normal.x, n.x, kTol);
  EXPECT_NEAR(m.normal.y, n.y, kTol);
  EXPECT_NEAR(m.normal.z, n.z, kTol);
  EXPECT_NEAR(dot(m.points[0].point - face_center, n), -0.005f, kTol);
  EXPECT_EQ(m.points[0].feature_id, (1u << 16) | (3u << 8));
  // Centre 0.1 inside that face.
  collide_hull_sphere(hull, {}, id, face_center - n * 0.1f, 0.2f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, -0.3f, kTol);
  EXPECT_NEAR(m.normal.x, n.x, kTol);
  // Beyond vertex 1 along x: distance 0.5 from it.
  const Vec3 v1 = hull.vertices[1];
  collide_hull_sphere(hull, {}, id, v1 + Vec3{0.5f, 0.0f, 0.0f}, 0.49f, kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  EXPECT_NEAR(m.normal.x, 1.0f, kTol);
  EXPECT_EQ(m.points[0].feature_id, (3u << 16) | 1u);
}

// ---- Brute force on the tetrahedron --------------------------------------------

// The point of triangle abc nearest p (Ericson 5.1.5), in double.
struct D3 {
  double x, y, z;
};
D3 d3(Vec3 v) {
  return {v.x, v.y, v.z};
}
D3 operator-(D3 a, D3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
D3 operator+(D3 a, D3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
D3 operator*(D3 a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
double dotd(D3 a, D3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
D3 closest_on_triangle_d(D3 p, D3 a, D3 b, D3 c) {
  const D3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dotd(ab, ap), d2 = dotd(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const D3 bp = p - b;
  const double d3v = dotd(ab, bp), d4 = dotd(ac, bp);
  if (d3v >= 0 && d4 <= d3v) return b;
  const double vc = d1 * d4 - d3v * d2;
  if (vc <= 0 && d1 >= 0 && d3v <= 0) return a + ab * (d1 / (d1 - d3v));
  const D3 cp = p - c;
  const double d5 = dotd(ab, cp), d6 = dotd(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3v * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3v) >= 0 && (d5 - d6) >= 0) {
    return b + (c - b) * ((d4 - d3v) / ((d4 - d3v) + (d5 - d6)));
  }
  const double den = 1.0 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

// The hull point nearest p (p outside), by its faces.
D3 closest_on_hull_d(const Hull& h, D3 p) {
  D3 best{};
  double best_sq = 1e300;
  for (const HullFace& f : h.faces) {
    const D3 a = d3(h.vertices[h.face_vertices[f.first]]);
    for (uint32_t k = 1; k + 1 < f.count; ++k) {
      const D3 q = closest_on_triangle_d(p, a, d3(h.vertices[h.face_vertices[f.first + k]]),
                                         d3(h.vertices[h.face_vertices[f.first + k + 1]]));
      const double sq = dotd(q - p, q - p);
      if (sq < best_sq) {
        best_sq = sq;
        best = q;
      }
    }
  }
  return best;
}

TEST(HullSphere, RandomAroundATetrahedronMatchBruteForce) {
  const Hull hull = make_tetra_hull();
  const Quat q = turn(Quat{0.4f, -0.3f, 0.2f, 0.8f});
  const Mat3 axes = mat3_from_quat(q);
  const Vec3 pos{2.0f, -1.0f, 0.5f};
  test::Rng rng{5};
  int outside = 0;
  int inside = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 c{rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f)};
    const float r = rng.uniform(0.05f, 0.8f);
    float depth = 1e30f;  // least penetration over the faces, when inside
    for (const HullFace& f : hull.faces) depth = std::min(depth, f.offset - dot(f.normal, c));
    Manifold m;
    collide_hull_sphere(hull, pos, axes, pos + axes * c, r, kSpec, m);
    if (depth > 0.0f) {
      ASSERT_EQ(m.point_count, 1u) << n;
      EXPECT_NEAR(m.points[0].separation, -depth - r, kTol) << n;
      ++inside;
      continue;
    }
    const D3 qd = closest_on_hull_d(hull, d3(c));
    const D3 dv = d3(c) - qd;
    const double dist = std::sqrt(dotd(dv, dv));
    if (dist < 1e-3) continue;  // the surface: GJK's normal is rounding there
    if (dist - r > kSpec + 1e-5) {
      EXPECT_EQ(m.point_count, 0u) << n;
      continue;
    }
    if (dist - r < kSpec - 1e-5) {
      ASSERT_EQ(m.point_count, 1u) << n;
    }
    if (m.point_count == 0) continue;
    EXPECT_NEAR(m.points[0].separation, dist - r, kTol) << n;
    const Vec3 normal_local{static_cast<float>(dv.x / dist), static_cast<float>(dv.y / dist),
                            static_cast<float>(dv.z / dist)};
    const Vec3 expected = axes * normal_local;
    EXPECT_NEAR(m.normal.x, expected.x, 1e-4f) << n;
    EXPECT_NEAR(m.normal.y, expected.y, 1e-4f) << n;
    EXPECT_NEAR(m.normal.z, expected.z, 1e-4f) << n;
    ++outside;
  }
  EXPECT_GT(outside, 150);
  EXPECT_GT(inside, 20);
}

TEST(HullCapsule, RandomAroundATetrahedronMatchGjkAndEpa) {
  // The deepest point's separation against the segment's distance to the
  // hull (GJK, checked above against brute force) or, when the segment
  // reaches in, against EPA's depth: independent of the routine's own
  // face test and separating axes.
  const Hull hull = make_tetra_hull();
  const Quat q = turn(Quat{-0.1f, 0.5f, 0.3f, 0.7f});
  const Mat3 axes = mat3_from_quat(q);
  const Vec3 pos{-1.0f, 0.5f, 2.0f};
  test::Rng rng{6};
  int separated = 0;
  int reaching = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 c{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
    const Vec3 u = normalize_or_zero(
        Vec3{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)});
    const float hh = rng.uniform(0.05f, 0.6f);
    const float r = rng.uniform(0.05f, 0.5f);
    const Vec3 seg[2] = {c - u * hh, c + u * hh};
    ConvexProxy hp;
    hp.points = hull.vertices.data();
    hp.count = static_cast<uint32_t>(hull.vertices.size());
    ConvexProxy sp;
    sp.points = seg;
    sp.count = 2;
    const GjkOutput g = gjk_distance(hp, sp);
    Manifold m;
    collide_hull_capsule(hull, pos, axes, CapsulePose{pos + axes * c, axes * u, hh, r}, kSpec, m);
    float deepest = 1e30f;
    for (uint32_t i = 0; i < m.point_count; ++i)
      deepest = std::min(deepest, m.points[i].separation);
    if (!g.overlap && g.distance > 1e-3f) {
      if (g.distance - r > kSpec + 1e-5f) {
        EXPECT_EQ(m.point_count, 0u) << n;
        continue;
      }
      if (g.distance - r < kSpec - 1e-5f) {
        ASSERT_GT(m.point_count, 0u) << n;
      }
      if (m.point_count == 0) continue;
      EXPECT_NEAR(deepest, g.distance - r, kTol) << n;
      ++separated;
    } else if (g.overlap) {
      const EpaOutput e = epa_penetration(hp, sp, g.simplex);
      ASSERT_GT(m.point_count, 0u) << n;
      EXPECT_NEAR(deepest, -e.depth - r, 1e-4f) << n;
      const Vec3 expected = axes * e.normal;
      EXPECT_NEAR(m.normal.x, expected.x, 1e-3f) << n;
      EXPECT_NEAR(m.normal.y, expected.y, 1e-3f) << n;
      EXPECT_NEAR(m.normal.z, expected.z, 1e-3f) << n;
      ++reaching;
    }
  }
  EXPECT_GT(separated, 200);
  EXPECT_GT(reaching, 100);
}

TEST(HullSphere, SameBitsTwice) {
  const Hull hull = make_box_hull({0.5f, 0.7f, 0.9f});
  const Mat3 axes = mat3_from_quat(turn(Quat{0.3f, -0.1f, 0.2f, 0.8f}));
  const Vec3 centers[3] = {{0.9f, 0.8f, 0.1f}, {0.2f, 0.1f, 0.3f}, {1.0f, 0.1f, -0.2f}};
  for (const Vec3& c : centers) {
    Manifold m1;
    Manifold m2;
    collide_hull_sphere(hull, {0.1f, 0.2f, 0.3f}, axes, c, 0.4f, kSpec, m1);
    collide_hull_sphere(hull, {0.1f, 0.2f, 0.3f}, axes, c, 0.4f, kSpec, m2);
    EXPECT_GT(m1.point_count, 0u);
    expect_same_bits(m1, m2);
  }
}

}  // namespace
}  // namespace rwd::sim::d3
