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

}  // namespace rwd::sim::d3
