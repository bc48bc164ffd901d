// SPDX-License-Identifier: MIT
// GJK distance between two convex proxies and the shape cast built on it.
//
// The sub-algorithm is Johnson's in the form of closest-point Voronoi
// region tests (Ericson, Real-Time Collision Detection 5.1; as Jolt's
// ClosestPoint): each step reduces the simplex to the smallest face that
// holds the point nearest the origin, with its barycentric weights. Two
// choices keep it accurate in float: a triangle's normal is taken from its
// two shortest edges (Box2D's "troublesome triangle"), and the nearest
// point of a face region is the origin's projection on the plane rather
// than the weighted sum of the vertices (as Jolt does), so the distance and
// normal do not inherit the weights' cancellation.
#include "d3/gjk.h"

#include <cmath>
#include <limits>

namespace rwd::sim::d3 {

using gjk_detail::mul_transpose;
using gjk_detail::RelativePose;

namespace {

// See the main loop: a step may be this much worse than the last, relative
// to the largest coordinate of its simplex, and still be taken (the closest
// point's rounding is a few float epsilons of that).
constexpr float kStepRounding = 16.0f * std::numeric_limits<float>::epsilon();
// A bound on the rounding of a dot product of three terms, relative to the
// sum of the terms' magnitudes (a few float epsilons).
constexpr float kDotRounding = 4.0f * std::numeric_limits<float>::epsilon();
// A triangle with no reliable normal (gjk_detail::triangle_normal) or a
// tetrahedron flatter than kFlatVolume is handled by its edges (faces).
constexpr float kFlatVolume = 1e-6f;

uint32_t support_local(const Vec3* points, uint32_t count, Vec3 dir) {
  uint32_t best = 0;
  float best_d = dot(points[0], dir);
  for (uint32_t i = 1; i < count; ++i) {
    const float d = dot(points[i], dir);
    if (d > best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

// The point of segment p0 p1 nearest the origin; `mask` says which ends
// carry weight (bit 0: p0, bit 1: p1).
Vec3 closest_on_segment(Vec3 p0, Vec3 p1, float weights[2], uint32_t& mask) {
  const Vec3 e = p1 - p0;
  const float num = -dot(p0, e);
  if (num <= 0.0f) {
    weights[0] = 1.0f;
    weights[1] = 0.0f;
    mask = 1u;
    return p0;
  }
  const float den = dot(e, e);
  if (num >= den) {
    weights[0] = 0.0f;
    weights[1] = 1.0f;
    mask = 2u;
    return p1;
  }
  const float t = num / den;
  weights[0] = 1.0f - t;
  weights[1] = t;
  mask = 3u;
  // From the end nearer the result: the rounding scales with the base
  // point's size, and the far end may be far out.
  return t <= 0.5f ? p0 + e * t : p1 - e * (1.0f - t);
}

// Triangle version; `mask` bits 0-2 name the vertices kept.
Vec3 closest_on_triangle_masked(Vec3 a, Vec3 b, Vec3 c, float weights[3], uint32_t& mask) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 bc = c - b;
  Vec3 n;
  if (!gjk_detail::triangle_normal(a, b, c, n)) {
    // Degenerate: the nearest of the three edges (ties to the first).
    const Vec3 ends[3][2] = {{a, b}, {a, c}, {b, c}};
    const uint32_t bits[3][2] = {{1u, 2u}, {1u, 4u}, {2u, 4u}};
    const int slot[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    float best_sq = std::numeric_limits<float>::max();
    Vec3 best;
    for (int k = 0; k < 3; ++k) {
      float w[2];
      uint32_t m = 0;
      const Vec3 p = closest_on_segment(ends[k][0], ends[k][1], w, m);
      const float d_sq = length_squared(p);
      if (k == 0 || d_sq < best_sq) {
        best_sq = d_sq;
        best = p;
        weights[0] = weights[1] = weights[2] = 0.0f;
        weights[slot[k][0]] = w[0];
        weights[slot[k][1]] = w[1];
        mask = ((m & 1u) ? bits[k][0] : 0u) | ((m & 2u) ? bits[k][1] : 0u);
      }
    }
    return best;
  }
  // Ericson 5.1.5 with p at the origin.
  const Vec3 ap = -a;
  const float d1 = dot(ab, ap);
  const float d2 = dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) {
    weights[0] = 1.0f;
    weights[1] = weights[2] = 0.0f;
    mask = 1u;
    return a;
  }
  const Vec3 bp = -b;
  const float d3 = dot(ab, bp);
  const float d4 = dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) {
    weights[1] = 1.0f;
    weights[0] = weights[2] = 0.0f;
    mask = 2u;
    return b;
  }
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float t = d1 / (d1 - d3);
    weights[0] = 1.0f - t;
    weights[1] = t;
    weights[2] = 0.0f;
    mask = 3u;
    return a + ab * t;
  }
  const Vec3 cp = -c;
  const float d5 = dot(ab, cp);
  const float d6 = dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) {
    weights[2] = 1.0f;
    weights[0] = weights[1] = 0.0f;
    mask = 4u;
    return c;
  }
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float t = d2 / (d2 - d6);
    weights[0] = 1.0f - t;
    weights[1] = 0.0f;
    weights[2] = t;
    mask = 5u;
    return a + ac * t;
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    weights[0] = 0.0f;
    weights[1] = 1.0f - t;
    weights[2] = t;
    mask = 6u;
    return b + bc * t;
  }
  const float sum = va + vb + vc;
  if (sum > 0.0f) {
    const float inv = 1.0f / sum;
    weights[1] = vb * inv;
    weights[2] = vc * inv;
    weights[0] = 1.0f - weights[1] - weights[2];
  } else {  // rounding left no region; the centroid's weights
    weights[0] = weights[1] = weights[2] = 1.0f / 3.0f;
  }
  mask = 7u;
  // The origin's projection on the plane (more accurate than the weighted
  // vertices), through the vertex nearest the origin: the rounding scales
  // with the size of the point used.
  const float a_sq = length_squared(a);
  const float b_sq = length_squared(b);
  const float c_sq = length_squared(c);
  const Vec3 base = (a_sq <= b_sq && a_sq <= c_sq) ? a : (b_sq <= c_sq ? b : c);
  return n * (dot(base, n) / length_squared(n));
}

