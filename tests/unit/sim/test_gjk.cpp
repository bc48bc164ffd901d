// SPDX-License-Identifier: MIT
// GJK, EPA and the shape cast on convex proxies: distances between points,
// spheres and boxes against hand-computed values (1e-5 m), box-box
// penetration against the separating axis test (1e-4), random point sets
// against a brute-force distance, and sweeps against analytic times of
// impact.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "d3/gjk.h"
#include "gjk_test_shapes.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace gjk_test;
// ---- GJK distance ----------------------------------------------------------

TEST(Gjk, PointToPoint) {
  const Vec3 pa{1.0f, 2.0f, 3.0f};
  const Vec3 zero{};
  const GjkOutput g = gjk_distance(proxy(&zero, 1, pa), proxy(&zero, 1, {4.0f, 6.0f, 3.0f}));
  EXPECT_FALSE(g.overlap);
  EXPECT_NEAR(g.distance, 5.0f, kTol);
  expect_vec(g.normal, {0.6f, 0.8f, 0.0f}, kTol);
  expect_vec(g.point_a, pa, kTol);
  expect_vec(g.point_b, {4.0f, 6.0f, 3.0f}, kTol);
}

TEST(Gjk, SpheresThroughProxies) {
  // Cores are the centres; the radii are the caller's: surfaces 0.25 apart.
  const Vec3 zero{};
  const ConvexProxy a = proxy(&zero, 1, {0.0f, 0.0f, 0.0f}, {}, 0.5f);
  const ConvexProxy b = proxy(&zero, 1, {0.0f, 0.0f, 1.5f}, {}, 0.75f);
  const GjkOutput g = gjk_distance(a, b);
  EXPECT_NEAR(g.distance - a.radius - b.radius, 0.25f, kTol);
  expect_vec(g.normal, {0.0f, 0.0f, 1.0f}, kTol);
}

TEST(Gjk, BoxesFaceEdgeAndCorner) {
  const BoxCorners big = corners({1.0f, 1.0f, 1.0f});
  const BoxCorners small = corners({0.5f, 0.5f, 0.5f});
  const ConvexProxy a = proxy(big.p, 8, {});
  // Face to face along x: 3 - 1 - 0.5.
  GjkOutput g = gjk_distance(a, proxy(small.p, 8, {3.0f, 0.2f, 0.1f}));
  EXPECT_NEAR(g.distance, 1.5f, kTol);
  expect_vec(g.normal, {1.0f, 0.0f, 0.0f}, kTol);
  EXPECT_NEAR(g.point_a.x, 1.0f, kTol);
  EXPECT_NEAR(g.point_b.x, 2.5f, kTol);
  // Corner to corner along the diagonal: (1,1,1) to (2.5,2.5,2.5).
  g = gjk_distance(a, proxy(small.p, 8, {3.0f, 3.0f, 3.0f}));
  EXPECT_NEAR(g.distance, 1.5f * std::sqrt(3.0f), kTol);
  expect_vec(g.point_a, {1.0f, 1.0f, 1.0f}, kTol);
  expect_vec(g.point_b, {2.5f, 2.5f, 2.5f}, kTol);
  // B turned 45 degrees about z: its vertical edge 0.3 from A's +x face.
  const float reach = 0.5f * std::sqrt(2.0f);
  g = gjk_distance(a, proxy(small.p, 8, {1.3f + reach, 0.1f, 0.0f}, kZ45));
  EXPECT_NEAR(g.distance, 0.3f, kTol);
  expect_vec(g.normal, {1.0f, 0.0f, 0.0f}, kTol);
  // Edge to edge: A turned 45 degrees about z puts its edge along z at
  // x = sqrt 2; B turned 45 degrees about y puts its edge along y at
  // x = 3 - reach; they cross at distance 3 - reach - sqrt 2.
  const Quat y45{0.0f, 0.38268343f, 0.0f, 0.92387953f};
  g = gjk_distance(proxy(big.p, 8, {}, kZ45), proxy(small.p, 8, {3.0f, 0.0f, 0.0f}, y45));
  EXPECT_NEAR(g.distance, 3.0f - reach - std::sqrt(2.0f), kTol);
  expect_vec(g.normal, {1.0f, 0.0f, 0.0f}, kTol);
}

