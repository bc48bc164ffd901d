// SPDX-License-Identifier: MIT
// Hull-hull manifolds (manifold_hull_sat.h): boxes given as hulls against
// collide_boxes (fixed poses and a SplitMix64 sweep), box-hull against
// hull-hull, hand-computed prism and tetrahedron contacts, role swaps,
// feature-id persistence, large faces (a 63-gon clipped by a 63-gon) and
// bit-identical repeats. The hulls are filled by hand here (the hull
// builder is separate); tolerance 1e-5 m unless stated.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "d3/hull.h"
#include "d3/manifold.h"
#include "d3/manifold_hull_sat.h"
#include "hull_sat_test_shapes.h"
#include "rewind/core/det_math.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace hull_sat_test;
// ---- Tests -----------------------------------------------------------------

TEST(ManifoldHullHull, HandHullsAndBoxHullAreWellFormed) {
  const Hull box = make_box({0.5f, 0.25f, 1.0f});
  expect_valid(hull_view(box), "box");
  const BoxHull stack_box = make_box_hull({0.5f, 0.25f, 1.0f});
  expect_valid(stack_box.view(), "BoxHull");
  const Hull prism = make_prism();
  expect_valid(hull_view(prism), "prism");
  const Hull tetra = make_tetrahedron();
  expect_valid(hull_view(tetra), "tetrahedron");
  const Hull ngon = make_ngon_prism(32, 0.5f, 0.2f);
  EXPECT_EQ(ngon.vertices.size(), kHullMaxVertices);
  expect_valid(hull_view(ngon), "32-gon prism");
  const Hull pyramid = make_pyramid(63, 1.0f, 0.8f);
  EXPECT_EQ(pyramid.vertices.size(), kHullMaxVertices);
  expect_valid(hull_view(pyramid), "63-gon pyramid");
  // The hand box and the stack box are the same data, edge for edge.
  const HullView v = stack_box.view();
  ASSERT_EQ(v.edge_count, box.edges.size());
  for (uint32_t e = 0; e < v.edge_count; ++e) {
    EXPECT_EQ(v.edges[e].v0, box.edges[e].v0);
    EXPECT_EQ(v.edges[e].v1, box.edges[e].v1);
    EXPECT_EQ(v.edges[e].face_left, box.edges[e].face_left);
    EXPECT_EQ(v.edges[e].face_right, box.edges[e].face_right);
  }
  for (uint32_t i = 0; i < 24; ++i) EXPECT_EQ(v.face_vertices[i], box.face_vertices[i]);
}

TEST(ManifoldHullHull, BoxesAsHullsMatchCollideBoxes) {
  for (const BoxCase& c : box_cases()) {
    SCOPED_TRACE(c.name);
    const Mat3 ra = axes(c.qa);
    const Mat3 rb = axes(c.qb);
    const Hull a = make_box(c.ha);
    const Hull b = make_box(c.hb);
    Manifold want;
    collide_boxes(c.ca, ra, c.ha, c.cb, rb, c.hb, kSpec, want);
    ASSERT_EQ(want.point_count, c.points);
    Manifold got;
    collide_hulls(a, c.ca, ra, b, c.cb, rb, kSpec, got);
    expect_same_contact(got, want, c.tol);
    // A pair that touches names no separating face.
    if (got.point_count > 0) {
      EXPECT_EQ(got.separating_axis, kNoSeparatingAxis);
    }
    EXPECT_EQ(is_edge_contact(got), is_edge_contact(want));
    // Box A through collide_box_hull: the same data, so the same bits.
    Manifold via_box;
    collide_box_hull(c.ca, ra, c.ha, b, c.cb, rb, kSpec, via_box);
    expect_same_bits(via_box, got);
    // Roles swapped, against collide_boxes swapped.
    Manifold want_swapped;
    collide_boxes(c.cb, rb, c.hb, c.ca, ra, c.ha, kSpec, want_swapped);
    Manifold got_swapped;
    collide_hulls(b, c.cb, rb, a, c.ca, ra, kSpec, got_swapped);
    expect_same_contact(got_swapped, want_swapped, c.tol);
  }
}

