// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the test_manifold_hull_round* tests.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>
#include "d3/gjk.h"
#include "d3/manifold.h"
#include "d3/manifold_hull.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3::hull_round_test {

constexpr float kTol = 1e-5f;
constexpr float kSpec = 0.02f;

// A hull from its vertices and its faces' vertex loops (counter-clockwise
// seen from outside): planes from the loops, edges listed once with the
// face whose loop runs v0 -> v1 on the left. Built by hand so these tests
// check the manifold routines apart from the hull builder.
inline Hull make_hull(const std::vector<Vec3>& vertices,
                      const std::vector<std::vector<uint8_t>>& loops) {
  Hull h;
  h.vertices = vertices;
  for (uint32_t f = 0; f < loops.size(); ++f) {
    const auto& loop = loops[f];
    HullFace face;
    face.first = static_cast<uint16_t>(h.face_vertices.size());
    face.count = static_cast<uint8_t>(loop.size());
    const Vec3 a = vertices[loop[0]];
    face.normal = normalize_or_zero(cross(vertices[loop[1]] - a, vertices[loop[2]] - a));
    face.offset = dot(face.normal, a);
    h.faces.push_back(face);
    for (size_t k = 0; k < loop.size(); ++k) {
      const uint8_t v0 = loop[k];
      const uint8_t v1 = loop[(k + 1) % loop.size()];
      h.face_vertices.push_back(v0);
      bool found = false;
      for (HullEdge& e : h.edges) {
        if (e.v0 == v1 && e.v1 == v0) {
          e.face_right = static_cast<uint8_t>(f);
          found = true;
        }
      }
      if (!found) h.edges.push_back(HullEdge{v0, v1, static_cast<uint8_t>(f), 0});
    }
  }
  for (const Vec3& v : vertices) h.extent = std::max(h.extent, length(v));
  return h;
}

// A box: vertex i at (+-x, +-y, +-z) by bits 0, 1, 2; faces in box-sphere's
// order (axis * 2 + positive): -x, +x, -y, +y, -z, +z.
inline Hull make_box_hull(Vec3 half) {
  std::vector<Vec3> v(8);
  for (int i = 0; i < 8; ++i) {
    v[i] = {(i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y, (i & 4) ? half.z : -half.z};
  }
  Hull h = make_hull(
      v, {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}});
  h.half_size = half;
  return h;
}

inline Quat turn(Quat q) {
  return normalize(q);
}

inline void expect_same(const Manifold& hull, const Manifold& box, const char* what, int n) {
  ASSERT_EQ(hull.point_count, box.point_count) << what << " " << n;
  if (box.point_count == 0) return;
  EXPECT_NEAR(hull.normal.x, box.normal.x, kTol) << what << " " << n;
  EXPECT_NEAR(hull.normal.y, box.normal.y, kTol) << what << " " << n;
  EXPECT_NEAR(hull.normal.z, box.normal.z, kTol) << what << " " << n;
  for (uint32_t i = 0; i < box.point_count; ++i) {
    EXPECT_NEAR(hull.points[i].separation, box.points[i].separation, kTol) << what << " " << n;
    EXPECT_NEAR(hull.points[i].point.x, box.points[i].point.x, kTol) << what << " " << n;
    EXPECT_NEAR(hull.points[i].point.y, box.points[i].point.y, kTol) << what << " " << n;
    EXPECT_NEAR(hull.points[i].point.z, box.points[i].point.z, kTol) << what << " " << n;
  }
}

inline bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}
inline bool same_bits(Vec3 a, Vec3 b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
inline void expect_same_bits(const Manifold& a, const Manifold& b) {
  ASSERT_EQ(a.point_count, b.point_count);
  EXPECT_TRUE(same_bits(a.normal, b.normal));
  for (uint32_t i = 0; i < a.point_count; ++i) {
    EXPECT_TRUE(same_bits(a.points[i].point, b.points[i].point));
    EXPECT_TRUE(same_bits(a.points[i].separation, b.points[i].separation));
    EXPECT_EQ(a.points[i].feature_id, b.points[i].feature_id);
  }
}

// A tetrahedron about its centroid: a slanted triangular face.
inline Hull make_tetra_hull() {
  const Vec3 c{0.25f, 0.25f, 0.25f};
  const std::vector<Vec3> v = {Vec3{0, 0, 0} - c, Vec3{1, 0, 0} - c, Vec3{0, 1, 0} - c,
                               Vec3{0, 0, 1} - c};
  // Face 3 is the slanted one, normal (1, 1, 1) / sqrt 3.
  return make_hull(v, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

}  // namespace rwd::sim::d3::hull_round_test