TEST(Gjk, SameDistanceFarFromTheOrigin) {
  // Computed in A's frame: the distance is that of the relative pose.
  const BoxCorners big = corners({1.0f, 1.0f, 1.0f});
  const BoxCorners small = corners({0.5f, 0.5f, 0.5f});
  const Vec3 far{5000.0f, -3000.0f, 7000.0f};
  const GjkOutput g =
      gjk_distance(proxy(big.p, 8, far), proxy(small.p, 8, far + Vec3{0.2f, 1.8f, 0.3f}));
  EXPECT_NEAR(g.distance, 0.3f, 1e-3f);  // the world positions themselves round to 5e-4
  EXPECT_NEAR(g.normal.y, 1.0f, kTol);
}

TEST(Gjk, OverlapAndEpaForAPointInsideABox) {
  const BoxCorners box = corners({1.0f, 2.0f, 3.0f});
  const Vec3 zero{};
  const ConvexProxy a = proxy(box.p, 8, {});
  const ConvexProxy b = proxy(&zero, 1, {0.7f, 0.3f, -0.2f});
  const GjkOutput g = gjk_distance(a, b);
  ASSERT_TRUE(g.overlap);
  EXPECT_EQ(g.distance, 0.0f);
  const EpaOutput e = epa_penetration(a, b, g.simplex);
  EXPECT_TRUE(e.converged);
  EXPECT_NEAR(e.depth, 0.3f, 1e-4f);                // out through +x
  expect_vec(e.normal, {1.0f, 0.0f, 0.0f}, 1e-4f);  // B leaves through +x
  expect_vec(e.point_b, {0.7f, 0.3f, -0.2f}, 1e-4f);
  expect_vec(e.point_a, {1.0f, 0.3f, -0.2f}, 1e-4f);
}

// ---- EPA against the separating axis test ----------------------------------

struct Sat {
  float depth;
  Vec3 normal;  // from A to B
};

// Penetration of two boxes: the least overlap over the 15 axes.
Sat box_sat(Vec3 ca, Quat qa, Vec3 ha, Vec3 cb, Quat qb, Vec3 hb) {
  const Mat3 ra = mat3_from_quat(qa);
  const Mat3 rb = mat3_from_quat(qb);
  const Vec3 ua[3] = {ra.c0, ra.c1, ra.c2};
  const Vec3 ub[3] = {rb.c0, rb.c1, rb.c2};
  const float ea[3] = {ha.x, ha.y, ha.z};
  const float eb[3] = {hb.x, hb.y, hb.z};
  std::vector<Vec3> axes;
  for (int i = 0; i < 3; ++i) axes.push_back(ua[i]);
  for (int i = 0; i < 3; ++i) axes.push_back(ub[i]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 l = cross(ua[i], ub[j]);
      if (length_squared(l) > 1e-6f) axes.push_back(normalize_or_zero(l));
    }
  }
  const Vec3 d = cb - ca;
  Sat best{1e30f, {}};
  for (const Vec3& l : axes) {
    float r = 0.0f;
    for (int i = 0; i < 3; ++i)
      r += ea[i] * std::fabs(dot(ua[i], l)) + eb[i] * std::fabs(dot(ub[i], l));
    const float dl = dot(d, l);
    const float overlap = r - std::fabs(dl);
    if (overlap < best.depth) {
      best.depth = overlap;
      best.normal = dl >= 0.0f ? l : -l;
    }
  }
  return best;
}

EpaOutput box_epa(Vec3 ca, Quat qa, const BoxCorners& a, Vec3 cb, Quat qb, const BoxCorners& b,
                  bool& overlap) {
  const ConvexProxy pa = proxy(a.p, 8, ca, qa);
  const ConvexProxy pb = proxy(b.p, 8, cb, qb);
  const GjkOutput g = gjk_distance(pa, pb);
  overlap = g.overlap;
  return epa_penetration(pa, pb, g.simplex);
}

