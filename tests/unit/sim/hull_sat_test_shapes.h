// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the test_manifold_hull_hull* tests.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>
#include "d3/hull.h"
#include "d3/manifold.h"
#include "d3/manifold_hull_sat.h"
#include "rewind/core/det_math.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3::hull_sat_test {

constexpr float kTol = 1e-5f;
constexpr float kSpec = 0.02f;

// ---- Hulls by hand ---------------------------------------------------------

// Lists each edge once from the face loops: a loop step p -> q with p < q is
// edge (p, q) with that face on its left; the face whose loop steps q -> p
// is on its right. Same order as BoxHull's table (faces, then loop order).
inline void fill_edges(Hull& h) {
  h.edges.clear();
  for (uint32_t f = 0; f < h.faces.size(); ++f) {
    const HullFace& face = h.faces[f];
    for (uint32_t s = 0; s < face.count; ++s) {
      const uint8_t p = h.face_vertices[face.first + s];
      const uint8_t q = h.face_vertices[face.first + (s + 1) % face.count];
      if (p > q) continue;
      uint8_t right = 0xFF;
      for (uint32_t g = 0; g < h.faces.size(); ++g) {
        const HullFace& other = h.faces[g];
        for (uint32_t k = 0; k < other.count; ++k) {
          if (h.face_vertices[other.first + k] == q &&
              h.face_vertices[other.first + (k + 1) % other.count] == p) {
            right = static_cast<uint8_t>(g);
          }
        }
      }
      h.edges.push_back({p, q, static_cast<uint8_t>(f), right});
    }
  }
}

inline void fill_bounds(Hull& h) {
  Vec3 hi{};
  float extent_sq = 0.0f;
  for (Vec3 v : h.vertices) {
    hi = max(hi, abs(v));
    extent_sq = std::max(extent_sq, length_squared(v));
  }
  h.half_size = hi;
  h.extent = std::sqrt(extent_sq);
}

// A hull from vertices (already centred on their centre of mass) and CCW
// loops; face planes from Newell's normal of each loop.
inline Hull make_hull(const std::vector<Vec3>& vertices,
                      const std::vector<std::vector<uint8_t>>& loops) {
  Hull h;
  h.vertices = vertices;
  for (const auto& loop : loops) {
    Vec3 n{};
    for (size_t k = 0; k < loop.size(); ++k) {
      n += cross(vertices[loop[k]], vertices[loop[(k + 1) % loop.size()]]);
    }
    n = normalize_or_zero(n);
    float offset = 0.0f;
    for (uint8_t v : loop) offset += dot(n, vertices[v]);
    HullFace face;
    face.normal = n;
    face.offset = offset / static_cast<float>(loop.size());
    face.first = static_cast<uint16_t>(h.face_vertices.size());
    face.count = static_cast<uint8_t>(loop.size());
    h.faces.push_back(face);
    h.face_vertices.insert(h.face_vertices.end(), loop.begin(), loop.end());
  }
  fill_edges(h);
  fill_bounds(h);
  return h;
}

// A box written out by hand in BoxHull's layout: vertex i at +-half by bits
// 0-2 of i, face 2k = -k, 2k + 1 = +k, normals and offsets exact.
inline Hull make_box(Vec3 half) {
  Hull h;
  for (uint32_t i = 0; i < 8; ++i) {
    h.vertices.push_back(
        {(i & 1u) ? half.x : -half.x, (i & 2u) ? half.y : -half.y, (i & 4u) ? half.z : -half.z});
  }
  const Vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  const float offsets[6] = {half.x, half.x, half.y, half.y, half.z, half.z};
  h.face_vertices = {0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4, 2, 6, 7, 3, 0, 2, 3, 1, 4, 5, 7, 6};
  for (uint32_t f = 0; f < 6; ++f) {
    HullFace face;
    face.normal = normals[f];
    face.offset = offsets[f];
    face.first = static_cast<uint16_t>(4 * f);
    face.count = 4;
    h.faces.push_back(face);
  }
  fill_edges(h);
  fill_bounds(h);
  return h;
}

// Triangle (-1,-1), (2,-1), (-1,2) in x-y (centroid at the origin)
// extruded over z in [-0.5, 0.5]. Faces: -z, +z, bottom (-y), left (-x),
// hypotenuse ((1,1,0)/sqrt 2).
inline Hull make_prism() {
  return make_hull({{-1, -1, -0.5f},
                    {2, -1, -0.5f},
                    {-1, 2, -0.5f},
                    {-1, -1, 0.5f},
                    {2, -1, 0.5f},
                    {-1, 2, 0.5f}},
                   {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}});
}

// Regular tetrahedron centred on the origin; face f is opposite vertex f,
// with normal -vertex_f / sqrt 3 and offset 1 / sqrt 3.
inline Hull make_tetrahedron() {
  return make_hull({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}},
                   {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}});
}

