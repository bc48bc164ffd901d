// SPDX-License-Identifier: MIT
// Hull-sphere and hull-capsule manifolds. A sphere is its centre and a
// capsule its segment, each rounded by the radius, so each pair is the
// closest points of a point or segment and the hull, pushed out by the
// radius. All work is in the hull's mass frame.
//  - Face test first: the separation of the point (the segment's lower end)
//    above each face plane. The greatest is a lower bound on the distance,
//    so beyond reach there is no contact and GJK is skipped.
//  - Outside: GJK gives the closest points. Where GJK's normal is a face's
//    normal (the closest point within kFaceLateral of the face's normal
//    prism), the closest hull point lies on that face: its exact plane
//    normal and plane distance are used, not GJK's, so a shape resting on
//    a face sees the same normal every step.
//  - Touching (closer than kTouchDistance, where GJK's normal would be
//    rounding noise) or reaching in: a point goes out through the face of
//    least penetration; a segment by a separating axis test over the face
//    normals and the segment crossed with the edges whose faces' normals
//    straddle it (the Minkowski difference's faces, so the test is exact).
//  - A segment along a face (within kFaceParallelSin of its plane) is
//    clipped by the face's side planes: two points, so a capsule lying on a
//    hull rests on both ends, as box-capsule does. A segment along the edge
//    GJK finds closest (within kEdgeParallelCos of its direction) is
//    clipped to the edge's length: two points sharing GJK's normal, as
//    box-capsule does, so a pole beside a plank's edge pushes both ends of
//    it alike.
//
// Feature ids, kind in bits 16-19:
//   face    (1 << 16) | face << 8 | k   the point lies over hull face `face`
//           (Hull::faces index). Sphere: k = 0. Capsule: for two points
//           along a face k = 0 at the clipped end toward the capsule's
//           -axis end and 1 toward its +axis end; for one point k is the
//           capsule end it comes from (0 = centre - axis * half_height,
//           1 = centre + axis * half_height), so a capsule tipping from
//           lying to leaning keeps its lower point's id.
//   edge    (2 << 16) | v_hi << 8 | v_lo  the closest hull point lies on the
//           edge between vertices v_lo < v_hi (Hull::vertices indices).
//           Two points along the edge: k << 20 added, k = 1 at the clipped
//           end toward the capsule's -axis end and 2 toward its +axis end.
//   vertex  (3 << 16) | v   the closest hull point is vertex v.
//   axis    (4 << 16) | e   a segment reaching in, pushed out along the
//           segment crossed with hull edge e (Hull::edges index).
#include <cmath>
#include <limits>

#include "d3/gjk.h"
#include "d3/manifold_hull.h"

