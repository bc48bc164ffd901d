// SPDX-License-Identifier: MIT
// A box against a triangle by separating axes (box_triangle.h). The work is
// done in the box's frame, where the box is centred and square to the
// axes: its reach along an axis is a sum of three products, and a box edge
// crossed with a triangle edge is the edge with one component dropped.
#include "d3/box_triangle.h"

#include <cmath>

#include "d3/manifold.h"

namespace rwd::sim::d3 {
namespace {

// A crossing of a box edge and a triangle edge shorter than this, relative
// to the triangle edge's length, is taken as parallel: it separates
// nothing the face axes do not.
constexpr float kParallelSin = 1e-5f;

// The larger and the smaller of two finite values, as plain compares
// (std::fmax and std::fmin are calls into the maths library here).
float larger(float a, float b) {
  return a < b ? b : a;
}
float smaller(float a, float b) {
  return b < a ? b : a;
}

// The gap along one axis (box frame) and the way the box lies from the
// triangle.
struct AxisGap {
  float gap = 0.0f;  ///< > 0 apart, else minus the overlap along the axis
  Vec3 dir;          ///< unit, from the triangle toward the box (box frame)
};

// The gap along axis u (box frame), times u's length: the box on u's side
// of the triangle q[0..3) or on the other, whichever leaves the larger gap
// (ties to u's side); `flip` says it was the other.
float scaled_gap(Vec3 half, const Vec3 q[3], Vec3 u, bool& flip) {
  const float r = half.x * std::fabs(u.x) + half.y * std::fabs(u.y) + half.z * std::fabs(u.z);
  const float d0 = dot(q[0], u);
  const float d1 = dot(q[1], u);
  const float d2 = dot(q[2], u);
  const float above = -r - larger(d0, larger(d1, d2));
  const float below = smaller(d0, smaller(d1, d2)) - r;
  flip = below > above;
  return flip ? below : above;
}

// The gap along box axis k: the triangle's extent along it against the
// half extent.
AxisGap gap_along_axis(Vec3 half, const Vec3 q[3], int k) {
  const float d0 = component(q[0], k);
  const float d1 = component(q[1], k);
  const float d2 = component(q[2], k);
  const float h = component(half, k);
  const float above = -h - larger(d0, larger(d1, d2));
  const float below = smaller(d0, smaller(d1, d2)) - h;
  Vec3 u;
  (k == 0 ? u.x : (k == 1 ? u.y : u.z)) = below > above ? -1.0f : 1.0f;
  return {below > above ? below : above, u};
}

// The box's corner farthest along -dir (toward the triangle), box frame,
// with its offset along axis `skip` left out (the middle of the edge along
// that axis; -1 skips none). A face or an edge square to dir ties to the
// axes' plus side.
Vec3 lowest_point(Vec3 half, Vec3 dir, int skip) {
  const auto pick = [](float d, float h) { return d > 0.0f ? -h : h; };
  return {skip == 0 ? 0.0f : pick(dir.x, half.x), skip == 1 ? 0.0f : pick(dir.y, half.y),
          skip == 2 ? 0.0f : pick(dir.z, half.z)};
}

// The triangle's corner farthest along dir (toward the box); ties to the
// lower index.
Vec3 highest_corner(const Vec3 q[3], Vec3 dir) {
  int best = 0;
  float best_d = dot(q[0], dir);
  for (int k = 1; k < 3; ++k) {
    const float d = dot(q[k], dir);
    if (d > best_d) {
      best_d = d;
      best = k;
    }
  }
  return q[best];
}

}  // namespace

BoxTriangleFeatures box_triangle_features(const BoxFrame& box, const TriangleRef& tri,
                                          float reach) {
  const Vec3* axes = box.axes;
  const auto to_box = [&](Vec3 v) {
    return Vec3{dot(v, axes[0]), dot(v, axes[1]), dot(v, axes[2])};
  };
  const auto from_box = [&](Vec3 v) { return axes[0] * v.x + axes[1] * v.y + axes[2] * v.z; };
  const Vec3 q[3] = {to_box(tri.p[0] - box.center), to_box(tri.p[1] - box.center),
                     to_box(tri.p[2] - box.center)};
  const Vec3 half = box.half;
  BoxTriangleFeatures out;
  const auto apart = [&](const AxisGap& g) {
    out.overlap = false;
    out.separation = g.gap;
    out.normal = from_box(g.dir);
    return out;
  };

  // The face axes: the triangle's normal first, then the box's faces.
  const Vec3 n = to_box(tri.normal);
  bool n_flip = false;
  const float n_gap = scaled_gap(half, q, n, n_flip);
  const AxisGap face_n{n_gap, n_flip ? -n : n};
  if (face_n.gap > reach) return apart(face_n);
  AxisGap face_b = gap_along_axis(half, q, 0);
  for (int k = 1; k < 3; ++k) {
    const AxisGap g = gap_along_axis(half, q, k);
    if (g.gap > face_b.gap) face_b = g;
  }
  if (face_b.gap > reach) return apart(face_b);
  const bool on_triangle_face = !(face_b.gap > face_n.gap + kBoxTriangleAxisSlack);
  const AxisGap face = on_triangle_face ? face_n : face_b;

  // The edge crossings, box edge k with triangle edge j: axis k crossed
  // with e is e with its k component dropped and the other two turned.
  AxisGap edge;
  int edge_k = -1;
  int edge_j = 0;
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = q[j == 2 ? 0 : j + 1] - q[j];
    const float e_len = length(e);
    for (int k = 0; k < 3; ++k) {
      const Vec3 c =
          k == 0 ? Vec3{0.0f, -e.z, e.y} : (k == 1 ? Vec3{e.z, 0.0f, -e.x} : Vec3{-e.y, e.x, 0.0f});
      const float c_len = length(c);
      if (!(c_len > kParallelSin * e_len)) continue;
      // Only an axis beyond the reach (which ends the search) or one that
      // beats the face and every edge so far is divided out.
      bool flip = false;
      const float scaled = scaled_gap(half, q, c, flip);
      const float beat = edge_k < 0 ? face.gap + kBoxTriangleAxisSlack : edge.gap;
      if (!(scaled > reach * c_len) && !(scaled > beat * c_len)) continue;
      const float inv = 1.0f / c_len;
      const AxisGap g{scaled * inv, c * (flip ? -inv : inv)};
      if (g.gap > reach) return apart(g);
      if (!(g.gap > beat)) continue;
      edge = g;
      edge_k = k;
      edge_j = j;
    }
  }