// A right prism over a regular n-gon of circumradius r in x-z, y in
// [-h, h]: 2n vertices (n = 32 gives the 64-vertex limit).
inline Hull make_ngon_prism(int n, float r, float h) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    const float a = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
    v.push_back({r * det_cos(a), -h, r * det_sin(a)});  // CCW about -y
  }
  for (int i = 0; i < n; ++i)
    v.push_back({v[static_cast<size_t>(i)].x, h, v[static_cast<size_t>(i)].z});
  std::vector<std::vector<uint8_t>> loops;
  std::vector<uint8_t> bottom;
  std::vector<uint8_t> top;
  for (int i = 0; i < n; ++i) bottom.push_back(static_cast<uint8_t>(i));
  for (int i = n - 1; i >= 0; --i) top.push_back(static_cast<uint8_t>(n + i));
  loops.push_back(bottom);
  loops.push_back(top);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    loops.push_back({static_cast<uint8_t>(i), static_cast<uint8_t>(n + i),
                     static_cast<uint8_t>(n + j), static_cast<uint8_t>(j)});
  }
  return make_hull(v, loops);
}

// A pyramid over a regular n-gon of circumradius r in x-z with its base at
// y = -h/4 and apex at y = 3h/4 (centroid at the origin); n = 63 gives the
// 64-vertex limit and a 63-sided face.
inline Hull make_pyramid(int n, float r, float h) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    const float a = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(n);
    v.push_back({r * det_cos(a), -0.25f * h, r * det_sin(a)});  // CCW about -y
  }
  v.push_back({0.0f, 0.75f * h, 0.0f});
  std::vector<std::vector<uint8_t>> loops;
  std::vector<uint8_t> base;
  for (int i = 0; i < n; ++i) base.push_back(static_cast<uint8_t>(i));
  loops.push_back(base);
  for (int i = 0; i < n; ++i) {
    loops.push_back(
        {static_cast<uint8_t>((i + 1) % n), static_cast<uint8_t>(i), static_cast<uint8_t>(n)});
  }
  return make_hull(v, loops);
}

// Every face loop counter-clockwise about an outward unit normal with all
// vertices behind its plane, every edge seen from both its faces as
// HullEdge says, and Euler's formula.
inline void expect_valid(const HullView& h, const char* what) {
  SCOPED_TRACE(what);
  for (uint32_t f = 0; f < h.face_count; ++f) {
    const HullFace& face = h.faces[f];
    Vec3 newell{};
    for (uint32_t k = 0; k < face.count; ++k) {
      newell += cross(h.vertices[h.face_vertices[face.first + k]],
                      h.vertices[h.face_vertices[face.first + (k + 1) % face.count]]);
    }
    EXPECT_GT(dot(normalize_or_zero(newell), face.normal), 0.9999f) << "face " << f;
    EXPECT_NEAR(length(face.normal), 1.0f, kTol);
    for (uint32_t k = 0; k < face.count; ++k) {
      EXPECT_NEAR(dot(face.normal, h.vertices[h.face_vertices[face.first + k]]), face.offset, kTol);
    }
    for (uint32_t v = 0; v < h.vertex_count; ++v) {
      EXPECT_LE(dot(face.normal, h.vertices[v]), face.offset + kTol);
    }
  }
  auto loop_has = [&](uint32_t f, uint8_t p, uint8_t q) {
    const HullFace& face = h.faces[f];
    for (uint32_t k = 0; k < face.count; ++k) {
      if (h.face_vertices[face.first + k] == p &&
          h.face_vertices[face.first + (k + 1) % face.count] == q) {
        return true;
      }
    }
    return false;
  };
  for (uint32_t e = 0; e < h.edge_count; ++e) {
    const HullEdge& edge = h.edges[e];
    EXPECT_TRUE(loop_has(edge.face_left, edge.v0, edge.v1)) << "edge " << e;
    EXPECT_TRUE(loop_has(edge.face_right, edge.v1, edge.v0)) << "edge " << e;
  }
  EXPECT_EQ(h.vertex_count + h.face_count, h.edge_count + 2);
}

// ---- Helpers ---------------------------------------------------------------

inline Mat3 axes(Quat q) {
  return mat3_from_quat(q);
}
inline Quat about(Vec3 axis, float angle) {
  const float s = det_sin(0.5f * angle);
  return normalize(Quat{axis.x * s, axis.y * s, axis.z * s, det_cos(0.5f * angle)});
}
// 180 degrees about z, exactly.
const Mat3 kFlipZ{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
// 180 degrees about x, exactly.
const Mat3 kFlipX{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}};

inline float min_separation(const Manifold& m) {
  float s = 1e30f;
  for (uint32_t i = 0; i < m.point_count; ++i) s = std::min(s, m.points[i].separation);
  return s;
}

inline bool is_edge_contact(const Manifold& m) {
  return m.point_count == 1 && (m.points[0].feature_id & 0x80000000u) != 0;
}