namespace rwd::sim::d3 {
namespace {

using gjk_detail::mul_transpose;

// Below this distance between the cores (metres) GJK's normal is mostly
// rounding (its closest point is good to about 1e-7 of the shapes' size),
// so the contact is treated as touching and resolved by faces and axes.
constexpr float kTouchDistance = 1e-4f;
// GJK's closest point within this lateral distance (metres) of a face's
// normal prism (|normal - face normal| * distance) lies on the face: then
// the face's exact plane normal is used. Well above GJK's rounding (about
// 1e-7 of the shapes' size), well below the side planes' clip margin.
constexpr float kFaceLateral = 1e-5f;
// As box-capsule: a segment within this (sin of the angle) of a face's
// plane lies along the face and gets two points.
constexpr float kFaceParallelSin = 0.1f;
// As box-capsule: a segment within this (cos of the angle) of an edge's
// direction lies along the edge and gets two points.
constexpr float kEdgeParallelCos = 0.995f;
// Side planes are widened by this much when clipping along a face, as for
// box-capsule, so an end exactly over an edge is kept (metres).
constexpr float kClipMargin = 0.001f;
// An edge axis must beat the best face by this much (metres): faces give
// two points and a steadier normal, so they win near-ties.
constexpr float kEdgeBias = 1e-6f;

constexpr uint32_t kFaceKind = 1u << 16;
constexpr uint32_t kEdgeKind = 2u << 16;
constexpr uint32_t kVertexKind = 3u << 16;
constexpr uint32_t kAxisKind = 4u << 16;

uint32_t face_id(uint32_t face, uint32_t k) {
  return kFaceKind | (face << 8) | k;
}

// A proxy of the hull (identity pose: GJK then works in the mass frame).
ConvexProxy hull_proxy(const Hull& hull) {
  ConvexProxy p;
  p.points = hull.vertices.data();
  p.count = static_cast<uint32_t>(hull.vertices.size());
  return p;
}

// The face whose plane the points (the lower of the `count` points) lie
// farthest above, and that separation; ties go to the lower index.
uint32_t best_face(const Hull& hull, const Vec3* points, int count, float& separation) {
  uint32_t best = 0;
  separation = -std::numeric_limits<float>::max();
  for (uint32_t i = 0; i < hull.faces.size(); ++i) {
    const HullFace& f = hull.faces[i];
    float s = dot(f.normal, points[0]) - f.offset;
    for (int k = 1; k < count; ++k) {
      const float sk = dot(f.normal, points[k]) - f.offset;
      if (sk < s) s = sk;
    }
    if (i == 0 || s > separation) {
      separation = s;
      best = i;
    }
  }
  return best;
}

// The face whose normal is nearest n; ties go to the lower index.
uint32_t aligned_face(const Hull& hull, Vec3 n) {
  uint32_t face = 0;
  float best = -std::numeric_limits<float>::max();
  for (uint32_t i = 0; i < hull.faces.size(); ++i) {
    const float d = dot(hull.faces[i].normal, n);
    if (d > best) {
      best = d;
      face = i;
    }
  }
  return face;
}

// Whether GJK's normal n at distance d is face f's normal: the closest
// hull point then lies on that face.
bool on_face(const HullFace& f, Vec3 n, float d) {
  return length_squared(n - f.normal) * (d * d) <= kFaceLateral * kFaceLateral;
}

// The hull feature of GJK's closest point: the distinct hull vertices of
// its final simplex (one: a vertex, two: an edge; more: a face, the one
// best aligned with the normal).
uint32_t simplex_feature(const Hull& hull, const GjkSimplex& s, Vec3 n) {
  uint32_t idx[4];
  uint32_t count = 0;
  for (uint32_t i = 0; i < s.count; ++i) {
    const uint32_t v = s.v[i].index_a;
    bool seen = false;
    for (uint32_t k = 0; k < count; ++k) seen = seen || idx[k] == v;
    if (!seen) idx[count++] = v;
  }
  if (count == 1) return kVertexKind | idx[0];
  if (count == 2) {
    const uint32_t lo = idx[0] < idx[1] ? idx[0] : idx[1];
    const uint32_t hi = idx[0] < idx[1] ? idx[1] : idx[0];
    return kEdgeKind | (hi << 8) | lo;
  }
  return face_id(aligned_face(hull, n), 0);
}

// Writes one point: hull surface point q, the other shape's core point p
// with radius r, normal n (hull frame), separation.
void one_point(Vec3 hull_position, const Mat3& hull_axes, Vec3 n, Vec3 q, Vec3 p, float r,
               float separation, uint32_t id, Manifold& out) {
  out.normal = hull_axes * n;
  out.point_count = 1;
  out.points[0].point = hull_position + hull_axes * ((q + (p - n * r)) * 0.5f);
  out.points[0].separation = separation;
  out.points[0].feature_id = id;
}

// The part [lo, hi] of the segment p0 + s v (s in [0, 1]) inside the side
// planes of `face` widened by `margin`; false if none.
bool clip_to_face(const Hull& hull, const HullFace& face, Vec3 p0, Vec3 v, float margin, float& lo,
                  float& hi) {
  lo = 0.0f;
  hi = 1.0f;
  for (uint32_t k = 0; k < face.count; ++k) {
    const uint32_t next = k + 1 == face.count ? 0u : k + 1;
    const Vec3 a = hull.vertices[hull.face_vertices[face.first + k]];
    const Vec3 b = hull.vertices[hull.face_vertices[face.first + next]];
    // The loop runs counter-clockwise about the normal: n x edge points in.
    const Vec3 m = normalize_or_zero(cross(face.normal, b - a));
    const float h0 = dot(m, p0 - a) + margin;  // inside when >= 0
    const float dv = dot(m, v);
    if (dv == 0.0f) {
      if (h0 < 0.0f) return false;
      continue;
    }
    const float t = -h0 / dv;
    if (dv > 0.0f) {
      if (t > lo) lo = t;
    } else if (t < hi) {
      hi = t;
    }
  }
  return lo <= hi;
}

// Points along face `fi` for the clipped part of the segment (up to two,
// those within speculative_m); point_count 0 when the clip leaves nothing.
void face_points(const Hull& hull, uint32_t fi, Vec3 p0, Vec3 v, float radius, float speculative_m,
                 Vec3 hull_position, const Mat3& hull_axes, Manifold& out) {
  out.point_count = 0;
  const HullFace& face = hull.faces[fi];
  float lo = 0.0f;
  float hi = 1.0f;
  if (!clip_to_face(hull, face, p0, v, kClipMargin, lo, hi)) return;
  const Vec3 n = face.normal;
  out.normal = hull_axes * n;
  const float ends[2] = {lo, hi};
  const int count = hi - lo > 1e-6f ? 2 : 1;
  for (int k = 0; k < count; ++k) {
    const Vec3 p = p0 + v * ends[k];
    const float separation = dot(n, p) - face.offset - radius;
    if (separation > speculative_m) continue;
    // Midway between the capsule's surface and the face plane.
    const Vec3 mid = p - n * (radius + 0.5f * separation);
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = hull_position + hull_axes * mid;
    mp.separation = separation;
    mp.feature_id = face_id(fi, static_cast<uint32_t>(k));
  }
}

// Points along the hull edge of feature id `edge` (GJK's closest, normal n)
// for the part of the segment beside it (its projection onto the edge
// within the edge, widened by the clip margin), when the segment lies along
// the edge; point_count 0 otherwise.
void edge_points(const Hull& hull, uint32_t edge, Vec3 p0, Vec3 v, Vec3 n, float radius,
                 float speculative_m, Vec3 hull_position, const Mat3& hull_axes, Manifold& out) {
  out.point_count = 0;
  const Vec3 a = hull.vertices[edge & 0xFFu];
  const Vec3 ed = hull.vertices[(edge >> 8) & 0xFFu] - a;
  const float ed_sq = length_squared(ed);
  const float v_sq = length_squared(v);
  const float along = dot(v, ed);
  if (!(ed_sq > 0.0f) || along * along < kEdgeParallelCos * kEdgeParallelCos * ed_sq * v_sq) {
    return;
  }
  // The edge parameter at segment parameter s is t0 + dt s.
  const float t0 = dot(p0 - a, ed) / ed_sq;
  const float dt = along / ed_sq;
  const float margin = kClipMargin / std::sqrt(ed_sq);
  float lo = (-margin - t0) / dt;
  float hi = (1.0f + margin - t0) / dt;
  if (lo > hi) {
    const float t = lo;
    lo = hi;
    hi = t;
  }
  lo = lo < 0.0f ? 0.0f : (lo > 1.0f ? 1.0f : lo);
  hi = hi < 0.0f ? 0.0f : (hi > 1.0f ? 1.0f : hi);
  if (!(hi - lo > 1e-6f)) return;
  out.normal = hull_axes * n;
  const float ends[2] = {lo, hi};
  for (uint32_t k = 0; k < 2; ++k) {
    const Vec3 p = p0 + v * ends[k];
    float t = t0 + dt * ends[k];
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    const Vec3 on_edge = a + ed * t;
    const float separation = dot(p - on_edge, n) - radius;
    if (separation > speculative_m) continue;
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = hull_position + hull_axes * ((on_edge + (p - n * radius)) * 0.5f);
    mp.separation = separation;
    mp.feature_id = edge | ((k + 1u) << 20);
  }
}

// One point on face `fi` from the capsule end nearer its plane.
void face_end_point(const Hull& hull, uint32_t fi, const Vec3 seg[2], float radius,
                    float speculative_m, Vec3 hull_position, const Mat3& hull_axes, Manifold& out) {
  out.point_count = 0;
  const HullFace& face = hull.faces[fi];
  const float h0 = dot(face.normal, seg[0]) - face.offset;
  const float h1 = dot(face.normal, seg[1]) - face.offset;
  const uint32_t end = h1 < h0 ? 1u : 0u;
  const float height = end == 1u ? h1 : h0;
  const float separation = height - radius;
  if (separation > speculative_m) return;
  const Vec3 p = seg[end];
  one_point(hull_position, hull_axes, face.normal, p - face.normal * height, p, radius, separation,
            face_id(fi, end), out);
}

}  // namespace

void collide_hull_sphere(const Hull& hull, Vec3 hull_position, const Mat3& hull_axes, Vec3 center,
                         float radius, float speculative_m, Manifold& out) {
  out.point_count = 0;
  if (hull.vertices.empty() || hull.faces.empty()) return;
  const Vec3 c = mul_transpose(hull_axes, center - hull_position);
  float s = 0.0f;
  const uint32_t fi = best_face(hull, &c, 1, s);
  const HullFace& face = hull.faces[fi];
  const float reach = radius + speculative_m;
  if (s > reach) return;  // the face's plane separates them
  if (s > 0.0f) {
    // Outside: GJK for the closest hull point.
    ConvexProxy point;
    point.points = &c;
    point.count = 1;
    const GjkOutput g = gjk_distance(hull_proxy(hull), point);
    if (!g.overlap && g.distance > reach) return;
    if (!g.overlap && g.distance >= kTouchDistance) {
      const uint32_t fn = aligned_face(hull, g.normal);
      const HullFace& on = hull.faces[fn];
      if (!on_face(on, g.normal, g.distance)) {
        one_point(hull_position, hull_axes, g.normal, g.point_a, c, radius, g.distance - radius,
                  simplex_feature(hull, g.simplex, g.normal), out);
        return;
      }
      // Over a face: its exact plane normal and distance.
      const float h = dot(on.normal, c) - on.offset;
      one_point(hull_position, hull_axes, on.normal, c - on.normal * h, c, radius, h - radius,
                face_id(fn, 0), out);
      return;
    }
  }
  // Inside or touching: out through the face of least penetration,
  // exactly along its plane normal.
  const Vec3 n = face.normal;
  one_point(hull_position, hull_axes, n, c - n * s, c, radius, s - radius, face_id(fi, 0), out);
}

void collide_hull_capsule(const Hull& hull, Vec3 hull_position, const Mat3& hull_axes,
                          const CapsulePose& capsule, float speculative_m, Manifold& out) {
  out.point_count = 0;
  if (hull.vertices.empty() || hull.faces.empty()) return;
  const Vec3 c = mul_transpose(hull_axes, capsule.center - hull_position);
  const Vec3 u = mul_transpose(hull_axes, capsule.axis);
  const Vec3 seg[2] = {c - u * capsule.half_height, c + u * capsule.half_height};
  const Vec3 v = seg[1] - seg[0];
  const float r = capsule.radius;
  const float reach = r + speculative_m;
  float s = 0.0f;
  const uint32_t fi = best_face(hull, seg, 2, s);
  if (s > reach) return;  // the face's plane separates them

  ConvexProxy segment;
  segment.points = seg;
  segment.count = 2;
  const GjkOutput g = gjk_distance(hull_proxy(hull), segment);
  if (!g.overlap && g.distance > reach) return;
  if (!g.overlap && g.distance >= kTouchDistance) {
    // The face GJK's normal points along, if it does: then the closest hull
    // point lies on it. (The face test's separation is no guide here: the
    // segment's lower end may hang beyond the face.)
    const uint32_t fn = aligned_face(hull, g.normal);
    const HullFace& face = hull.faces[fn];
    if (on_face(face, g.normal, g.distance)) {
      if (std::fabs(dot(u, face.normal)) <= kFaceParallelSin) {
        face_points(hull, fn, seg[0], v, r, speculative_m, hull_position, hull_axes, out);
        if (out.point_count > 0) return;
      } else {
        // One point, at GJK's closest point of the segment (its lower end
        // but for rounding), measured from the face's plane.
        const Vec3 p = g.point_b;
        const float height = dot(face.normal, p) - face.offset;
        const float separation = height - r;
        if (separation > speculative_m) return;
        const uint32_t end = dot(face.normal, seg[1]) < dot(face.normal, seg[0]) ? 1u : 0u;
        one_point(hull_position, hull_axes, face.normal, p - face.normal * height, p, r, separation,
                  face_id(fn, end), out);
        return;
      }
    }
    // An edge or a vertex of the hull is closest: one point, GJK's; two
    // where the segment lies along the edge.
    const uint32_t feature = simplex_feature(hull, g.simplex, g.normal);
    if ((feature & (0xFu << 16)) == kEdgeKind) {
      edge_points(hull, feature, seg[0], v, g.normal, r, speculative_m, hull_position, hull_axes,
                  out);
      if (out.point_count > 0) return;
    }
    one_point(hull_position, hull_axes, g.normal, g.point_a, g.point_b, r, g.distance - r, feature,
              out);
    return;
  }

  // Touching or reaching in: the axis of least penetration among the face
  // normals and the segment crossed with each edge whose two faces' normals
  // lie on opposite sides of the plane perpendicular to the segment (only
  // those edges and the segment make faces of the Minkowski difference).
  // The face separations are the face test's above.
  float best = s;
  int best_edge = -1;
  Vec3 best_normal = hull.faces[fi].normal;
  for (uint32_t i = 0; i < hull.edges.size(); ++i) {
    const HullEdge& e = hull.edges[i];
    const Vec3 nl = hull.faces[e.face_left].normal;
    const Vec3 nr = hull.faces[e.face_right].normal;
    if (!(dot(u, nl) * dot(u, nr) < 0.0f)) continue;
    const Vec3 a = hull.vertices[e.v0];
    const Vec3 ed = hull.vertices[e.v1] - a;
    Vec3 m = cross(u, ed);
    const float m_sq = length_squared(m);
    if (!(m_sq > 1e-12f * length_squared(ed))) continue;  // along the edge: a face covers it
    m = m * (1.0f / std::sqrt(m_sq));
    // The edge is the hull's support along m only on the side between its
    // faces' normals.
    if (dot(m, nl + nr) < 0.0f) m = -m;
    const float s0 = dot(m, seg[0]);
    const float s1 = dot(m, seg[1]);
    const float sep = (s0 < s1 ? s0 : s1) - dot(m, a);
    if (sep > best + kEdgeBias) {
      best = sep;
      best_edge = static_cast<int>(i);
      best_normal = m;
    }
  }
  if (best_edge < 0) {
    face_points(hull, fi, seg[0], v, r, speculative_m, hull_position, hull_axes, out);
    if (out.point_count > 0) return;
    face_end_point(hull, fi, seg, r, speculative_m, hull_position, hull_axes, out);
    return;
  }
  // An edge axis: one point, between the segment and that edge.
  const HullEdge& e = hull.edges[static_cast<uint32_t>(best_edge)];
  const Vec3 a = hull.vertices[e.v0];
  const Vec3 ed = hull.vertices[e.v1] - a;
  float ss = 0.0f;
  float tt = 0.0f;
  closest_on_segments(seg[0], v, a, ed, ss, tt);
  const Vec3 on_segment = seg[0] + v * ss;
  const Vec3 on_edge = a + ed * tt;
  const float separation = dot(on_segment - on_edge, best_normal) - r;
  if (separation > speculative_m) return;
  one_point(hull_position, hull_axes, best_normal, on_edge, on_segment, r, separation,
            kAxisKind | static_cast<uint32_t>(best_edge), out);
}

}  // namespace rwd::sim::d3
