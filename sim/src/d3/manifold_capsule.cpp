// SPDX-License-Identifier: MIT
// Capsule manifolds: a capsule is its segment swept by a sphere, so each
// pair is the closest points of the segment and the other shape, pushed
// out by the radius.
//  - capsule-sphere: the closest point of the segment to the centre; one
//    point.
//  - capsule-capsule: the closest points of the two segments; one point,
//    or two where the segments lie side by side (so a capsule resting on
//    another does not roll about a single point).
//  - box-capsule: the closest points of the segment and the box, exactly
//    (the squared distance is a quadratic in the segment parameter between
//    the places where the segment crosses a face plane); two points where
//    the segment lies along a face or along an edge (both ends of the part
//    of it beside the face or the edge, so the push is spread evenly across
//    the box: a plank struck across its width by a pole does not take the
//    whole blow at one corner and roll about its long axis), one otherwise.
//    A segment that reaches into the box is pushed out along the axis of
//    least penetration (separating axis test over the three face normals
//    and the segment crossed with the three edge directions).
// Feature ids: capsule-sphere 0; capsule-capsule 0 (one point), 1 and 2
// (side by side); box-capsule 0x100 | face << 4 | end (along a face), 0x200
// | region of the box point (one point outside), 0x300 | axis (reaching in,
// edge axes), 0x400 | edge << 4 | end (along an edge).
#include <cmath>
#include <limits>

#include "d3/manifold.h"

