// SPDX-License-Identifier: MIT
// A face contact with one triangle: the shape's lowest core points, seen
// along the face normal, as a convex outline clipped to the triangle.
// Conventions are manifold_triangles.h's; everything works in the source's
// frame, on fixed arrays.
#include <algorithm>
#include <cmath>

#include "d3/manifold_triangles.h"
#include "d3/polygon_clip.h"

namespace rwd::sim::d3 {
namespace {

constexpr uint32_t kCrossCode = 16;

// Outline points this close to a triangle's edge count as over it when
// the clipped outline is empty (metres, scaled by the edge's length).
constexpr float kEdgeSlack = 1e-5f;

// Largest outline: every core point, plus one per clipping edge.
constexpr uint32_t kMaxOutline = kProxyMaxPoints + 4;

// A point of the shape's outline in the triangle's plane coordinates:
// (u, v) along the tangents, h the height of the core point above the
// plane, code as manifold_triangles.h numbers it.
struct OutlinePoint {
  float u;
  float v;
  float h;
  uint32_t code;
};

float cross2(float ax, float ay, float bx, float by) {
  return ax * by - ay * bx;
}

OutlinePoint lerp(const OutlinePoint& a, const OutlinePoint& b, float t, uint32_t code) {
  return {a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t, a.h + (b.h - a.h) * t, code};
}

bool outline_less(const OutlinePoint& a, const OutlinePoint& b) {
  if (a.u != b.u) return a.u < b.u;
  if (a.v != b.v) return a.v < b.v;
  if (a.h != b.h) return a.h < b.h;
  return a.code < b.code;
}

// Convex hull (Andrew's monotone chain, counter-clockwise in (u, v)) of
// `count` points, in place; returns the hull's size. Points sharing (u, v)
// keep the lowest (sorted first); collinear points are dropped. The sort
// is on a total order, so the hull is a function of the points' bits.
uint32_t outline_hull(OutlinePoint* p, uint32_t count) {
  std::sort(p, p + count, outline_less);
  uint32_t n = 0;
  for (uint32_t i = 0; i < count; ++i) {
    if (n > 0 && p[i].u == p[n - 1].u && p[i].v == p[n - 1].v) continue;
    p[n++] = p[i];
  }
  if (n < 3) return n;
  OutlinePoint hull[2 * kMaxOutline];
  uint32_t k = 0;
  auto turn = [&](const OutlinePoint& o, const OutlinePoint& a, const OutlinePoint& b) {
    return cross2(a.u - o.u, a.v - o.v, b.u - o.u, b.v - o.v);
  };
  for (uint32_t i = 0; i < n; ++i) {
    while (k >= 2 && !(turn(hull[k - 2], hull[k - 1], p[i]) > 0.0f)) --k;
    hull[k++] = p[i];
  }
  const uint32_t lower = k + 1;
  for (uint32_t i = n - 1; i-- > 0;) {
    while (k >= lower && !(turn(hull[k - 2], hull[k - 1], p[i]) > 0.0f)) --k;
    hull[k++] = p[i];
  }
  --k;                           // the last point repeats the first
  if (k < 2) k = n < 2 ? n : 2;  // all collinear: the chain's ends
  for (uint32_t i = 0; i < k; ++i) p[i] = hull[i];
  return k;
}

// Clips the outline (1, 2 or >= 3 points, counter-clockwise) to the
// triangle (q, oriented by `orient` so that inside is >= 0), in place;
// returns the count left. A crossing is coded kCrossCode + 2 e where the
// outline enters over edge e and one more where it leaves.
uint32_t clip_outline(OutlinePoint* poly, uint32_t n, const float q[3][2], float orient) {
  OutlinePoint tmp[kMaxOutline];
  float dist[kMaxOutline];
  for (uint32_t e = 0; e < 3 && n > 0; ++e) {
    const float ax = q[e][0];
    const float ay = q[e][1];
    const float ex = q[(e + 1) % 3][0] - ax;
    const float ey = q[(e + 1) % 3][1] - ay;
    // Distance outward: minus the side, which is positive inside.
    for (uint32_t i = 0; i < n; ++i) {
      dist[i] = -(orient * cross2(ex, ey, poly[i].u - ax, poly[i].v - ay));
    }
    const uint32_t code = kCrossCode + 2 * e;
    const int m = clip_polygon<static_cast<int>(kMaxOutline)>(
        poly, dist, static_cast<int>(n), tmp,
        [code](const OutlinePoint& a, const OutlinePoint& b, float t, bool leaving) {
          return lerp(a, b, t, leaving ? code + 1 : code);
        });
    n = static_cast<uint32_t>(m);
    for (uint32_t i = 0; i < n; ++i) poly[i] = tmp[i];
  }
  return n;
}

// Whether (u, v) lies within kEdgeSlack of the triangle q (orientation
// `orient`), whose edges have lengths len.
bool near_triangle(float u, float v, const float q[3][2], const float len[3], float orient) {
  for (uint32_t e = 0; e < 3; ++e) {
    const float ex = q[(e + 1) % 3][0] - q[e][0];
    const float ey = q[(e + 1) % 3][1] - q[e][1];
    const float s = orient * cross2(ex, ey, u - q[e][0], v - q[e][1]);
    if (!(s >= -kEdgeSlack * len[e])) return false;
  }
  return true;
}

}  // namespace

namespace triangle_detail {

bool face_contact(const ShapeCore& core, const TriangleRef& tri, Vec3 side, bool slack,
                  float speculative_m, TriangleContact& out) {
  Vec3 t1;
  Vec3 t2;
  tangent_basis(side, t1, t2);
  const Vec3 o = tri.p[0];
  float q[3][2];
  float len[3];
  for (int k = 0; k < 3; ++k) {
    q[k][0] = dot(tri.p[k] - o, t1);
    q[k][1] = dot(tri.p[k] - o, t2);
    len[k] = length(tri.p[(k + 1) % 3] - tri.p[k]);
  }
  const float orient =
      cross2(q[1][0] - q[0][0], q[1][1] - q[0][1], q[2][0] - q[0][0], q[2][1] - q[0][1]) > 0.0f
          ? 1.0f
          : -1.0f;
  float h[kProxyMaxPoints];
  float h_min = 0.0f;
  uint32_t i_min = 0;
  for (uint32_t i = 0; i < core.count; ++i) {
    h[i] = dot(core.points[i] - o, side);
    if (i == 0 || h[i] < h_min) {
      h_min = h[i];
      i_min = i;
    }
  }
  const float sep_min = h_min - core.radius;
  if (!(sep_min <= speculative_m)) return false;
  const float limit = (speculative_m > sep_min ? speculative_m : sep_min) + kFaceSlab;
  OutlinePoint poly[kMaxOutline];
  uint32_t n = 0;
  for (uint32_t i = 0; i < core.count; ++i) {
    if (!(h[i] - core.radius <= limit)) continue;
    const Vec3 d = core.points[i] - o;
    poly[n++] = {dot(d, t1), dot(d, t2), h[i], i & 15u};
  }
  n = outline_hull(poly, n);
  OutlinePoint outline[kMaxOutline];
  for (uint32_t i = 0; i < n; ++i) outline[i] = poly[i];
  const uint32_t outline_count = n;
  n = clip_outline(poly, n, q, orient);
  if (n == 0 && slack) {
    for (uint32_t i = 0; i < outline_count; ++i) {
      const OutlinePoint& p = outline[i];
      if (!near_triangle(p.u, p.v, q, len, orient)) continue;
      if (n == 0 || p.h < poly[0].h || (p.h == poly[0].h && p.code < poly[0].code)) {
        poly[0] = p;
        n = 1;
      }
    }
  }

  // The outline is the convex hull of the low points seen along the
  // normal, so a tilted shape's deepest corner, lying inside that outline
  // in projection, is not one of its points. It is what the contact must
  // push out first: it is added whenever it lies over the triangle and no
  // point of the clipped outline is as deep.
  {
    const Vec3 d = core.points[i_min] - o;
    const OutlinePoint deepest{dot(d, t1), dot(d, t2), h_min, i_min & 15u};
    bool over = true;
    for (uint32_t e = 0; e < 3; ++e) {
      const float ex = q[(e + 1) % 3][0] - q[e][0];
      const float ey = q[(e + 1) % 3][1] - q[e][1];
      over = over && orient * cross2(ex, ey, deepest.u - q[e][0], deepest.v - q[e][1]) >= 0.0f;
    }
    bool present = false;
    for (uint32_t i = 0; i < n; ++i) present = present || poly[i].h <= h_min;
    if (over && !present && n < kMaxOutline) poly[n++] = deepest;
  }

  out.normal = side;
  out.id = tri.id;
  out.count = 0;
  TrianglePoint pts[kMaxOutline];
  uint32_t m = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const float sep = poly[i].h - core.radius;
    if (!(sep <= speculative_m)) continue;
    pts[m++] = {o + t1 * poly[i].u + t2 * poly[i].v + side * (0.5f * sep), sep,
                (tri.id << kTriangleFeatureShift) | poly[i].code};
  }
  if (m == 0) return false;
  if (m <= kMaxTrianglePoints) {
    for (uint32_t i = 0; i < m; ++i) out.points[out.count++] = pts[i];
  } else {
    uint32_t chosen[4];
    const uint32_t c = reduce_triangle_points(pts, m, side, chosen);
    for (uint32_t i = 0; i < c; ++i) out.points[out.count++] = pts[chosen[i]];
  }
  out.separation = out.points[0].separation;
  for (uint32_t i = 1; i < out.count; ++i) {
    if (out.points[i].separation < out.separation) out.separation = out.points[i].separation;
  }
  return true;
}

}  // namespace triangle_detail

}  // namespace rwd::sim::d3