// Tetrahedron version: `inside` when the origin is within it (then the
// weights are its barycentric coordinates and the result is the origin).
Vec3 closest_on_tetrahedron(const Vec3 p[4], float weights[4], uint32_t& mask, bool& inside) {
  inside = false;
  const Vec3 ab = p[1] - p[0];
  const Vec3 ac = p[2] - p[0];
  const Vec3 ad = p[3] - p[0];
  const float det = dot(cross(ab, ac), ad);
  const float scale = length_squared(ab) * length_squared(ac) * length_squared(ad);
  const bool flat = !(det * det > kFlatVolume * kFlatVolume * scale);
  // Faces as vertex triples, with the opposite vertex last.
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
  bool any_outside = false;
  float best_sq = std::numeric_limits<float>::max();
  Vec3 best;
  for (const auto& f : kFaces) {
    const Vec3 a = p[f[0]];
    const Vec3 n = cross(p[f[1]] - a, p[f[2]] - a);
    const float side_origin = -dot(n, a);
    const float side_opposite = dot(n, p[f[3]] - a);
    // Ericson's PointOutsideOfPlane: the origin and the opposite vertex on
    // different sides; every face counts when the tetrahedron is flat.
    if (!flat && !(side_origin * side_opposite < 0.0f)) continue;
    any_outside = true;
    float w[3];
    uint32_t m = 0;
    const Vec3 q = closest_on_triangle_masked(a, p[f[1]], p[f[2]], w, m);
    const float d_sq = length_squared(q);
    if (d_sq < best_sq) {
      best_sq = d_sq;
      best = q;
      weights[0] = weights[1] = weights[2] = weights[3] = 0.0f;
      mask = 0u;
      for (int k = 0; k < 3; ++k) {
        weights[f[k]] = w[k];
        if (m & (1u << k)) mask |= 1u << f[k];
      }
    }
  }
  if (any_outside) return best;
  // Inside: barycentric coordinates by signed volumes.
  inside = true;
  const float inv = 1.0f / det;
  const Vec3 ao = -p[0];
  weights[1] = dot(cross(ao, ac), ad) * inv;
  weights[2] = dot(cross(ab, ao), ad) * inv;
  weights[3] = dot(cross(ab, ac), ao) * inv;
  weights[0] = 1.0f - weights[1] - weights[2] - weights[3];
  mask = 15u;
  return Vec3{};
}