TEST(ManifoldHullHull, ResultsAreSpecified) {
  // The resting case in detail: four corners midway, ids naming A's +y face
  // (3) as reference and B's -y face (2) as incident, each incident vertex
  // as the two incident loop sides it joins.
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull box = make_box({0.5f, 0.5f, 0.5f});
  Manifold m;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, box, {0, 0.9f, 0}, Mat3{}, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  expect_near(m.normal, {0, 1, 0}, 0.0f);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.1f, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.45f, kTol);
    const uint32_t id = m.points[i].feature_id;
    EXPECT_EQ(id >> 16, (3u << 7) | 2u);
    const uint32_t in = (id >> 7) & 0x7Fu;
    const uint32_t out = id & 0x7Fu;
    EXPECT_EQ((in + 1) % 4, out);  // loop vertex `out` of the incident quad
  }
  // Ground above a tilted box: B's -y face (2) is the reference (bit 30),
  // the normal still from A up to B.
  const BoxCase under = box_cases()[3];
  collide_hulls(make_box(under.ha), under.ca, axes(under.qa), make_box(under.hb), under.cb,
                axes(under.qb), kSpec, m);
  ASSERT_EQ(m.point_count, 2u);
  expect_near(m.normal, {0, 1, 0}, kTol);
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_EQ(m.points[i].feature_id >> 23, (1u << 7) | 2u);
    EXPECT_NEAR(m.points[i].separation, -0.03f, kTol);
  }
  // The edge crossing: bit 31 and the two edges.
  const BoxCase c = box_cases()[4];
  collide_hulls(make_box(c.ha), c.ca, axes(c.qa), make_box(c.hb), c.cb, axes(c.qb), kSpec, m);
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id & 0xFFFF0000u, 0x80000000u);
  EXPECT_LT((m.points[0].feature_id >> 8) & 0xFFu, 12u);
  EXPECT_LT(m.points[0].feature_id & 0xFFu, 12u);
}

TEST(ManifoldHullHull, OctagonOverlapIsReducedToFourSpreadPoints) {
  // Equal boxes, the upper turned 45 degrees: eight candidates.
  const Hull box = make_box({0.5f, 0.5f, 0.5f});
  const Mat3 turned = axes(about({0, 1, 0}, 0.25f * kPi));
  Manifold m;
  collide_hulls(box, {0, 0, 0}, Mat3{}, box, {0, 0.95f, 0}, turned, kSpec, m);
  Manifold want;
  collide_boxes({0, 0, 0}, Mat3{}, {0.5f, 0.5f, 0.5f}, {0, 0.95f, 0}, turned, {0.5f, 0.5f, 0.5f},
                kSpec, want);
  ASSERT_EQ(m.point_count, 4u);
  expect_near(m.normal, want.normal, kTol);
  float min_x = 1, max_x = -1, min_z = 1, max_z = -1;
  for (uint32_t i = 0; i < 4; ++i) {
    const Vec3 p = m.points[i].point;
    EXPECT_NEAR(m.points[i].separation, -0.05f, kTol);
    EXPECT_NEAR(p.y, 0.475f, kTol);
    EXPECT_LE(std::fabs(p.x), 0.5f + 0.002f);
    EXPECT_LE(std::fabs(p.z), 0.5f + 0.002f);
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_z = std::min(min_z, p.z);
    max_z = std::max(max_z, p.z);
    for (uint32_t j = 0; j < i; ++j) EXPECT_NE(m.points[i].feature_id, m.points[j].feature_id);
  }
  EXPECT_GT(max_x - min_x, 0.5f);
  EXPECT_GT(max_z - min_z, 0.5f);
}

TEST(ManifoldHullHull, PrismOnItsSideRestsOnFourCorners) {
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull prism = make_prism();
  // Bottom face (y = -1 in the prism) 5 cm into the ground's top (y = 0.5).
  const Vec3 p{-0.3f, 1.45f, 0.2f};
  Manifold m;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, prism, p, Mat3{}, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  expect_near(m.normal, {0, 1, 0}, kTol);
  for (float x : {-1.0f, 2.0f}) {
    for (float z : {-0.5f, 0.5f}) {
      bool found = false;
      for (uint32_t i = 0; i < 4; ++i) {
        const Vec3 d = m.points[i].point - Vec3{p.x + x, 0.475f, p.z + z};
        if (std::fabs(d.x) < kTol && std::fabs(d.y) < kTol && std::fabs(d.z) < kTol) {
          found = true;
          EXPECT_NEAR(m.points[i].separation, -0.05f, kTol);
        }
      }
      EXPECT_TRUE(found) << x << " " << z;
    }
  }
  // collide_box_hull gives the same contact with the box as a BoxHull.
  Manifold via_box;
  collide_box_hull({0, 0, 0}, Mat3{}, {2, 0.5f, 2}, prism, p, Mat3{}, kSpec, via_box);
  expect_same_bits(via_box, m);
}