  Vec3 on_box;
  Vec3 on_tri;
  AxisGap best = face;
  if (edge_k >= 0) {  // it beat the face by the slack
    // The box edge along axis edge_k that leads toward the triangle, and
    // triangle edge edge_j: their closest points.
    best = edge;
    const float h = component(half, edge_k);
    Vec3 axis;
    (edge_k == 0 ? axis.x : (edge_k == 1 ? axis.y : axis.z)) = 1.0f;
    const Vec3 from = lowest_point(half, edge.dir, edge_k) - axis * h;
    const Vec3 a = q[edge_j];
    const Vec3 b = q[edge_j == 2 ? 0 : edge_j + 1];
    float s = 0.0f;
    float t = 0.0f;
    closest_on_segments(from, axis * (2.0f * h), a, b - a, s, t);
    on_box = from + axis * (2.0f * h * s);
    on_tri = a + (b - a) * t;
  } else if (on_triangle_face) {
    on_box = lowest_point(half, face.dir, -1);
    on_tri = on_box - face.dir * face.gap;
  } else {
    // Apart, the box's point nearest the triangle's corner (on the face
    // when the corner lies over it, else on its rim); overlapping, the
    // corner pushed out to the face.
    on_tri = highest_corner(q, face.dir);
    on_box = face.gap > 0.0f ? Vec3{larger(-half.x, smaller(half.x, on_tri.x)),
                                    larger(-half.y, smaller(half.y, on_tri.y)),
                                    larger(-half.z, smaller(half.z, on_tri.z))}
                             : on_tri + face.dir * face.gap;
  }
  out.overlap = !(best.gap > 0.0f);
  out.separation = best.gap;
  out.normal = from_box(best.dir);
  out.on_box = box.center + from_box(on_box);
  out.on_triangle = box.center + from_box(on_tri);
  return out;
}

}  // namespace rwd::sim::d3