// Reduces the simplex to the vertices named by `mask` (order kept), with
// their weights; returns the point nearest the origin.
Vec3 solve(GjkSimplex& s, bool& inside) {
  inside = false;
  float weights[4] = {1.0f, 0.0f, 0.0f, 0.0f};
  uint32_t mask = 1u;
  Vec3 v;
  switch (s.count) {
    case 1:
      v = s.v[0].w;
      break;
    case 2:
      v = closest_on_segment(s.v[0].w, s.v[1].w, weights, mask);
      break;
    case 3:
      v = closest_on_triangle_masked(s.v[0].w, s.v[1].w, s.v[2].w, weights, mask);
      break;
    default: {
      const Vec3 p[4] = {s.v[0].w, s.v[1].w, s.v[2].w, s.v[3].w};
      v = closest_on_tetrahedron(p, weights, mask, inside);
      break;
    }
  }
  uint32_t kept = 0;
  for (uint32_t i = 0; i < s.count; ++i) {
    if (!(mask & (1u << i))) continue;
    s.v[kept] = s.v[i];
    s.v[kept].weight = weights[i];
    ++kept;
  }
  s.count = kept;
  return v;
}

Vec3 to_world(const ConvexProxy& a, Vec3 local) {
  return a.position + a.axes * local;
}

}  // namespace

namespace gjk_detail {

RelativePose relative_pose(const ConvexProxy& a, const ConvexProxy& b) {
  RelativePose pose;
  pose.axes = {mul_transpose(a.axes, b.axes.c0), mul_transpose(a.axes, b.axes.c1),
               mul_transpose(a.axes, b.axes.c2)};
  pose.position = mul_transpose(a.axes, b.position - a.position);
  return pose;
}

SimplexVertex make_vertex(const ConvexProxy& a, const ConvexProxy& b, const RelativePose& pose,
                          uint32_t index_a, uint32_t index_b) {
  SimplexVertex v;
  v.a = a.points[index_a];
  v.b = pose.position + pose.axes * b.points[index_b];
  v.w = v.b - v.a;
  v.index_a = static_cast<uint8_t>(index_a);
  v.index_b = static_cast<uint8_t>(index_b);
  return v;
}

SimplexVertex support_vertex(const ConvexProxy& a, const ConvexProxy& b, const RelativePose& pose,
                             Vec3 dir) {
  const uint32_t ia = support_local(a.points, a.count, -dir);
  const uint32_t ib = support_local(b.points, b.count, mul_transpose(pose.axes, dir));
  return make_vertex(a, b, pose, ia, ib);
}

Vec3 closest_on_triangle(Vec3 p0, Vec3 p1, Vec3 p2, float weights[3]) {
  uint32_t mask = 0;
  return closest_on_triangle_masked(p0, p1, p2, weights, mask);
}

}  // namespace gjk_detail

uint32_t proxy_support(const ConvexProxy& proxy, Vec3 dir) {
  return support_local(proxy.points, proxy.count, mul_transpose(proxy.axes, dir));
}