TEST(ManifoldHullHull, PrismOnAnEdgeTouchesAlongTheEdge) {
  // Turned 180 degrees about z: the edge through (-1, 2) is now the lowest,
  // at x = 1 relative to the prism, running along z. 3 cm deep.
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull prism = make_prism();
  const Vec3 p{0.0f, 2.47f, 0.0f};
  Manifold m;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, prism, p, kFlipZ, kSpec, m);
  ASSERT_EQ(m.point_count, 2u);
  expect_near(m.normal, {0, 1, 0}, kTol);
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.03f, kTol);
    EXPECT_NEAR(m.points[i].point.x, 1.0f, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.485f, kTol);
    EXPECT_NEAR(std::fabs(m.points[i].point.z), 0.5f, kTol);
  }
  EXPECT_NE(m.points[0].point.z, m.points[1].point.z);
}

TEST(ManifoldHullHull, TetrahedronFaceDownOnABox) {
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull tetra = make_tetrahedron();
  // Turn the tetrahedron so that its face opposite vertex 0 (normal
  // -(1,1,1)/sqrt 3) faces down: rows of the rotation are (t1, u, t2)
  // with u = (1,1,1)/sqrt 3 and t1 x u = t2.
  const float r3 = std::sqrt(3.0f);
  const Vec3 u{1 / r3, 1 / r3, 1 / r3};
  Vec3 b1;
  Vec3 b2;
  tangent_basis(u, b1, b2);  // u x b1 = b2, so (b2, u, b1) is right-handed
  const Vec3 t1 = b2;
  const Vec3 t2 = b1;
  const Mat3 r{{t1.x, u.x, t2.x}, {t1.y, u.y, t2.y}, {t1.z, u.z, t2.z}};
  const float depth = 0.04f;
  const Vec3 p{0.2f, 0.5f + 1 / r3 - depth, -0.1f};
  Manifold m;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, tetra, p, r, kSpec, m);
  ASSERT_EQ(m.point_count, 3u);
  expect_near(m.normal, {0, 1, 0}, kTol);
  for (uint32_t k = 1; k < 4; ++k) {
    // Reference is the ground: the triangle's corners themselves, midway.
    const Vec3 want = p + r * tetra.vertices[k] + Vec3{0, 0.5f * depth, 0};
    bool found = false;
    for (uint32_t i = 0; i < 3; ++i) {
      const Vec3 d = m.points[i].point - want;
      if (length(d) < 1e-4f) {
        found = true;
        EXPECT_NEAR(m.points[i].separation, -depth, kTol);
      }
    }
    EXPECT_TRUE(found) << k;
  }
  // Swapped, the tetrahedron's face is the reference (A's faces win ties):
  // the box face is clipped to the triangle pushed out by the 1 mm clip
  // margin, so the corners lie 1 mm / sin 30 deg = 2 mm beyond the
  // triangle's, along its bisectors.
  Manifold s;
  collide_hulls(tetra, p, r, ground, {0, 0, 0}, Mat3{}, kSpec, s);
  ASSERT_EQ(s.point_count, 3u);
  expect_near(s.normal, {0, -1, 0}, kTol);
  const Vec3 centre =
      p + r * ((tetra.vertices[1] + tetra.vertices[2] + tetra.vertices[3]) * (1.0f / 3.0f)) +
      Vec3{0, 0.5f * depth, 0};
  for (uint32_t k = 1; k < 4; ++k) {
    const Vec3 corner = p + r * tetra.vertices[k] + Vec3{0, 0.5f * depth, 0};
    const Vec3 want = corner + normalize_or_zero(corner - centre) * 0.002f;
    bool found = false;
    for (uint32_t i = 0; i < 3; ++i) {
      if (length(s.points[i].point - want) < 1e-4f) {
        found = true;
        EXPECT_NEAR(s.points[i].separation, -depth, kTol);
      }
    }
    EXPECT_TRUE(found) << k;
  }
}

