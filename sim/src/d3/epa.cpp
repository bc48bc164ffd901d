// SPDX-License-Identifier: MIT
// EPA: the penetration of two overlapping cores. The Minkowski difference
// B - A holds the origin; EPA grows a polytope inside it from GJK's
// simplex, each step adding the support point along the normal of the face
// nearest the origin, until that face lies on the difference's boundary.
// Its normal (negated: the polytope's faces point out of B - A) and
// distance are the penetration normal and depth.
//
// The polytope lives in fixed arrays (kEpaMaxVertices, kEpaMaxFaces). A
// step removes the faces the new point sees, found by a walk over
// neighbours from the nearest face (so only a connected region goes, as in
// Ericson's and Jolt's EPA; neighbours are looked up by their shared edge
// rather than stored), and fans the horizon to the new point. Faces keep
// their order (removed ones compacted out, new ones appended), so every
// choice, and every tie, is a function of the input bits.
#include <array>
#include <cmath>

#include "d3/gjk.h"

namespace rwd::sim::d3 {

using gjk_detail::RelativePose;

namespace {

// Two support points closer than this are the same point (metres^2).
constexpr float kSamePointSq = 1e-12f;
// A polytope face sees the new point when it lies this far above it; less
// counts as coplanar and the face stays (keeping slivers out).
constexpr float kVisibleEpsilon = 1e-6f;  // metres
// An apex this close to a triangle's plane gives it no volume (metres).
constexpr float kFlatHeight = 1e-7f;

// Filled by make_face before use (no initializers, so the scratch arrays
// below cost nothing to declare).
struct Face {
  uint8_t v[3];
  Vec3 n;      // unit, out of the polytope
  float dist;  // of the plane from the origin along n
};

struct Polytope {
  std::array<SimplexVertex, kEpaMaxVertices> verts;
  uint32_t vert_count = 0;
  std::array<Face, kEpaMaxFaces> faces;
  uint32_t face_count = 0;
};

// The plane of triangle (i0, i1, i2), wound counter-clockwise seen from
// outside; false when it is degenerate.
bool make_face(const Polytope& p, uint32_t i0, uint32_t i1, uint32_t i2, Face& f) {
  const Vec3 a = p.verts[i0].w;
  const Vec3 b = p.verts[i1].w;
  const Vec3 c = p.verts[i2].w;
  Vec3 n;
  if (!gjk_detail::triangle_normal(a, b, c, n)) return false;
  const float n_sq = length_squared(n);
  if (!(n_sq > 0.0f)) return false;
  f.v[0] = static_cast<uint8_t>(i0);
  f.v[1] = static_cast<uint8_t>(i1);
  f.v[2] = static_cast<uint8_t>(i2);
  f.n = n * (1.0f / std::sqrt(n_sq));
  f.dist = dot(f.n, (a + b + c) * (1.0f / 3.0f));
  return true;
}

// Faces of a closed start polytope given as triples, each turned to face
// away from `inside` (a point strictly within).
bool add_oriented_faces(Polytope& p, const uint8_t (*tris)[3], uint32_t count, Vec3 inside) {
  for (uint32_t k = 0; k < count; ++k) {
    Face f;
    if (!make_face(p, tris[k][0], tris[k][1], tris[k][2], f)) return false;
    if (dot(f.n, inside) > f.dist) {  // facing in: swap two vertices
      if (!make_face(p, tris[k][0], tris[k][2], tris[k][1], f)) return false;
    }
    p.faces[p.face_count++] = f;
  }
  return true;
}

// The face holding directed edge (i, j), or -1.
int find_edge(const Polytope& p, uint32_t i, uint32_t j) {
  for (uint32_t k = 0; k < p.face_count; ++k) {
    const Face& f = p.faces[k];
    for (int e = 0; e < 3; ++e) {
      if (f.v[e] == i && f.v[(e + 1) % 3] == j) return static_cast<int>(k);
    }
  }
  return -1;
}

uint32_t nearest_face(const Polytope& p) {
  uint32_t best = 0;
  for (uint32_t k = 1; k < p.face_count; ++k) {
    if (p.faces[k].dist < p.faces[best].dist) best = k;
  }
  return best;
}

// Adds w, replacing the faces it sees (a connected region about face
// `start`) by a fan from the horizon. False, with the polytope unchanged,
// when the arrays are full or the polytope or a new face is degenerate.
bool expand(Polytope& p, uint32_t start, const SimplexVertex& w) {
  if (p.vert_count >= kEpaMaxVertices) return false;
  std::array<bool, kEpaMaxFaces> visible{};
  std::array<uint8_t, kEpaMaxFaces> stack{};
  std::array<uint8_t, kEpaMaxFaces> horizon_i{};
  std::array<uint8_t, kEpaMaxFaces> horizon_j{};
  uint32_t top = 0;
  uint32_t horizon = 0;
  uint32_t removed = 1;
  visible[start] = true;
  stack[top++] = static_cast<uint8_t>(start);
  while (top > 0) {
    const Face f = p.faces[stack[--top]];
    for (int e = 0; e < 3; ++e) {
      const uint32_t i = f.v[e];
      const uint32_t j = f.v[(e + 1) % 3];
      const int nb = find_edge(p, j, i);
      if (nb < 0) return false;  // not closed: rounding broke it
      if (visible[nb]) continue;
      const Face& g = p.faces[nb];
      if (dot(g.n, w.w - p.verts[g.v[0]].w) > kVisibleEpsilon) {
        visible[nb] = true;
        stack[top++] = static_cast<uint8_t>(nb);
        ++removed;
      } else {
        if (horizon == kEpaMaxFaces) return false;
        horizon_i[horizon] = static_cast<uint8_t>(i);
        horizon_j[horizon] = static_cast<uint8_t>(j);
        ++horizon;
      }
    }
  }
  if (p.face_count - removed + horizon > kEpaMaxFaces) return false;
  const uint32_t index = p.vert_count;
  p.verts[index] = w;
  std::array<Face, kEpaMaxFaces> fresh;  // the first `horizon` are filled
  for (uint32_t k = 0; k < horizon; ++k) {
    if (!make_face(p, horizon_i[k], horizon_j[k], index, fresh[k])) return false;
  }
  ++p.vert_count;
  uint32_t kept = 0;
  for (uint32_t k = 0; k < p.face_count; ++k) {
    if (!visible[k]) p.faces[kept++] = p.faces[k];
  }
  for (uint32_t k = 0; k < horizon; ++k) p.faces[kept++] = fresh[k];
  p.face_count = kept;
  return true;
}

Vec3 to_world(const ConvexProxy& a, Vec3 local) {
  return a.position + a.axes * local;
}

// Depth 0 for cores whose difference has no volume about the origin (flat,
// a segment or a point): the normal is `n` (A's frame), or failing that
// the line between the proxies' positions, or +y; the witnesses are GJK's.
EpaOutput flat_result(const ConvexProxy& a, const RelativePose& pose, const GjkSimplex& simplex,
                      Vec3 n) {
  EpaOutput out;
  Vec3 pa;
  Vec3 pb;
  for (uint32_t i = 0; i < simplex.count; ++i) {
    pa += simplex.v[i].a * simplex.v[i].weight;
    pb += simplex.v[i].b * simplex.v[i].weight;
  }
  Vec3 normal = normalize_or_zero(n);
  if (normal == Vec3{}) normal = normalize_or_zero(pose.position);
  if (normal == Vec3{}) normal = Vec3{0.0f, 1.0f, 0.0f};
  // Point it from A toward B where that is defined.
  if (dot(normal, pose.position) < 0.0f) normal = -normal;
  out.normal = a.axes * normal;
  out.depth = 0.0f;
  out.point_a = to_world(a, pa);
  out.point_b = to_world(a, pb);
  out.converged = false;
  return out;
}

}  // namespace

EpaOutput epa_penetration(const ConvexProxy& a, const ConvexProxy& b, const GjkSimplex& simplex) {
  const RelativePose pose = gjk_detail::relative_pose(a, b);
  Polytope p;
  for (uint32_t i = 0; i < simplex.count && i < 4; ++i) p.verts[p.vert_count++] = simplex.v[i];
  if (p.vert_count == 0) {
    p.verts[0] = gjk_detail::make_vertex(a, b, pose, 0, 0);
    p.vert_count = 1;
  }

  // Blow the simplex up to a polytope with volume, deterministically: a
  // second point along the axes, a third along three directions 120
  // degrees apart about the segment, then apexes on both sides of the
  // triangle (both when both have volume: the double pyramid holds an
  // origin that lies on the triangle).
  if (p.vert_count >= 2 && !(length_squared(p.verts[1].w - p.verts[0].w) > kSamePointSq)) {
    p.vert_count = 1;
  }
  if (p.vert_count == 1) {
    const Vec3 dirs[6] = {{1.0f, 0.0f, 0.0f},  {-1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                          {0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 1.0f},  {0.0f, 0.0f, -1.0f}};
    for (const Vec3& d : dirs) {
      const SimplexVertex s = gjk_detail::support_vertex(a, b, pose, d);
      if (length_squared(s.w - p.verts[0].w) > kSamePointSq) {
        p.verts[p.vert_count++] = s;
        break;
      }
    }
    if (p.vert_count == 1) return flat_result(a, pose, simplex, Vec3{});
  }
  auto triangle_ok = [&]() {
    Face f;
    return make_face(p, 0, 1, 2, f);
  };
  if (p.vert_count >= 3 && !triangle_ok()) p.vert_count = 2;
  if (p.vert_count == 2) {
    const Vec3 d = normalize_or_zero(p.verts[1].w - p.verts[0].w);
    const Vec3 ad = abs(d);
    const Vec3 axis = (ad.x <= ad.y && ad.x <= ad.z)
                          ? Vec3{1.0f, 0.0f, 0.0f}
                          : (ad.y <= ad.z ? Vec3{0.0f, 1.0f, 0.0f} : Vec3{0.0f, 0.0f, 1.0f});
    const Vec3 n1 = normalize_or_zero(cross(d, axis));
    const Vec3 n2 = cross(d, n1);
    constexpr float kSin120 = 0.8660254f;
    const Vec3 dirs[3] = {n1, n1 * -0.5f + n2 * kSin120, n1 * -0.5f - n2 * kSin120};
    for (const Vec3& dir : dirs) {
      p.verts[2] = gjk_detail::support_vertex(a, b, pose, dir);
      p.vert_count = 3;
      if (triangle_ok()) break;
      p.vert_count = 2;
    }
    if (p.vert_count == 2) return flat_result(a, pose, simplex, Vec3{});
  }
  const Vec3 tri_n = [&]() {
    Face f;
    make_face(p, 0, 1, 2, f);
    return f.n;
  }();
  if (p.vert_count == 4) {
    const float h = dot(tri_n, p.verts[3].w - p.verts[0].w);
    if (!(std::fabs(h) > kFlatHeight)) p.vert_count = 3;
  }
  if (p.vert_count == 4) {
    static constexpr uint8_t kTet[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    const Vec3 inside = (p.verts[0].w + p.verts[1].w + p.verts[2].w + p.verts[3].w) * 0.25f;
    if (!add_oriented_faces(p, kTet, 4, inside)) {
      return flat_result(a, pose, simplex, tri_n);
    }
  } else {
    const SimplexVertex up = gjk_detail::support_vertex(a, b, pose, tri_n);
    const SimplexVertex down = gjk_detail::support_vertex(a, b, pose, -tri_n);
    const float h_up = dot(tri_n, up.w - p.verts[0].w);
    const float h_down = -dot(tri_n, down.w - p.verts[0].w);
    const bool has_up = h_up > kFlatHeight;
    const bool has_down = h_down > kFlatHeight;
    if (!has_up && !has_down) return flat_result(a, pose, simplex, tri_n);
    if (has_up && has_down) {
      p.verts[3] = up;
      p.verts[4] = down;
      p.vert_count = 5;
      static constexpr uint8_t kBipyramid[6][3] = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3},
                                                   {0, 1, 4}, {1, 2, 4}, {2, 0, 4}};
      const Vec3 inside = (p.verts[0].w + p.verts[1].w + p.verts[2].w) * (1.0f / 3.0f);
      if (!add_oriented_faces(p, kBipyramid, 6, inside)) {
        return flat_result(a, pose, simplex, tri_n);
      }
    } else {
      p.verts[3] = h_up >= h_down ? up : down;
      p.vert_count = 4;
      static constexpr uint8_t kTet[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
      const Vec3 inside = (p.verts[0].w + p.verts[1].w + p.verts[2].w + p.verts[3].w) * 0.25f;
      if (!add_oriented_faces(p, kTet, 4, inside)) return flat_result(a, pose, simplex, tri_n);
    }
  }

  EpaOutput out;
  uint32_t iter = 0;
  for (; iter < kEpaMaxIterations; ++iter) {
    const uint32_t best = nearest_face(p);
    const Face f = p.faces[best];
    const SimplexVertex w = gjk_detail::support_vertex(a, b, pose, f.n);
    if (dot(f.n, w.w) - f.dist <= kEpaTolerance) {
      out.converged = true;
      break;
    }
    bool known = false;
    for (uint32_t i = 0; i < p.vert_count; ++i) {
      if (p.verts[i].index_a == w.index_a && p.verts[i].index_b == w.index_b) {
        known = true;
        break;
      }
    }
    if (known) {  // the boundary, up to rounding
      out.converged = true;
      break;
    }
    if (!expand(p, best, w)) break;  // full or degenerate: the best face so far
  }
  out.iterations = iter;

  const Face f = p.faces[nearest_face(p)];
  float weights[3];
  gjk_detail::closest_on_triangle(p.verts[f.v[0]].w, p.verts[f.v[1]].w, p.verts[f.v[2]].w, weights);
  Vec3 pa;
  Vec3 pb;
  for (int k = 0; k < 3; ++k) {
    pa += p.verts[f.v[k]].a * weights[k];
    pb += p.verts[f.v[k]].b * weights[k];
  }
  out.normal = a.axes * -f.n;
  out.depth = f.dist > 0.0f ? f.dist : 0.0f;
  out.point_a = to_world(a, pa);
  out.point_b = to_world(a, pb);
  return out;
}

}  // namespace rwd::sim::d3