GjkOutput gjk_distance(const ConvexProxy& a, const ConvexProxy& b, GjkCache* cache) {
  GjkOutput out;
  const RelativePose pose = gjk_detail::relative_pose(a, b);
  GjkSimplex s;
  if (cache != nullptr && cache->count >= 1 && cache->count <= 4) {
    for (uint32_t i = 0; i < cache->count; ++i) {
      const uint32_t ia = cache->index_a[i];
      const uint32_t ib = cache->index_b[i];
      if (ia >= a.count || ib >= b.count) {  // stale: start cold
        s.count = 0;
        break;
      }
      s.v[s.count++] = gjk_detail::make_vertex(a, b, pose, ia, ib);
    }
  }
  if (s.count == 0) {
    s.v[0] = gjk_detail::make_vertex(a, b, pose, 0, 0);
    s.count = 1;
  }

  const float overlap_sq = kGjkOverlapDistance * kGjkOverlapDistance;
  GjkSimplex best = s;
  float best_sq = std::numeric_limits<float>::max();
  Vec3 v;
  bool overlap = false;
  uint32_t iter = 0;
  for (;;) {
    // The vertices before the solve, to tell a support point the solve
    // just dropped.
    uint8_t save_a[4];
    uint8_t save_b[4];
    Vec3 pre[4];
    const uint32_t save_count = s.count;
    for (uint32_t i = 0; i < s.count; ++i) {
      save_a[i] = s.v[i].index_a;
      save_b[i] = s.v[i].index_b;
      pre[i] = s.v[i].w;
    }
    bool inside = false;
    const Vec3 closest = solve(s, inside);
    if (inside) {
      v = Vec3{};
      overlap = true;
      break;
    }
    const float dist_sq = length_squared(closest);
    // A step that does not get closer ends the search, but rounding may
    // make the right step look a hair worse: where a face and one of its
    // edges nearly tie in distance, the edge's normal can be off to first
    // order while its distance is off only to second. So a step no worse
    // than the rounding of the simplex's coordinates is taken (the gap test
    // below then ends the search with its better normal); a true
    // regression returns the best simplex.
    float scale = 0.0f;
    for (uint32_t i = 0; i < save_count; ++i) {
      const Vec3 m = abs(pre[i]);
      scale = m.x > scale ? m.x : scale;
      scale = m.y > scale ? m.y : scale;
      scale = m.z > scale ? m.z : scale;
    }
    if (iter > 0 && !(std::sqrt(dist_sq) <= std::sqrt(best_sq) + kStepRounding * scale)) {
      s = best;
      break;
    }
    const bool progress = dist_sq < best_sq;
    best = s;
    best_sq = dist_sq;
    v = closest;
    if (dist_sq <= overlap_sq) {
      overlap = true;
      break;
    }
    if (iter == kGjkMaxIterations) break;
    ++iter;
    const SimplexVertex w = gjk_detail::support_vertex(a, b, pose, -v);
    // dot(v, w) / |v| is a lower bound on the distance, |v| an upper one;
    // the second term is the rounding of dot(v, w), which for a small v
    // and a large w would otherwise keep the test from ever passing.
    const float gap = dist_sq - dot(v, w.w);
    if (gap <= kGjkRelativeTolerance * dist_sq + kDotRounding * dot(abs(v), abs(w.w))) break;
    // A support point already in the simplex cannot help (rounding kept the
    // gap test from seeing it). One the solve just dropped may, since the
    // solve's choice among near ties is what a wide gap calls into doubt;
    // but only after a step that got closer, so the two cannot cycle.
    bool duplicate = false;
    for (uint32_t i = 0; i < s.count; ++i) {
      duplicate = duplicate || (s.v[i].index_a == w.index_a && s.v[i].index_b == w.index_b);
    }
    for (uint32_t i = 0; i < save_count && !progress; ++i) {
      duplicate = duplicate || (save_a[i] == w.index_a && save_b[i] == w.index_b);
    }
    if (duplicate) break;
    s.v[s.count++] = w;
  }

  Vec3 pa;
  Vec3 pb;
  for (uint32_t i = 0; i < s.count; ++i) {
    pa += s.v[i].a * s.v[i].weight;
    pb += s.v[i].b * s.v[i].weight;
  }
  out.point_a = to_world(a, pa);
  out.point_b = to_world(a, pb);
  out.iterations = iter;
  out.simplex = s;
  out.overlap = overlap;
  if (!overlap) {
    const float dist = std::sqrt(length_squared(v));
    out.distance = dist;
    out.normal = a.axes * (v * (1.0f / dist));
  }
  if (cache != nullptr) {
    cache->count = s.count;
    for (uint32_t i = 0; i < 4; ++i) {
      cache->index_a[i] = i < s.count ? s.v[i].index_a : 0;
      cache->index_b[i] = i < s.count ? s.v[i].index_b : 0;
    }
  }
  return out;
}

ShapeCastOutput shape_cast(const ConvexProxy& a, const ConvexProxy& b, Vec3 translation_b,
                           float max_fraction) {
  ShapeCastOutput out;
  const float radii = a.radius + b.radius;
  const float target = radii + kCastTargetGap;
  ConvexProxy moved = b;
  GjkCache cache;
  float t = 0.0f;
  for (uint32_t iter = 0; iter < kShapeCastMaxIterations; ++iter) {
    moved.position = b.position + translation_b * t;
    const GjkOutput g = gjk_distance(a, moved, &cache);
    out.iterations = iter + 1;
    if (g.overlap || g.distance < radii) {
      // Only at the start: every later step stops short of the target gap.
      out.hit = true;
      out.initially_overlapping = iter == 0;
      out.fraction = t;
      if (g.overlap) {
        const EpaOutput e = epa_penetration(a, moved, g.simplex);
        out.normal = e.normal;
        out.point = e.point_a + e.normal * a.radius;
      } else {
        out.normal = g.normal;
        out.point = g.point_a + g.normal * a.radius;
      }
      return out;
    }
    // The distance falls at this rate along the sweep here, and no faster
    // later (it is convex in t), so the step below never overshoots.
    const float closing = -dot(g.normal, translation_b);
    if (!(closing > 0.0f)) return out;  // not approaching: the distance only grows
    const float t_touch = t + (g.distance - radii) / closing;
    if (t_touch > max_fraction) return out;  // even the earliest touch is too late
    if (g.distance <= target + kCastTolerance || iter + 1 == kShapeCastMaxIterations) {
      out.hit = true;
      out.fraction = t_touch;
      out.normal = g.normal;
      out.point = g.point_a + g.normal * a.radius;
      return out;
    }
    t += (g.distance - target) / closing;
  }
  return out;
}

}  // namespace rwd::sim::d3