TEST(ManifoldHullHull, TetrahedraCrossingEdgesGiveOnePoint) {
  // A's top edge runs from (-1,-1,1) to (1,1,1); B (the same tetrahedron
  // turned about z) has its bottom edge through (0, 0, -1) in its frame, so
  // the edges cross on the z axis, 3 cm deep.
  const Hull tetra = make_tetrahedron();
  for (float angle : {0.0f, 0.5f, -1.0f, 2.0f}) {
    SCOPED_TRACE(angle);
    const Mat3 rb = axes(about({0, 0, 1}, angle));
    Manifold m;
    collide_hulls(tetra, {0, 0, 0}, Mat3{}, tetra, {0, 0, 2 - 0.03f}, rb, kSpec, m);
    ASSERT_EQ(m.point_count, 1u);
    EXPECT_NE(m.points[0].feature_id & 0x80000000u, 0u);
    expect_near(m.normal, {0, 0, 1}, kTol);
    EXPECT_NEAR(m.points[0].separation, -0.03f, kTol);
    expect_near(m.points[0].point, {0, 0, 1 - 0.015f}, kTol);
    // Swapped: the same point, the normal flipped, the same depth.
    Manifold s;
    collide_hulls(tetra, {0, 0, 2 - 0.03f}, rb, tetra, {0, 0, 0}, Mat3{}, kSpec, s);
    ASSERT_EQ(s.point_count, 1u);
    expect_near(s.normal, {0, 0, -1}, kTol);
    EXPECT_NEAR(s.points[0].separation, -0.03f, kTol);
    expect_near(s.points[0].point, {0, 0, 1 - 0.015f}, kTol);
  }
  // 5 cm apart, beyond the speculative distance: nothing.
  Manifold far;
  collide_hulls(tetra, {0, 0, 0}, Mat3{}, tetra, {0, 0, 2.05f}, Mat3{}, kSpec, far);
  EXPECT_EQ(far.point_count, 0u);
}