inline void expect_near(Vec3 got, Vec3 want, float tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// Same normal and the same points (position and separation) in any order.
inline void expect_same_contact(const Manifold& got, const Manifold& want, float tol) {
  ASSERT_EQ(got.point_count, want.point_count);
  if (want.point_count == 0) return;
  expect_near(got.normal, want.normal, tol);
  bool used[kMaxManifoldPoints] = {};
  for (uint32_t i = 0; i < want.point_count; ++i) {
    bool found = false;
    for (uint32_t j = 0; j < got.point_count && !found; ++j) {
      const Vec3 d = got.points[j].point - want.points[i].point;
      if (!used[j] && std::fabs(d.x) <= tol && std::fabs(d.y) <= tol && std::fabs(d.z) <= tol &&
          std::fabs(got.points[j].separation - want.points[i].separation) <= tol) {
        used[j] = true;
        found = true;
      }
    }
    EXPECT_TRUE(found) << "point " << i << " (" << want.points[i].point.x << ", "
                       << want.points[i].point.y << ", " << want.points[i].point.z << ")";
  }
}

inline uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

inline void expect_same_bits(const Manifold& a, const Manifold& b) {
  ASSERT_EQ(a.point_count, b.point_count);
  EXPECT_EQ(a.separating_axis, b.separating_axis);
  if (a.point_count == 0) return;
  EXPECT_EQ(bits(a.normal.x), bits(b.normal.x));
  EXPECT_EQ(bits(a.normal.y), bits(b.normal.y));
  EXPECT_EQ(bits(a.normal.z), bits(b.normal.z));
  for (uint32_t i = 0; i < a.point_count; ++i) {
    EXPECT_EQ(bits(a.points[i].point.x), bits(b.points[i].point.x));
    EXPECT_EQ(bits(a.points[i].point.y), bits(b.points[i].point.y));
    EXPECT_EQ(bits(a.points[i].point.z), bits(b.points[i].point.z));
    EXPECT_EQ(bits(a.points[i].separation), bits(b.points[i].separation));
    EXPECT_EQ(a.points[i].feature_id, b.points[i].feature_id);
  }
}

struct BoxCase {
  const char* name;
  Vec3 ca;
  Quat qa;
  Vec3 ha;
  Vec3 cb;
  Quat qb;
  Vec3 hb;
  uint32_t points;  // what collide_boxes gives
  float tol = kTol;
};

// Box-box poses that clip to at most four candidates, so the point sets
// are the same with any reduction rule.
inline std::vector<BoxCase> box_cases() {
  const float e = std::sqrt(0.5f);
  const float tilt = 0.3f;
  const float low = 0.5f * det_cos(tilt) + 0.5f * det_sin(tilt);  // lowest corner below centre
  const Quat slab = about({0.3f, 0.8f, -0.5f}, 1.1f);
  return {
      {"resting", {0, 0, 0}, Quat{}, {2, 0.5f, 2}, {0, 0.9f, 0}, Quat{}, {0.5f, 0.5f, 0.5f}, 4},
      {"offset turned about the normal",
       {0, 0, 0},
       Quat{},
       {2, 0.5f, 2},
       {0.3f, 0.95f, -0.2f},
       about({0, 1, 0}, 0.4f),
       {0.5f, 0.45f, 0.3f},
       4},
      {"tilted onto an edge",
       {0, 0, 0},
       Quat{},
       {2, 0.5f, 2},
       {0.1f, 0.5f + low - 0.03f, 0.2f},
       about({0, 0, 1}, tilt),
       {0.5f, 0.5f, 0.5f},
       2},
      {"tilted under a ground above (reference on B)",
       {0.1f, -(0.5f + low - 0.03f), 0.2f},
       about({0, 0, 1}, tilt),
       {0.5f, 0.5f, 0.5f},
       {0, 0, 0},
       Quat{},
       {2, 0.5f, 2},
       2},
      {"edge crossing edge",
       {0, 0, 0},
       about({0, 0, 1}, 0.25f * kPi),
       {0.5f, 0.5f, 0.5f},
       {0, 2 * e - 0.05f, 0},
       about({1, 0, 0}, 0.25f * kPi),
       {0.5f, 0.5f, 0.5f},
       1},
      {"beyond speculative",
       {0, 0, 0},
       Quat{},
       {0.5f, 0.5f, 0.5f},
       {0.1f, 1.03f, 0},
       Quat{},
       {0.5f, 0.5f, 0.5f},
       0},
      {"speculative band",
       {0, 0, 0},
       Quat{},
       {1, 0.5f, 1},
       {0.1f, 1.01f, 0},
       about({0, 1, 0}, 0.2f),
       {0.5f, 0.5f, 0.5f},
       4},
      // A tilted slab far from the origin with a small box resting on it;
      // positions there round to 6e-5 m.
      {"far from the origin",
       {1000, -20, 500},
       slab,
       {1.5f, 0.25f, 1.0f},
       Vec3{1000, -20, 500} + rotate(slab, {0.3f, 0.34f, 0.2f}),
       slab * about({0, 1, 0}, 0.3f),
       {0.1f, 0.1f, 0.1f},
       4,
       2e-4f},
  };
}

}  // namespace rwd::sim::d3::hull_sat_test