namespace rwd::sim::d3 {
namespace {

// Segments whose directions' cross product is shorter than this (sin of the
// angle between them) count as side by side.
constexpr float kParallelSin = 0.02f;
// A segment within this (sin of the angle) of a box face's plane lies along
// the face: both its clipped ends become points (those out of reach are
// dropped), so a capsule lying on a box rests on two points, not one.
constexpr float kFaceParallelSin = 0.1f;
// A segment within this (cos of the angle) of a box edge's direction lies
// along the edge: both its clipped ends become points, as along a face.
constexpr float kEdgeParallelCos = 0.995f;  // sqrt(1 - kFaceParallelSin^2)

float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// Any unit vector perpendicular to u.
Vec3 perpendicular(Vec3 u) {
  const Vec3 other = std::fabs(u.x) < 0.6f ? Vec3{1.0f, 0.0f, 0.0f} : Vec3{0.0f, 1.0f, 0.0f};
  return normalize_or_zero(cross(u, other));
}

// One contact between two spheres of radius ra at qa and rb at qb, normal
// from a to b (or, where the centres meet, any normal perpendicular to
// `axis`: worked out only then).
bool sphere_point(Vec3 qa, float ra, Vec3 qb, float rb, Vec3 axis, float speculative_m, uint32_t id,
                  Manifold& out) {
  const Vec3 d = qb - qa;
  const float dist_sq = length_squared(d);
  const float reach = ra + rb + speculative_m;
  if (dist_sq > reach * reach) return false;
  const float dist = std::sqrt(dist_sq);
  const Vec3 n = dist > 1e-9f ? d * (1.0f / dist) : perpendicular(axis);
  out.normal = n;
  out.point_count = 1;
  out.points[0].point = ((qa + n * ra) + (qb - n * rb)) * 0.5f;
  out.points[0].separation = dist - ra - rb;
  out.points[0].feature_id = id;
  return true;
}

}  // namespace

// The closest points of the segments p + s d and q + t e, s and t in
// [0, 1] (Ericson, Real-Time Collision Detection 5.1.9); a segment of zero
// length is a point.
void closest_on_segments(Vec3 p, Vec3 d, Vec3 q, Vec3 e, float& s, float& t) {
  const Vec3 w = p - q;
  const float a = dot(d, d);
  const float b = dot(d, e);
  const float c = dot(e, e);
  const float f = dot(e, w);
  const float g = dot(d, w);
  if (a <= 1e-12f && c <= 1e-12f) {
    s = 0.0f;
    t = 0.0f;
    return;
  }
  if (a <= 1e-12f) {
    s = 0.0f;
    t = clampf(f / c, 0.0f, 1.0f);
    return;
  }
  if (c <= 1e-12f) {
    t = 0.0f;
    s = clampf(-g / a, 0.0f, 1.0f);
    return;
  }
  const float denom = a * c - b * b;
  s = denom > 1e-12f * a * c ? clampf((b * f - g * c) / denom, 0.0f, 1.0f) : 0.0f;
  t = (b * s + f) / c;
  if (t < 0.0f) {
    t = 0.0f;
    s = clampf(-g / a, 0.0f, 1.0f);
  } else if (t > 1.0f) {
    t = 1.0f;
    s = clampf((b - g) / a, 0.0f, 1.0f);
  }
}

void collide_capsule_sphere(const CapsulePose& capsule, Vec3 center, float radius,
                            float speculative_m, Manifold& out) {
  out.point_count = 0;
  const float s =
      clampf(dot(center - capsule.center, capsule.axis), -capsule.half_height, capsule.half_height);
  const Vec3 q = capsule.center + capsule.axis * s;
  sphere_point(q, capsule.radius, center, radius, capsule.axis, speculative_m, 0, out);
}

void collide_capsules(const CapsulePose& a, const CapsulePose& b, float speculative_m,
                      Manifold& out) {
  out.point_count = 0;
  const Vec3 ua = a.axis;
  const Vec3 ub = b.axis;
  const Vec3 w = a.center - b.center;
  const float bb = dot(ua, ub);
  const float aw = dot(ua, w);
  const float bw = dot(ub, w);
  const float denom = 1.0f - bb * bb;  // sin^2 of the angle between the axes
  if (denom > kParallelSin * kParallelSin) {
    // Closest points of the lines, clamped to the segments.
    float s = clampf((bb * bw - aw) / denom, -a.half_height, a.half_height);
    const float t = clampf(bb * s + bw, -b.half_height, b.half_height);
    s = clampf(bb * t - aw, -a.half_height, a.half_height);
    sphere_point(a.center + ua * s, a.radius, b.center + ub * t, b.radius, ua, speculative_m, 0,
                 out);
    return;
  }
  // Side by side: the stretch of A that B's segment covers, seen along A.
  const float s0 = dot(b.center - ub * b.half_height - a.center, ua);
  const float s1 = dot(b.center + ub * b.half_height - a.center, ua);
  const float lo = clampf(s0 < s1 ? s0 : s1, -a.half_height, a.half_height);
  const float hi = clampf(s0 < s1 ? s1 : s0, -a.half_height, a.half_height);
  // The normal from the middle of that stretch, so both points share it.
  const float mid = 0.5f * (lo + hi);
  const Vec3 qa_mid = a.center + ua * mid;
  const float t_mid = clampf(dot(qa_mid - b.center, ub), -b.half_height, b.half_height);
  Manifold one;
  if (!sphere_point(qa_mid, a.radius, b.center + ub * t_mid, b.radius, ua, speculative_m, 0, one)) {
    return;
  }
  if (!(hi - lo > 1e-4f)) {  // end to end: one point
    out = one;
    return;
  }
  const Vec3 n = one.normal;
  out.normal = n;
  out.point_count = 0;
  const float ends[2] = {lo, hi};
  for (int k = 0; k < 2; ++k) {
    const Vec3 qa = a.center + ua * ends[k];
    const float t = clampf(dot(qa - b.center, ub), -b.half_height, b.half_height);
    const Vec3 qb = b.center + ub * t;
    const float separation = dot(qb - qa, n) - a.radius - b.radius;
    if (separation > speculative_m) continue;
    ManifoldPoint& p = out.points[out.point_count++];
    p.point = ((qa + n * a.radius) + (qb - n * b.radius)) * 0.5f;
    p.separation = separation;
    p.feature_id = 1u + static_cast<uint32_t>(k);
  }
}

namespace {

// The segment p0 + s v (s in [0, 1]) and a box of half extents h about the
// origin, all in the box's frame.
struct LocalSegment {
  float p0[3];
  float v[3];
  float h[3];
  float at(int axis, float s) const { return p0[axis] + v[axis] * s; }
  Vec3 point(float s) const { return {at(0, s), at(1, s), at(2, s)}; }
};

// The parameter of the segment's point nearest the box and the squared
// distance there. Between consecutive places where a coordinate crosses a
// face plane, each coordinate is below, within or above the box, so the
// squared distance is one quadratic; its minimum on each piece is closed
// form. Ties go to the lower parameter.
float nearest_parameter(const LocalSegment& seg, float& best_sq) {
  float breaks[8];
  int count = 0;
  breaks[count++] = 0.0f;
  for (int i = 0; i < 3; ++i) {
    if (seg.v[i] == 0.0f) continue;
    for (float side : {-seg.h[i], seg.h[i]}) {
      const float s = (side - seg.p0[i]) / seg.v[i];
      if (s > 0.0f && s < 1.0f) breaks[count++] = s;
    }
  }
  breaks[count++] = 1.0f;
  for (int i = 1; i < count; ++i) {  // insertion sort: at most eight values
    const float x = breaks[i];
    int j = i;
    while (j > 0 && breaks[j - 1] > x) {
      breaks[j] = breaks[j - 1];
      --j;
    }
    breaks[j] = x;
  }
  float best_s = 0.0f;
  best_sq = -1.0f;
  for (int k = 0; k + 1 < count; ++k) {
    const float lo = breaks[k];
    const float hi = breaks[k + 1];
    const float mid = 0.5f * (lo + hi);
    // The quadratic sum over outside axes of (p0 + v s - side)^2.
    float num = 0.0f;
    float den = 0.0f;
    float side[3] = {0.0f, 0.0f, 0.0f};
    bool outside[3] = {false, false, false};
    for (int i = 0; i < 3; ++i) {
      const float x = seg.at(i, mid);
      if (x < -seg.h[i] || x > seg.h[i]) {
        outside[i] = true;
        side[i] = x < 0.0f ? -seg.h[i] : seg.h[i];
        num += seg.v[i] * (side[i] - seg.p0[i]);
        den += seg.v[i] * seg.v[i];
      }
    }
    const float s = den > 0.0f ? clampf(num / den, lo, hi) : lo;
    float sq = 0.0f;
    for (int i = 0; i < 3; ++i) {
      if (!outside[i]) continue;
      const float d = seg.at(i, s) - side[i];
      sq += d * d;
    }
    if (best_sq < 0.0f || sq < best_sq) {
      best_sq = sq;
      best_s = s;
    }
  }
  return best_s;
}

// The part [lo, hi] of the segment whose coordinates on the two axes other
// than `axis` lie within the face (widened by `margin`); false if none.
bool clip_to_face(const LocalSegment& seg, int axis, float margin, float& lo, float& hi) {
  lo = 0.0f;
  hi = 1.0f;
  for (int i = 0; i < 3; ++i) {
    if (i == axis) continue;
    const float limit = seg.h[i] + margin;
    if (seg.v[i] == 0.0f) {
      if (seg.p0[i] < -limit || seg.p0[i] > limit) return false;
      continue;
    }
    float t0 = (-limit - seg.p0[i]) / seg.v[i];
    float t1 = (limit - seg.p0[i]) / seg.v[i];
    if (t0 > t1) {
      const float t = t0;
      t0 = t1;
      t1 = t;
    }
    if (t0 > lo) lo = t0;
    if (t1 < hi) hi = t1;
  }
  return lo <= hi;
}

// Side planes are widened by this much when clipping along a face, as for
// box-box (manifold_box_box.cpp), so an end exactly on an edge is kept.
constexpr float kClipMargin = 0.001f;  // metres

// Points along face `axis` on side `sign` of the box for the clipped part
// of the segment, in the box's frame; returns how many (their separations
// within speculative_m).
void face_points(const LocalSegment& seg, int axis, float sign, float radius, float speculative_m,
                 const BoxPose& box, Manifold& out) {
  out.point_count = 0;
  float lo = 0.0f;
  float hi = 1.0f;
  if (!clip_to_face(seg, axis, kClipMargin, lo, hi)) return;
  float n_local[3] = {0.0f, 0.0f, 0.0f};
  n_local[axis] = sign;
  const Vec3 n_box{n_local[0], n_local[1], n_local[2]};
  out.normal = rotate(box.rotation, n_box);
  const uint32_t face = static_cast<uint32_t>(axis) * 2u + (sign > 0.0f ? 1u : 0u);
  const float ends[2] = {lo, hi};
  const int count = hi - lo > 1e-6f ? 2 : 1;
  for (int k = 0; k < count; ++k) {
    const Vec3 p = seg.point(ends[k]);
    const float height = sign * component(p, axis) - seg.h[axis];
    const float separation = height - radius;
    if (separation > speculative_m) continue;
    // Midway between the capsule's surface and the face plane.
    const Vec3 mid_local = p - n_box * (radius + 0.5f * separation);
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = box.center + rotate(box.rotation, mid_local);
    mp.separation = separation;
    mp.feature_id = 0x100u | (face << 4) | static_cast<uint32_t>(k);
  }
}

// The part [lo, hi] of the segment whose coordinate along `axis` lies
// within the box (widened by the clip margin); false if it is a point or
// nothing.
bool clip_along(const LocalSegment& seg, int axis, float& lo, float& hi) {
  const float v = seg.v[axis];
  if (v == 0.0f) return false;
  const float limit = seg.h[axis] + kClipMargin;
  lo = (-limit - seg.p0[axis]) / v;
  hi = (limit - seg.p0[axis]) / v;
  if (lo > hi) {
    const float t = lo;
    lo = hi;
    hi = t;
  }
  lo = clampf(lo, 0.0f, 1.0f);
  hi = clampf(hi, 0.0f, 1.0f);
  return hi - lo > 1e-6f;
}

// Points at the ends [lo, hi] of the part of the segment beside the box
// edge in direction `axis` whose other two coordinates are those of `edge`
// (each on a face plane), all sharing the normal `n` (the box's frame). The
// separation at each end is measured along n from the edge, as for
// capsules side by side.
void edge_points(const LocalSegment& seg, int axis, float lo, float hi, Vec3 edge, Vec3 n,
                 float radius, float speculative_m, const BoxPose& box, Manifold& out) {
  out.point_count = 0;
  out.normal = rotate(box.rotation, n);
  // Which edge: its direction and the sides of the other two axes.
  uint32_t edge_id = static_cast<uint32_t>(axis) * 4u;
  uint32_t bit = 1u;
  for (int i = 0; i < 3; ++i) {
    if (i == axis) continue;
    if (component(edge, i) > 0.0f) edge_id |= bit;
    bit <<= 1;
  }
  const float ends[2] = {lo, hi};
  for (int k = 0; k < 2; ++k) {
    const Vec3 p = seg.point(ends[k]);
    float e[3] = {edge.x, edge.y, edge.z};
    e[axis] = clampf(component(p, axis), -seg.h[axis], seg.h[axis]);
    const Vec3 on_edge{e[0], e[1], e[2]};
    const float separation = dot(p - on_edge, n) - radius;
    if (separation > speculative_m) continue;
    const Vec3 mid_local = (on_edge + (p - n * radius)) * 0.5f;
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = box.center + rotate(box.rotation, mid_local);
    mp.separation = separation;
    mp.feature_id = 0x400u | (edge_id << 4) | static_cast<uint32_t>(k);
  }
}

// A coordinate of the segment's nearest point within this of a face plane
// lies on it: the nearest point found at a break (where the segment
// crosses a side plane) lands on either side of that plane by rounding,
// and a segment along a face must not read as one beyond its edge.
float on_plane_tolerance(const LocalSegment& seg, int axis, float length_m) {
  return 1e-5f * (1.0f + seg.h[axis] + length_m);
}

}  // namespace

void collide_box_capsule(const BoxPose& box, const CapsulePose& capsule, float speculative_m,
                         Manifold& out) {
  out.point_count = 0;
  const Vec3 c = inv_rotate(box.rotation, capsule.center - box.center);
  const Vec3 u = inv_rotate(box.rotation, capsule.axis);
  const Vec3 p0 = c - u * capsule.half_height;
  const Vec3 v = u * (2.0f * capsule.half_height);
  LocalSegment seg{{p0.x, p0.y, p0.z},
                   {v.x, v.y, v.z},
                   {box.half_extents.x, box.half_extents.y, box.half_extents.z}};
  const float r = capsule.radius;
  float dist_sq = 0.0f;
  const float s = nearest_parameter(seg, dist_sq);
  if (dist_sq > 0.0f) {
    const float reach = r + speculative_m;
    if (dist_sq > reach * reach) return;
    const Vec3 p = seg.point(s);
    const Vec3 q{clampf(p.x, -seg.h[0], seg.h[0]), clampf(p.y, -seg.h[1], seg.h[1]),
                 clampf(p.z, -seg.h[2], seg.h[2])};
    // Along a face: one coordinate outside (a coordinate within rounding of
    // a face plane is on it), and the segment nearly parallel to that face.
    // Along an edge: two outside, and the segment nearly parallel to the
    // third axis.
    const float len = length(v);
    int outside = 0;
    int axis = 0;
    int along = 0;
    for (int i = 0; i < 3; ++i) {
      if (std::fabs(component(p, i) - component(q, i)) > on_plane_tolerance(seg, i, len)) {
        ++outside;
        axis = i;
      } else {
        along = i;
      }
    }
    if (outside == 1 && std::fabs(component(v, axis)) <= kFaceParallelSin * len) {
      face_points(seg, axis, component(p, axis) > 0.0f ? 1.0f : -1.0f, r, speculative_m, box, out);
      if (out.point_count > 0) return;
    }
    float lo = 0.0f;
    float hi = 0.0f;
    if (outside == 2 && std::fabs(component(v, along)) >= kEdgeParallelCos * len &&
        clip_along(seg, along, lo, hi)) {
      // Both points share the normal at the nearest point, square to the
      // edge (q is on it: its other two coordinates are clamped onto face
      // planes). Where that point is inside the part beside the edge, the
      // segment is square to the normal there, so both ends are as far
      // along it as the nearest point.
      float off[3] = {p.x - q.x, p.y - q.y, p.z - q.z};
      off[along] = 0.0f;
      const Vec3 n = normalize_or_zero(Vec3{off[0], off[1], off[2]});
      if (length_squared(n) > 0.0f) {
        edge_points(seg, along, lo, hi, q, n, r, speculative_m, box, out);
        if (out.point_count > 0) return;
      }
    }
    const float dist = std::sqrt(dist_sq);
    const Vec3 n_local = (p - q) * (1.0f / dist);
    auto region = [](float x, float half) -> uint32_t {
      return x < -half ? 0u : (x > half ? 2u : 1u);
    };
    out.normal = rotate(box.rotation, n_local);
    out.point_count = 1;
    const Vec3 surface = p - n_local * r;
    out.points[0].point = box.center + rotate(box.rotation, (q + surface) * 0.5f);
    out.points[0].separation = dist - r;
    out.points[0].feature_id =
        0x200u | (region(p.x, seg.h[0]) + 3u * region(p.y, seg.h[1]) + 9u * region(p.z, seg.h[2]));
    return;
  }
  // The segment reaches into the box: the axis of least penetration among
  // the face normals and the segment crossed with each edge direction.
  float best = -std::numeric_limits<float>::max();
  int best_axis = 0;
  Vec3 best_normal;
  for (int i = 0; i < 6; ++i) {
    Vec3 l;
    if (i < 3) {
      float e[3] = {0.0f, 0.0f, 0.0f};
      e[i] = 1.0f;
      l = {e[0], e[1], e[2]};
    } else {
      float e[3] = {0.0f, 0.0f, 0.0f};
      e[i - 3] = 1.0f;
      l = cross(v, Vec3{e[0], e[1], e[2]});
      const float l_sq = length_squared(l);
      if (l_sq < 1e-12f * length_squared(v)) continue;  // parallel: a face axis covers it
      l = l * (1.0f / std::sqrt(l_sq));
    }
    const float a0 = dot(l, p0);
    const float a1 = dot(l, p0 + v);
    const float seg_lo = a0 < a1 ? a0 : a1;
    const float seg_hi = a0 < a1 ? a1 : a0;
    const float box_r =
        seg.h[0] * std::fabs(l.x) + seg.h[1] * std::fabs(l.y) + seg.h[2] * std::fabs(l.z);
    // Positive side: push the segment toward +l; negative: toward -l.
    const float up = box_r - seg_lo;    // how far it must move along +l
    const float down = seg_hi + box_r;  // ... along -l
    const float sep = -(up < down ? up : down);
    if (sep > best + 1e-6f) {  // face axes (tested first) win near-ties
      best = sep;
      best_axis = i;
      best_normal = up < down ? l : -l;
    }
  }
  if (best_axis < 3) {
    const float sign = component(best_normal, best_axis);
    face_points(seg, best_axis, sign, r, speculative_m, box, out);
    if (out.point_count > 0) return;
  }
  // An edge axis (or a face whose clip left nothing): one point, between
  // the segment and the box's edge (or corner) farthest along the normal;
  // two, at the ends of the part beside the edge, where the segment lies
  // along the edge.
  const Vec3 n = best_normal;
  const int k = best_axis < 3 ? -1 : best_axis - 3;  // the edge's direction
  float lo = 0.0f;
  float hi = 0.0f;
  if (k >= 0 && std::fabs(component(v, k)) >= kEdgeParallelCos * length(v) &&
      clip_along(seg, k, lo, hi)) {
    float edge[3];
    for (int i = 0; i < 3; ++i) edge[i] = component(n, i) >= 0.0f ? seg.h[i] : -seg.h[i];
    edge_points(seg, k, lo, hi, Vec3{edge[0], edge[1], edge[2]}, n, r, speculative_m, box, out);
    if (out.point_count > 0) return;
  }
  float e0[3];
  float ed[3] = {0.0f, 0.0f, 0.0f};
  for (int i = 0; i < 3; ++i) {
    e0[i] = component(n, i) >= 0.0f ? seg.h[i] : -seg.h[i];
    if (i == k) {
      e0[i] = -seg.h[i];
      ed[i] = 2.0f * seg.h[i];
    }
  }
  float ss = 0.0f;
  float tt = 0.0f;
  closest_on_segments(p0, v, Vec3{e0[0], e0[1], e0[2]}, Vec3{ed[0], ed[1], ed[2]}, ss, tt);
  const Vec3 on_segment = p0 + v * ss;
  const Vec3 on_box = Vec3{e0[0], e0[1], e0[2]} + Vec3{ed[0], ed[1], ed[2]} * tt;
  const float separation = dot(on_segment - on_box, n) - r;
  if (separation > speculative_m) return;
  const Vec3 mid_local = (on_box + (on_segment - n * r)) * 0.5f;
  out.normal = rotate(box.rotation, n);
  out.point_count = 1;
  out.points[0].point = box.center + rotate(box.rotation, mid_local);
  out.points[0].separation = separation;
  out.points[0].feature_id = 0x300u | static_cast<uint32_t>(best_axis);
}

}  // namespace rwd::sim::d3
