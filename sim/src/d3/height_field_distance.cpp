// SPDX-License-Identifier: MIT
// The signed distance from a point to a height field (height_field.h).
//
// Nearest triangle: the cells are visited in square rings about the cell
// under the point (or the nearest one to it, from beside the field), ring
// k being the cells k cells away along x or z. Before each ring a lower
// bound on the distance to any of its triangles (the gap in x or z to the
// ring's nearest column or row, and the gap in y to the field's height
// range) is checked against the best so far, and the walk stops when the
// ring lies farther; so a point near the surface costs a cell or two, and
// a point high above it no more, since the height gap alone exceeds the
// rest. The bound is widened by a few parts per million, so the answer is
// the least (squared distance, id) over every triangle.
//
// Sign: a height field is a surface seen from above, so the side is "under
// or not": a point is under the field when it lies within the footprint,
// over a cell that is not a hole, and below the surface's height at its x
// and z. This needs no feature of the nearest point (unlike a mesh's
// pseudo-normal), and stays right where that point is on the border of the
// footprint or of a hole, whose faces would say nothing about the side.
// Beside the field and under a hole there is no ground above the point,
// so it reads positive.
#include <cmath>
#include <cstdint>

#include "d3/height_field.h"
#include "d3/triangle_closest.h"

namespace rwd::sim::d3 {
namespace {

// See mesh_distance.cpp's kSkipFactor.
constexpr float kSkipFactor = 1.0f + 1e-6f;

// Distance from v to [lo, hi] along one axis.
float gap(float v, float lo, float hi) {
  return v < lo ? lo - v : (v > hi ? v - hi : 0.0f);
}

// Distance from v to the span of cell i along an axis of `spacing`: the
// same rounded edges (i * spacing) the corners have, so no triangle of the
// cell lies nearer than this.
float cell_gap(float v, int64_t i, float spacing) {
  return gap(v, static_cast<float>(i) * spacing, static_cast<float>(i + 1) * spacing);
}

// The cell along one axis holding v, or the nearest one to it.
int64_t nearest_cell(float v, float spacing, uint32_t cells) {
  const float f = std::floor(v / spacing);
  if (!(f > 0.0f)) return 0;
  return f < static_cast<float>(cells - 1) ? static_cast<int64_t>(f) : cells - 1;
}

// Whether q is under the surface (see the top of the file).
bool under(const HeightField& hf, Vec3 q) {
  const uint32_t cells_x = hf.cols - 1;
  const uint32_t cells_z = hf.rows - 1;
  if (!(q.x >= 0.0f && q.x <= static_cast<float>(cells_x) * hf.scale.x && q.z >= 0.0f &&
        q.z <= static_cast<float>(cells_z) * hf.scale.z)) {
    return false;
  }
  const auto c = static_cast<uint32_t>(nearest_cell(q.x, hf.scale.x, cells_x));
  const auto r = static_cast<uint32_t>(nearest_cell(q.z, hf.scale.z, cells_z));
  const uint32_t cell = r * cells_x + c;
  if (height_field_is_hole(hf, cell)) return false;
  // Half 0 (p00, p01, p11) covers the part of the cell where the fraction
  // along z is at least the fraction along x.
  const Vec3 p00 = height_field_point(hf, r, c);
  const uint32_t half = (q.z - p00.z) * hf.scale.x >= (q.x - p00.x) * hf.scale.z ? 0 : 1;
  Vec3 p[3];
  height_field_corners(hf, cell * 2 + half, p);
  const Vec3 n = triangle_cross(p[0], p[1], p[2]);  // n.y > 0: the cell has an area
  const float surface = p[0].y - (n.x * (q.x - p[0].x) + n.z * (q.z - p[0].z)) / n.y;
  return q.y < surface;
}

}  // namespace

bool height_field_signed_distance(const HeightField& hf, Vec3 q, SurfaceDistance& out) {
  const uint32_t cells_x = hf.cols - 1;
  const uint32_t cells_z = hf.rows - 1;
  const float sx = hf.scale.x;
  const float sz = hf.scale.z;
  const int64_t c0 = nearest_cell(q.x, sx, cells_x);
  const int64_t r0 = nearest_cell(q.z, sz, cells_z);
  // Gaps no cell beats: to the footprint along x and z, to the height range.
  const float gx = gap(q.x, 0.0f, static_cast<float>(cells_x) * sx);
  const float gz = gap(q.z, 0.0f, static_cast<float>(cells_z) * sz);
  const float gy = gap(q.y, hf.bounds.lower.y, hf.bounds.upper.y);

  bool found = false;
  uint32_t best_id = 0;
  PointTriangleClosest best;
  Vec3 best_corners[3];
  const auto visit = [&](int64_t r, int64_t c) {
    const auto cell = static_cast<uint32_t>(r * cells_x + c);
    if (height_field_is_hole(hf, cell)) return;
    for (uint32_t half = 0; half < 2; ++half) {
      const uint32_t id = cell * 2 + half;
      Vec3 p[3];
      height_field_corners(hf, id, p);
      const PointTriangleClosest at = closest_point_triangle(q, p);
      if (!found || at.distance_sq < best.distance_sq ||
          (at.distance_sq == best.distance_sq && id < best_id)) {
        found = true;
        best_id = id;
        best = at;
        for (int k = 0; k < 3; ++k) best_corners[k] = p[k];
      }
    }
  };
  for (int64_t k = 0;; ++k) {
    const bool left = c0 - k >= 0;
    const bool right = c0 + k < cells_x;
    const bool low = r0 - k >= 0;
    const bool high = r0 + k < cells_z;
    if (!left && !right && !low && !high) break;  // the rings have left the grid
    if (k > 0 && found) {
      float bound = INFINITY;
      if (left || right) {
        const float g = std::fmin(left ? cell_gap(q.x, c0 - k, sx) : INFINITY,
                                  right ? cell_gap(q.x, c0 + k, sx) : INFINITY);
        bound = g * g + gz * gz;
      }
      if (low || high) {
        const float g = std::fmin(low ? cell_gap(q.z, r0 - k, sz) : INFINITY,
                                  high ? cell_gap(q.z, r0 + k, sz) : INFINITY);
        bound = std::fmin(bound, g * g + gx * gx);
      }
      if (bound + gy * gy > best.distance_sq * kSkipFactor) break;
    }
    const int64_t r_lo = low ? r0 - k : 0;
    const int64_t r_hi = high ? r0 + k : cells_z - 1;
    const int64_t c_lo = left ? c0 - k : 0;
    const int64_t c_hi = right ? c0 + k : cells_x - 1;
    for (int64_t r = r_lo; r <= r_hi; ++r) {
      if (r == r0 - k || r == r0 + k) {
        for (int64_t c = c_lo; c <= c_hi; ++c) visit(r, c);
      } else {
        if (left) visit(r, c0 - k);
        if (right) visit(r, c0 + k);
      }
    }
  }
  if (!found) return false;
  const Vec3 face =
      normalize_or_zero(triangle_cross(best_corners[0], best_corners[1], best_corners[2]));
  out = signed_surface_distance(q, best, face, under(hf, q), face);
  return true;
}

}  // namespace rwd::sim::d3