TEST(ManifoldHullHull, SwappingRolesFlipsTheNormalAndKeepsTheDepth) {
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull box = make_box({0.5f, 0.3f, 0.4f});
  const Hull prism = make_prism();
  const Hull tetra = make_tetrahedron();
  struct Case {
    const char* name;
    const Hull* a;
    Vec3 pa;
    Quat qa;
    const Hull* b;
    Vec3 pb;
    Quat qb;
  };
  const Case cases[] = {
      {"prism on ground", &ground, {0, 0, 0}, Quat{}, &prism, {-0.3f, 1.45f, 0.2f}, Quat{}},
      {"turned prism on ground",
       &ground,
       {0, 0, 0},
       Quat{},
       &prism,
       {0.1f, 1.48f, 0},
       about({0, 1, 0}, 0.7f)},
      {"box under prism", &prism, {0, 0, 0}, Quat{}, &box, {0, -1.28f, 0}, about({0, 1, 0}, 0.3f)},
      {"tetra on box", &box, {0, 0, 0}, Quat{}, &tetra, {0.1f, 1.28f, 0.05f}, Quat{}},
      {"tilted box on tetra",
       &tetra,
       {0, 0, 0},
       Quat{},
       &box,
       {0.05f, 0.02f, 1.39f},
       about({1, 0, 0}, 0.05f)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Manifold m;
    Manifold s;
    collide_hulls(*c.a, c.pa, axes(c.qa), *c.b, c.pb, axes(c.qb), kSpec, m);
    collide_hulls(*c.b, c.pb, axes(c.qb), *c.a, c.pa, axes(c.qa), kSpec, s);
    ASSERT_GT(m.point_count, 0u);
    ASSERT_EQ(s.point_count, m.point_count);
    expect_near(s.normal, -m.normal, kTol);
    EXPECT_NEAR(min_separation(s), min_separation(m), kTol);
  }
}

TEST(ManifoldHullHull, FeatureIdsPersistAcrossSmallMotion) {
  const Hull ground = make_box({2, 0.5f, 2});
  const Hull prism = make_prism();
  Manifold frame1;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, prism, {0.1f, 1.49f, -0.2f},
                axes(about({0, 1, 0}, 0.1f)), kSpec, frame1);
  // Next step: slid 3 mm, turned a little more, sunk 1 mm.
  Manifold frame2;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, prism, {0.103f, 1.489f, -0.2f},
                axes(about({0, 1, 0}, 0.11f)), kSpec, frame2);
  ASSERT_EQ(frame1.point_count, 4u);
  ASSERT_EQ(frame2.point_count, 4u);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(frame1.points[i].feature_id, frame2.points[i].feature_id) << i;
    for (uint32_t j = 0; j < i; ++j) {
      EXPECT_NE(frame2.points[i].feature_id, frame2.points[j].feature_id);
    }
  }
  // A box half over the ground's edge: clipped points keep their ids too.
  const Hull box = make_box({0.5f, 0.5f, 0.5f});
  Manifold c1;
  Manifold c2;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, box, {1.8f, 0.99f, 0.3f}, axes(about({0, 1, 0}, 0.3f)),
                kSpec, c1);
  collide_hulls(ground, {0, 0, 0}, Mat3{}, box, {1.802f, 0.989f, 0.3f},
                axes(about({0, 1, 0}, 0.305f)), kSpec, c2);
  ASSERT_EQ(c1.point_count, 4u);
  ASSERT_EQ(c2.point_count, 4u);
  int clipped = 0;
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c1.points[i].feature_id, c2.points[i].feature_id) << i;
    const uint32_t in = (c1.points[i].feature_id >> 7) & 0x7Fu;
    const uint32_t out = c1.points[i].feature_id & 0x7Fu;
    if (in >= 64 || out >= 64) ++clipped;
  }
  EXPECT_EQ(clipped, 2);  // two corners overhang the +x side
}

TEST(ManifoldHullHull, LargeFacesClipWithinTheirBuffers) {
  // A 63-gon clipped by a 63-gon (base to base, one turned half a step):
  // a 126-gon of candidates, reduced to four well-spread points.
  const float h = 0.8f;
  const Hull pyramid = make_pyramid(63, 1.0f, h);
  const Mat3 rb = axes(about({0, 1, 0}, kPi / 63.0f));
  const float depth = 0.01f;
  Manifold m;
  collide_hulls(pyramid, {0, 0, 0}, kFlipX, pyramid, {0, 0.5f * h - depth, 0}, rb, kSpec, m);
  ASSERT_EQ(m.point_count, 4u);
  expect_near(m.normal, {0, 1, 0}, kTol);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -depth, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.25f * h - 0.5f * depth, kTol);
    EXPECT_LE(length(Vec3{m.points[i].point.x, 0, m.points[i].point.z}), 1.0f + 0.002f);
    for (uint32_t j = 0; j < i; ++j) {
      EXPECT_GT(length(m.points[i].point - m.points[j].point),
                1.0f);  // spread over the disc
    }
  }
  Manifold again;
  collide_hulls(pyramid, {0, 0, 0}, kFlipX, pyramid, {0, 0.5f * h - depth, 0}, rb, kSpec, again);
  expect_same_bits(again, m);

  // A 32-gon prism standing on a box: 32 candidates, four kept, the
  // deepest (it is tilted a little) among them.
  const Hull ngon = make_ngon_prism(32, 0.5f, 0.2f);
  const Hull ground = make_box({2, 0.5f, 2});
  Manifold n;
  collide_hulls(ground, {0, 0, 0}, Mat3{}, ngon, {0, 0.69f, 0}, axes(about({1, 0, 0}, 0.01f)),
                kSpec, n);
  ASSERT_EQ(n.point_count, 4u);
  // Rim vertices next to the deepest are within the reduction's 0.5 mm
  // depth tie of it.
  const float deepest = -0.01f - 0.5f * det_sin(0.01f);
  EXPECT_NEAR(min_separation(n), deepest, 0.0005f + 1e-5f);
}