TEST(Epa, AxisAlignedBoxes) {
  const Vec3 ha{1.0f, 1.0f, 1.0f};
  const Vec3 hb{0.5f, 0.5f, 0.5f};
  const BoxCorners a = corners(ha);
  const BoxCorners b = corners(hb);
  bool overlap = false;
  const EpaOutput e = box_epa({}, {}, a, {1.3f, 0.1f, 0.2f}, {}, b, overlap);
  ASSERT_TRUE(overlap);
  EXPECT_TRUE(e.converged);
  EXPECT_NEAR(e.depth, 0.2f, 1e-4f);
  expect_vec(e.normal, {1.0f, 0.0f, 0.0f}, 1e-4f);
  // Witnesses: A's deepest point at x = 1, B's at x = 0.8.
  EXPECT_NEAR(e.point_a.x, 1.0f, 1e-4f);
  EXPECT_NEAR(e.point_b.x, 0.8f, 1e-4f);
  expect_vec(e.point_a, e.point_b + e.normal * e.depth, 1e-4f);
}

TEST(Epa, RotatedBoxesMatchTheSeparatingAxisTest) {
  test::Rng rng{12345};
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    const Vec3 ha{rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f)};
    const Vec3 hb{rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f), rng.uniform(0.3f, 1.5f)};
    const Quat qa = rng.rotation();
    const Quat qb = rng.rotation();
    const Vec3 ca{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
    const Vec3 cb =
        ca + Vec3{rng.uniform(-2.0f, 2.0f), rng.uniform(-2.0f, 2.0f), rng.uniform(-2.0f, 2.0f)};
    const Sat sat = box_sat(ca, qa, ha, cb, qb, hb);
    if (sat.depth < 1e-3f) continue;  // separated or grazing
    const BoxCorners a = corners(ha);
    const BoxCorners b = corners(hb);
    bool overlap = false;
    const EpaOutput e = box_epa(ca, qa, a, cb, qb, b, overlap);
    ASSERT_TRUE(overlap) << n;
    EXPECT_NEAR(e.depth, sat.depth, 1e-4f) << n;
    EXPECT_NEAR(length(e.normal), 1.0f, 1e-5f) << n;
    // Where two axes nearly tie the normal may be either; the depth may not.
    const Sat moved = box_sat(ca, qa, ha, cb + e.normal * (e.depth + 1e-3f), qb, hb);
    EXPECT_LT(moved.depth, 0.0f) << n;  // B moved by the depth along the normal is out
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(Epa, RotatedBoxesKnownAnswer) {
  // B turned 45 degrees about z, its vertical edge 0.15 into A's +x face.
  const BoxCorners a = corners({1.0f, 1.0f, 1.0f});
  const BoxCorners b = corners({0.5f, 0.5f, 0.5f});
  const float reach = 0.5f * std::sqrt(2.0f);
  bool overlap = false;
  EpaOutput e = box_epa({}, {}, a, {0.85f + reach, 0.1f, 0.0f}, kZ45, b, overlap);
  ASSERT_TRUE(overlap);
  EXPECT_NEAR(e.depth, 0.15f, 1e-4f);
  expect_vec(e.normal, {1.0f, 0.0f, 0.0f}, 1e-4f);
  // The same pair turned as a whole: depth unchanged, normal turned.
  const Quat q = normalize(Quat{0.2f, -0.4f, 0.1f, 0.9f});
  const Vec3 cb = rotate(q, Vec3{0.85f + reach, 0.1f, 0.0f});
  e = box_epa({}, q, a, cb, q * kZ45, b, overlap);
  ASSERT_TRUE(overlap);
  EXPECT_NEAR(e.depth, 0.15f, 1e-4f);
  expect_vec(e.normal, rotate(q, Vec3{1.0f, 0.0f, 0.0f}), 1e-4f);
}

TEST(Epa, FlatAndPointCoresFallBackToDepthZero) {
  // Two crossing segments: their difference is a flat parallelogram.
  const Vec3 sa[2] = {{-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  const Vec3 sb[2] = {{0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}};
  const ConvexProxy a = proxy(sa, 2, {});
  const ConvexProxy b = proxy(sb, 2, {0.2f, 0.0f, 0.1f});
  const GjkOutput g = gjk_distance(a, b);
  ASSERT_TRUE(g.overlap);
  EpaOutput e = epa_penetration(a, b, g.simplex);
  EXPECT_EQ(e.depth, 0.0f);
  EXPECT_NEAR(std::fabs(e.normal.y), 1.0f, 1e-5f);
  // Coincident points.
  const Vec3 zero{};
  const ConvexProxy p = proxy(&zero, 1, {1.0f, 2.0f, 3.0f});
  e = epa_penetration(p, p, gjk_distance(p, p).simplex);
  EXPECT_EQ(e.depth, 0.0f);
  EXPECT_FALSE(e.converged);
  EXPECT_NEAR(length(e.normal), 1.0f, 1e-5f);
}

TEST(Epa, TouchingBoxesHaveDepthNearZero) {
  // Face to face with no gap: GJK sees distance 0 (or a hair more); EPA
  // from there finds depth 0 along the faces' normal.
  const BoxCorners a = corners({1.0f, 1.0f, 1.0f});
  const ConvexProxy pa = proxy(a.p, 8, {});
  const ConvexProxy pb = proxy(a.p, 8, {0.5f, 2.0f, 0.25f});
  const GjkOutput g = gjk_distance(pa, pb);
  if (!g.overlap) {
    EXPECT_LT(g.distance, 1e-5f);
    return;
  }
  const EpaOutput e = epa_penetration(pa, pb, g.simplex);
  EXPECT_NEAR(e.depth, 0.0f, 1e-5f);
  expect_vec(e.normal, {0.0f, 1.0f, 0.0f}, 1e-4f);
}

// ---- Random point sets against brute force ----------------------------------

double dot_d(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Squared distance from p to triangle abc (Ericson 5.1.5 in double).
double point_triangle_sq(const double p[3], const double a[3], const double b[3],
                         const double c[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; ++i) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
    bp[i] = p[i] - b[i];
    cp[i] = p[i] - c[i];
  }
  auto dist_sq = [&](double u, double v, double w) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double q = a[i] * u + b[i] * v + c[i] * w - p[i];
      s += q * q;
    }
    return s;
  };
  const double d1 = dot_d(ab, ap), d2 = dot_d(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dist_sq(1, 0, 0);
  const double d3 = dot_d(ab, bp), d4 = dot_d(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist_sq(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return dist_sq(1 - v, v, 0);
  }
  const double d5 = dot_d(ab, cp), d6 = dot_d(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist_sq(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return dist_sq(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist_sq(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  return dist_sq(1 - vb * denom - vc * denom, vb * denom, vc * denom);
}

// Squared distance between segments p0p1 and q0q1 (sampled finely plus
// the endpoint-to-segment distances: exact enough for a check at 1e-5).
double segment_segment_sq(const double p0[3], const double p1[3], const double q0[3],
                          const double q1[3]) {
  double d[3], e[3], r[3];
  for (int i = 0; i < 3; ++i) {
    d[i] = p1[i] - p0[i];
    e[i] = q1[i] - q0[i];
    r[i] = p0[i] - q0[i];
  }
  const double a = dot_d(d, d), b = dot_d(d, e), c = dot_d(e, e), f = dot_d(e, r), g = dot_d(d, r);
  auto clamp01 = [](double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); };
  double s = 0, t = 0;
  const double denom = a * c - b * b;
  s = denom > 1e-18 ? clamp01((b * f - g * c) / denom) : 0.0;
  t = (b * s + f) / c;
  if (t < 0) {
    t = 0;
    s = clamp01(-g / a);
  } else if (t > 1) {
    t = 1;
    s = clamp01((b - g) / a);
  }
  double sq = 0;
  for (int i = 0; i < 3; ++i) {
    const double x = p0[i] + d[i] * s - (q0[i] + e[i] * t);
    sq += x * x;
  }
  return sq;
}

// Distance between the convex hulls of two disjoint point sets: the closest
// pair lies on a vertex-triangle or segment-segment pair of the points.
double brute_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  auto d3 = [](Vec3 v, double out[3]) {
    out[0] = v.x;
    out[1] = v.y;
    out[2] = v.z;
  };
  std::vector<std::array<double, 3>> pa(a.size()), pb(b.size());
  for (size_t i = 0; i < a.size(); ++i) d3(a[i], pa[i].data());
  for (size_t i = 0; i < b.size(); ++i) d3(b[i], pb[i].data());
  double best = 1e300;
  auto tri = [&](const std::vector<std::array<double, 3>>& pts,
                 const std::vector<std::array<double, 3>>& other) {
    const size_t n = pts.size();
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i; j < n; ++j)
        for (size_t k = j; k < n; ++k)
          for (const auto& p : other) {
            best = std::min(
                best, point_triangle_sq(p.data(), pts[i].data(), pts[j].data(), pts[k].data()));
          }
  };
  tri(pa, pb);
  tri(pb, pa);
  for (size_t i = 0; i < pa.size(); ++i)
    for (size_t j = i + 1; j < pa.size(); ++j)
      for (size_t k = 0; k < pb.size(); ++k)
        for (size_t l = k + 1; l < pb.size(); ++l) {
          best = std::min(
              best, segment_segment_sq(pa[i].data(), pa[j].data(), pb[k].data(), pb[l].data()));
        }
  return std::sqrt(best);
}

TEST(Gjk, RandomPointSetsMatchBruteForce) {
  test::Rng rng{2024};
  test::Rng dirs{7};  // its own sequence, so each case's shapes do not depend on the others
  int separated = 0;
  int overlapping = 0;
  for (int n = 0; n < 1000; ++n) {
    const uint32_t na = 1 + static_cast<uint32_t>(rng.next() % 10);
    const uint32_t nb = 1 + static_cast<uint32_t>(rng.next() % 10);
    std::vector<Vec3> la(na), lb(nb);
    for (Vec3& p : la) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    for (Vec3& p : lb) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const Vec3 pos_a{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    const Vec3 pos_b =
        pos_a + Vec3{rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f)};
    const ConvexProxy a = proxy(la.data(), na, pos_a, rng.rotation());
    const ConvexProxy b = proxy(lb.data(), nb, pos_b, rng.rotation());
    std::vector<Vec3> wa(na), wb(nb);
    for (uint32_t i = 0; i < na; ++i) wa[i] = a.position + a.axes * la[i];
    for (uint32_t i = 0; i < nb; ++i) wb[i] = b.position + b.axes * lb[i];
    const GjkOutput g = gjk_distance(a, b);
    if (g.overlap) {
      // The certificate: the simplex's weights make one point of both hulls
      // (the brute force below only holds for disjoint hulls).
      float sum = 0.0f;
      Vec3 w;
      for (uint32_t i = 0; i < g.simplex.count; ++i) {
        EXPECT_GE(g.simplex.v[i].weight, -1e-6f) << n;
        sum += g.simplex.v[i].weight;
        w += g.simplex.v[i].w * g.simplex.v[i].weight;
      }
      EXPECT_NEAR(sum, 1.0f, 1e-5f) << n;
      EXPECT_LE(length(w), 1e-5f) << n;
      EXPECT_LE(length(g.point_b - g.point_a), 1e-5f) << n;
      // EPA: moving B by the depth along the normal separates the cores,
      // and no direction tried separates them with less.
      const EpaOutput e = epa_penetration(a, b, g.simplex);
      EXPECT_NEAR(length(e.normal), 1.0f, 1e-5f) << n;
      ConvexProxy moved = b;
      moved.position = b.position + e.normal * (e.depth + 1e-3f);
      const GjkOutput after = gjk_distance(a, moved);
      EXPECT_NEAR(after.distance, 1e-3f, 2e-4f) << n;
      for (int k = 0; k < 64; ++k) {
        const Vec3 d =
            normalize_or_zero(Vec3{dirs.uniform(-1, 1), dirs.uniform(-1, 1), dirs.uniform(-1, 1)});
        float max_a = -1e30f, min_b = 1e30f;
        for (const Vec3& p : wa) max_a = std::max(max_a, dot(p, d));
        for (const Vec3& p : wb) min_b = std::min(min_b, dot(p, d));
        EXPECT_LE(e.depth, max_a - min_b + 1e-4f) << n;
      }
      ++overlapping;
      continue;
    }
    const double brute = brute_distance(wa, wb);
    EXPECT_NEAR(g.distance, brute, 1e-5 * (1.0 + brute)) << n;
    EXPECT_NEAR(length(g.normal), 1.0f, 1e-5f) << n;
    EXPECT_NEAR(dot(g.normal, g.point_b - g.point_a), g.distance, 1e-4f) << n;
    // The normal separates: A's extent along it ends where B's begins.
    float max_a = -1e30f, min_b = 1e30f;
    for (const Vec3& p : wa) max_a = std::max(max_a, dot(p, g.normal));
    for (const Vec3& p : wb) min_b = std::min(min_b, dot(p, g.normal));
    EXPECT_NEAR(min_b - max_a, g.distance, 1e-4f) << n;
    ++separated;
  }
  EXPECT_GT(separated, 300);
  EXPECT_GT(overlapping, 100);
}

TEST(Gjk, WarmStartGivesTheSameAnswer) {
  test::Rng rng{77};
  for (int n = 0; n < 100; ++n) {
    std::vector<Vec3> la(8), lb(8);
    for (Vec3& p : la) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    for (Vec3& p : lb) p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const ConvexProxy a = proxy(la.data(), 8, {}, rng.rotation());
    // One draw per statement: the order of a call's arguments is unspecified.
    const Vec3 pos_b{3.0f, rng.uniform(-1, 1), 0.0f};
    ConvexProxy b = proxy(lb.data(), 8, pos_b, rng.rotation());
    GjkCache cache;
    gjk_distance(a, b, &cache);  // fills the cache
    EXPECT_GE(cache.count, 1u);
    b.position.x += 0.01f;  // a small move, as from one step to the next
    const GjkOutput ref = gjk_distance(a, b);
    const GjkOutput warm = gjk_distance(a, b, &cache);
    EXPECT_NEAR(warm.distance, ref.distance, 1e-5f) << n;
    EXPECT_LE(warm.iterations, ref.iterations + 1) << n;
  }
}

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}
bool same_bits(Vec3 a, Vec3 b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

TEST(Gjk, SameBitsTwice) {
  const BoxCorners a = corners({1.0f, 0.5f, 0.7f});
  const ConvexProxy pa = proxy(a.p, 8, {0.1f, 0.2f, 0.3f}, normalize(Quat{0.1f, 0.2f, 0.3f, 0.9f}));
  const ConvexProxy pb =
      proxy(a.p, 8, {1.5f, 1.2f, -0.3f}, normalize(Quat{-0.3f, 0.2f, 0.1f, 0.8f}));
  const GjkOutput g1 = gjk_distance(pa, pb);
  const GjkOutput g2 = gjk_distance(pa, pb);
  ASSERT_TRUE(g1.overlap);
  EXPECT_EQ(g1.overlap, g2.overlap);
  EXPECT_TRUE(same_bits(g1.point_a, g2.point_a) && same_bits(g1.point_b, g2.point_b));
  ASSERT_EQ(g1.simplex.count, g2.simplex.count);
  for (uint32_t i = 0; i < g1.simplex.count; ++i) {
    EXPECT_TRUE(same_bits(g1.simplex.v[i].w, g2.simplex.v[i].w));
    EXPECT_TRUE(same_bits(g1.simplex.v[i].weight, g2.simplex.v[i].weight));
  }
  const EpaOutput e1 = epa_penetration(pa, pb, g1.simplex);
  const EpaOutput e2 = epa_penetration(pa, pb, g2.simplex);
  EXPECT_TRUE(same_bits(e1.normal, e2.normal) && same_bits(e1.depth, e2.depth));
  EXPECT_TRUE(same_bits(e1.point_a, e2.point_a) && same_bits(e1.point_b, e2.point_b));
  // Separated: the distance, normal and points.
  ConvexProxy far = pb;
  far.position = {4.0f, 1.0f, 0.5f};
  const GjkOutput s1 = gjk_distance(pa, far);
  const GjkOutput s2 = gjk_distance(pa, far);
  ASSERT_FALSE(s1.overlap);
  EXPECT_TRUE(same_bits(s1.distance, s2.distance) && same_bits(s1.normal, s2.normal));
  EXPECT_TRUE(same_bits(s1.point_a, s2.point_a) && same_bits(s1.point_b, s2.point_b));
  const ShapeCastOutput c1 = shape_cast(pa, far, {-4.0f, -1.0f, 0.0f}, 1.0f);
  const ShapeCastOutput c2 = shape_cast(pa, far, {-4.0f, -1.0f, 0.0f}, 1.0f);
  ASSERT_TRUE(c1.hit);
  EXPECT_TRUE(same_bits(c1.fraction, c2.fraction) && same_bits(c1.normal, c2.normal));
  EXPECT_TRUE(same_bits(c1.point, c2.point));
}

}  // namespace
}  // namespace rwd::sim::d3
