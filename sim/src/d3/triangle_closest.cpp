// SPDX-License-Identifier: MIT
// Point and segment against a triangle (triangle_closest.h). A segment that
// does not cross the triangle is nearest it at one of its ends (against the
// triangle) or along one of the triangle's edges (segment against segment);
// one that crosses it overlaps. Every candidate is tried in a fixed order
// and the first of equal distances kept, so the answer is a pure function
// of the inputs.
#include "d3/triangle_closest.h"

#include <cmath>

#include "d3/gjk.h"

namespace rwd::sim::d3 {
namespace {

// The triangle's point nearest q.
Vec3 on_triangle(const Vec3 p[3], Vec3 q) {
  float weights[3];
  return q + gjk_detail::closest_on_triangle(p[0] - q, p[1] - q, p[2] - q, weights);
}

float clamp01(float v) {
  return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
}

// Closest points of segments p1 q1 and p2 q2 (Ericson 5.1.9), into c1, c2.
void closest_segments(Vec3 p1, Vec3 q1, Vec3 p2, Vec3 q2, Vec3& c1, Vec3& c2) {
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const float a = dot(d1, d1);
  const float e = dot(d2, d2);
  const float f = dot(d2, r);
  float s = 0.0f;
  float t = 0.0f;
  if (a <= 0.0f && e <= 0.0f) {
    c1 = p1;
    c2 = p2;
    return;
  }
  if (a <= 0.0f) {
    t = clamp01(f / e);
  } else {
    const float c = dot(d1, r);
    if (e <= 0.0f) {
      s = clamp01(-c / a);
    } else {
      const float b = dot(d1, d2);
      const float denom = a * e - b * b;
      // Parallel (or nearly): any s will do; 0 is the fixed choice.
      s = denom > 1e-12f * a * e ? clamp01((b * f - c * e) / denom) : 0.0f;
      t = (b * s + f) / e;
      if (t < 0.0f) {
        t = 0.0f;
        s = clamp01(-c / a);
      } else if (t > 1.0f) {
        t = 1.0f;
        s = clamp01((b - c) / a);
      }
    }
  }
  c1 = p1 + d1 * s;
  c2 = p2 + d2 * t;
}

// Whether segment s0 s1 crosses the triangle's plane inside the triangle.
bool crosses(const Vec3 p[3], Vec3 n, Vec3 s0, Vec3 s1) {
  const float d0 = dot(s0 - p[0], n);
  const float d1 = dot(s1 - p[0], n);
  if ((d0 > 0.0f && d1 > 0.0f) || (d0 < 0.0f && d1 < 0.0f) || d0 == d1) return false;
  const Vec3 x = s0 + (s1 - s0) * (d0 / (d0 - d1));
  // Inside: on the inner side of all three edges (about n).
  for (int i = 0; i < 3; ++i) {
    if (dot(cross(p[(i + 1) % 3] - p[i], x - p[i]), n) < 0.0f) return false;
  }
  return true;
}

}  // namespace

CoreTriangleClosest closest_core_triangle(const Vec3* points, uint32_t count, const Vec3 p[3],
                                          Vec3 n) {
  CoreTriangleClosest out;
  out.on_core = points[0];
  out.on_tri = on_triangle(p, points[0]);
  float best_sq = length_squared(out.on_core - out.on_tri);
  if (count > 1) {
    const Vec3 s0 = points[0];
    const Vec3 s1 = points[1];
    if (!(n == Vec3{}) && crosses(p, n, s0, s1)) {
      out.overlap = true;
      return out;
    }
    const auto consider = [&](Vec3 on_core, Vec3 on_tri) {
      const float d_sq = length_squared(on_core - on_tri);
      if (d_sq < best_sq) {
        best_sq = d_sq;
        out.on_core = on_core;
        out.on_tri = on_tri;
      }
    };
    consider(s1, on_triangle(p, s1));
    for (int i = 0; i < 3; ++i) {
      Vec3 on_core;
      Vec3 on_tri;
      closest_segments(s0, s1, p[i], p[(i + 1) % 3], on_core, on_tri);
      consider(on_core, on_tri);
    }
  }
  out.distance = std::sqrt(best_sq);
  if (!(out.distance > kGjkOverlapDistance)) {
    out.overlap = true;
    return out;
  }
  out.normal = (out.on_core - out.on_tri) * (1.0f / out.distance);
  return out;
}

PointTriangleClosest closest_point_triangle(Vec3 q, const Vec3 p[3]) {
  PointTriangleClosest out;
  const auto at = [&](Vec3 point, TriangleFeature feature, uint32_t index) {
    out.point = point;
    out.distance_sq = length_squared(q - point);
    out.feature = feature;
    out.index = index;
    return out;
  };
  // Each denominator is a squared length or area, positive for a triangle
  // with an area; a sliver whose rounding makes it zero gets the feature's
  // first point rather than a NaN.
  const auto ratio = [](float num, float den) { return den > 0.0f ? num / den : 0.0f; };
  // The region tests work on q's projections onto the two edges from each
  // corner; each feature is tried once, vertices before the edges they
  // bound, so every q lands in exactly one region.
  const Vec3 ab = p[1] - p[0];
  const Vec3 ac = p[2] - p[0];
  const Vec3 aq = q - p[0];
  const float d1 = dot(ab, aq);
  const float d2 = dot(ac, aq);
  if (d1 <= 0.0f && d2 <= 0.0f) return at(p[0], TriangleFeature::kVertex, 0);
  const Vec3 bq = q - p[1];
  const float d3 = dot(ab, bq);
  const float d4 = dot(ac, bq);
  if (d3 >= 0.0f && d4 <= d3) return at(p[1], TriangleFeature::kVertex, 1);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    return at(p[0] + ab * ratio(d1, d1 - d3), TriangleFeature::kEdge, 0);
  }
  const Vec3 cq = q - p[2];
  const float d5 = dot(ab, cq);
  const float d6 = dot(ac, cq);
  if (d6 >= 0.0f && d5 <= d6) return at(p[2], TriangleFeature::kVertex, 2);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    return at(p[0] + ac * ratio(d2, d2 - d6), TriangleFeature::kEdge, 2);
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) {
    return at(p[1] + (p[2] - p[1]) * ratio(d4 - d3, (d4 - d3) + (d5 - d6)), TriangleFeature::kEdge,
              1);
  }
  const float sum = va + vb + vc;
  return at(p[0] + ab * ratio(vb, sum) + ac * ratio(vc, sum), TriangleFeature::kFace, 0);
}

SurfaceDistance signed_surface_distance(Vec3 q, const PointTriangleClosest& at, Vec3 face_normal,
                                        bool behind, Vec3 on_surface) {
  SurfaceDistance out;
  const Vec3 off = q - at.point;
  const float d = std::sqrt(at.distance_sq);
  out.distance = behind ? -d : d;
  out.point = at.point;
  if (at.feature == TriangleFeature::kFace) {
    // Off a face, q - point is the face normal scaled; the normal itself is
    // exact. It is turned only where the caller's side disagrees with the
    // face's (a height field's point outside its footprint, below the
    // plane of its nearest face); on the face it is the face's.
    const float side = dot(off, face_normal);
    out.normal = side == 0.0f || (side > 0.0f) != behind ? face_normal : -face_normal;
  } else if (d > 1e-30f) {  // 1 / d stays finite
    out.normal = off * ((behind ? -1.0f : 1.0f) / d);
  } else {
    out.normal = on_surface;
  }
  return out;
}

}  // namespace rwd::sim::d3