TEST(ManifoldHullHull, SameInputsGiveTheSameBits) {
  const Hull prism = make_prism();
  const Hull tetra = make_tetrahedron();
  const Mat3 ra = axes(about({0.2f, 1, 0.3f}, 0.7f));
  const Mat3 rb = axes(about({1, 0.1f, -0.4f}, 2.1f));
  Manifold first;
  Manifold second;
  collide_hulls(prism, {0.1f, 0.2f, 0.3f}, ra, tetra, {0.9f, 1.1f, 0.4f}, rb, kSpec, first);
  collide_hulls(prism, {0.1f, 0.2f, 0.3f}, ra, tetra, {0.9f, 1.1f, 0.4f}, rb, kSpec, second);
  ASSERT_GT(first.point_count, 0u);
  expect_same_bits(first, second);
}

TEST(ManifoldHullHull, InvalidViewsCollideWithNothing) {
  const Hull box = make_box({0.5f, 0.5f, 0.5f});
  HullView empty;
  Manifold m;
  m.point_count = 3;
  collide_hulls(empty, {0, 0, 0}, Mat3{}, hull_view(box), {0, 0.5f, 0}, Mat3{}, kSpec, m);
  EXPECT_EQ(m.point_count, 0u);
  HullView too_many = hull_view(box);
  too_many.vertex_count = kHullMaxVertices + 1;
  collide_hulls(hull_view(box), {0, 0, 0}, Mat3{}, too_many, {0, 0.5f, 0}, Mat3{}, kSpec, m);
  EXPECT_EQ(m.point_count, 0u);
}

TEST(ManifoldHullHull, RandomBoxPosesAgreeWithCollideBoxes) {
  test::Rng rng{0x5A7C0FFEEull};
  int faces = 0;
  int edges = 0;
  int edges_compared = 0;
  int separated = 0;
  for (int i = 0; i < 4000; ++i) {
    SCOPED_TRACE(i);
    const Vec3 ha{rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f)};
    const Vec3 hb{rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f)};
    const Mat3 ra = axes(rng.rotation());
    const Mat3 rb = axes(rng.rotation());
    const Vec3 ca{rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)};
    const Vec3 dir =
        normalize_or_zero({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    const float reach = length(ha) + length(hb);
    const Vec3 cb = ca + dir * (reach * rng.uniform(0.2f, 1.0f));
    Manifold want;
    collide_boxes(ca, ra, ha, cb, rb, hb, kSpec, want);
    const BoxHull ba = make_box_hull(ha);
    const BoxHull bb = make_box_hull(hb);
    Manifold got;
    collide_hulls(ba.view(), ca, ra, bb.view(), cb, rb, kSpec, got);
    if (want.separating_axis != kNoSeparatingAxis) {
      ++separated;
      EXPECT_EQ(got.point_count, 0u);
      continue;
    }
    if (want.point_count == 0) continue;
    if (!is_edge_contact(want)) {
      // A face contact: the same face, depth and (up to the reduction's
      // 0.5 mm depth ties) points.
      ++faces;
      ASSERT_FALSE(is_edge_contact(got));
      ASSERT_EQ(got.point_count, want.point_count);
      expect_near(got.normal, want.normal, 1e-5f);
      if (want.point_count < 4) {
        expect_same_contact(got, want, 1e-4f);
      } else {
        EXPECT_NEAR(min_separation(got), min_separation(want), 0.0005f + 1e-5f);
      }
    } else {
      ++edges;
      if (is_edge_contact(got)) {
        ++edges_compared;
        expect_same_contact(got, want, 1e-4f);
      } else if (got.point_count > 0 && min_separation(got) <= 0.0f) {
        // A face here only by the relative bias: the edge was within 2% +
        // 1 mm of the face's depth (which is no shallower than any point).
        EXPECT_LE(want.points[0].separation, 0.98f * min_separation(got) + 0.001f + 1e-5f);
      }
    }
  }
  // The sweep covers every kind of outcome.
  EXPECT_GT(faces, 500);
  EXPECT_GT(edges_compared, 100);
  EXPECT_GT(separated, 200);
  std::printf("random boxes: %d face, %d edge (%d also edge here), %d separated\n", faces, edges,
              edges_compared, separated);
}

}  // namespace
}  // namespace rwd::sim::d3
