// SPDX-License-Identifier: MIT
// Height field build, triangles with their active edges, and the ray walk.
//
// Ray: the segment is clipped to the field's bounds, then the rows of cells
// it crosses are visited in the ray's direction. In each row the cells
// under the part of the segment within the row (widened by half a cell
// along z and one cell along x, against rounding) are tested exactly with
// ray_triangle; the walk stops at the first row whose widened slab starts
// beyond the best hit. Every triangle that could hit at or before the best
// t is therefore tested, so the answer (closest t, ties to the lower id) is
// the brute-force one, and the work is about the number of cells under the
// segment.
#include <cmath>
#include <string>
#include <utility>

#include "d3/height_field.h"

namespace rwd::sim::d3 {
namespace {

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

bool positive_finite(float v) {
  return std::isfinite(v) && v > 0.0f;
}

Vec3 unit_normal(const Vec3 p[3]) {
  return normalize_or_zero(triangle_cross(p[0], p[1], p[2]));
}

// kAcross[half][e]: the neighbour across edge e of a triangle of cell
// (r, c): its cell's offset, its half, the index of its corner off the
// edge, and that corner's sample offset from (r, c). Half 0 (p00, p01,
// p11): the left edge to cell (r, c - 1) half 1 (far corner its p00,
// index 0); the top edge to (r + 1, c) half 1 (far corner p11, index 1);
// the diagonal to this cell's half 1 (far corner p10, index 2). Half 1
// (p00, p11, p10): the diagonal to half 0 (far corner p01, index 1); the
// right edge to (r, c + 1) half 0 (far corner p11, index 2); the bottom
// edge to (r - 1, c) half 0 (far corner p00, index 0).
struct Across {
  int32_t dr;
  int32_t dc;
  uint32_t half;
  uint32_t far_corner;
  int32_t far_dr;
  int32_t far_dc;
};
constexpr Across kAcross[2][3] = {{{0, -1, 1, 0, 0, -1}, {1, 0, 1, 1, 2, 1}, {0, 0, 1, 2, 0, 1}},
                                  {{0, 0, 0, 1, 1, 0}, {0, 1, 0, 2, 1, 2}, {-1, 0, 0, 0, -1, 0}}};

// The id of the triangle across edge e of triangle `id`; false when the
// edge borders the field or a hole.
bool neighbour_across(const HeightField& hf, uint32_t id, uint32_t e, uint32_t& other) {
  const uint32_t cell = id >> 1;
  const Across& a = kAcross[id & 1][e];
  const int64_t r = static_cast<int64_t>(cell / (hf.cols - 1)) + a.dr;
  const int64_t c = static_cast<int64_t>(cell % (hf.cols - 1)) + a.dc;
  if (r < 0 || c < 0 || r >= static_cast<int64_t>(hf.rows) - 1 ||
      c >= static_cast<int64_t>(hf.cols) - 1) {
    return false;
  }
  const uint32_t n = static_cast<uint32_t>(r) * (hf.cols - 1) + static_cast<uint32_t>(c);
  if (height_field_is_hole(hf, n)) return false;
  other = n * 2 + a.half;
  return true;
}

// The active-edge bits of triangle `id` (not in a hole) from its
// neighbours: boundary bits, or the classification against the
// neighbour's far corner.
uint8_t active_edges_of(const HeightField& hf, uint32_t id) {
  Vec3 p[3];
  height_field_corners(hf, id, p);
  const Vec3 n = unit_normal(p);
  uint8_t bits = 0;
  for (uint32_t e = 0; e < 3; ++e) {
    uint32_t other = 0;
    uint8_t b = kBoundaryEdgeBits;
    if (neighbour_across(hf, id, e, other)) {
      Vec3 q[3];
      height_field_corners(hf, other, q);
      b = classify_shared_edge(n, unit_normal(q), p[e], q[kAcross[id & 1][e].far_corner]);
    }
    bits = static_cast<uint8_t>(bits | (b << e));
  }
  return bits;
}

}  // namespace

namespace height_field_detail {

bool cell_range(float lo, float hi, float spacing, uint32_t cells, uint32_t& first,
                uint32_t& last) {
  if (!(lo <= hi)) return false;
  const float a = std::floor(lo / spacing) - 1.0f;
  const float b = std::floor(hi / spacing) + 1.0f;
  const float top = static_cast<float>(cells - 1);
  if (!(b >= 0.0f) || !(a <= top)) return false;
  first = a > 0.0f ? static_cast<uint32_t>(a) : 0;
  last = b < top ? static_cast<uint32_t>(b) : cells - 1;
  return true;
}

}  // namespace height_field_detail

Result<HeightField> build_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                       std::span<const float> heights,
                                       std::span<const uint8_t> holes) {
  if (rows < kHeightFieldMinSamples || rows > kHeightFieldMaxSamples ||
      cols < kHeightFieldMinSamples || cols > kHeightFieldMaxSamples) {
    return invalid("height field: rows " + std::to_string(rows) + " and cols " +
                   std::to_string(cols) + " must lie in 2..4096");
  }
  const size_t samples = static_cast<size_t>(rows) * cols;
  const size_t cells = static_cast<size_t>(rows - 1) * (cols - 1);
  if (heights.size() != samples) {
    return invalid("height field: " + std::to_string(heights.size()) + " heights for " +
                   std::to_string(samples) + " samples");
  }
  if (!holes.empty() && holes.size() != cells) {
    return invalid("height field: " + std::to_string(holes.size()) + " hole flags for " +
                   std::to_string(cells) + " cells");
  }
  if (!positive_finite(scale.x) || !positive_finite(scale.y) || !positive_finite(scale.z)) {
    return invalid("height field: scale components must be finite and positive");
  }
  if (!(static_cast<float>(cols - 1) * scale.x <= kHeightFieldMaxCoordinate) ||
      !(static_cast<float>(rows - 1) * scale.z <= kHeightFieldMaxCoordinate)) {
    return invalid("height field: extent beyond 1e5 m");
  }
  for (size_t i = 0; i < holes.size(); ++i) {
    if (holes[i] > 1) {
      return invalid("height field: hole flag of cell " + std::to_string(i) + " is not 0 or 1");
    }
  }
  float lo = 0.0f;
  float hi = 0.0f;
  for (size_t i = 0; i < samples; ++i) {
    const float y = heights[i] * scale.y;
    if (!std::isfinite(heights[i]) || !(std::fabs(y) <= kHeightFieldMaxCoordinate)) {
      return invalid("height field: height of sample " + std::to_string(i) + " (row " +
                     std::to_string(i / cols) + ", col " + std::to_string(i % cols) +
                     ") is not finite or beyond 1e5 m");
    }
    lo = i == 0 || y < lo ? y : lo;
    hi = i == 0 || y > hi ? y : hi;
  }
  HeightField hf;
  hf.rows = rows;
  hf.cols = cols;
  hf.scale = scale;
  hf.heights.assign(heights.begin(), heights.end());
  hf.holes.assign(holes.begin(), holes.end());
  hf.bounds = {
      {0.0f, lo, 0.0f},
      {static_cast<float>(cols - 1) * scale.x, hi, static_cast<float>(rows - 1) * scale.z}};
  hf.edge_bits.assign(cells, 0);
  for (uint32_t cell = 0; cell < cells; ++cell) {
    if (height_field_is_hole(hf, cell)) continue;
    hf.edge_bits[cell] = static_cast<uint16_t>(active_edges_of(hf, cell * 2) |
                                               (active_edges_of(hf, cell * 2 + 1) << 8));
  }
  return hf;
}

TriangleRef height_field_triangle(const HeightField& hf, uint32_t id) {
  TriangleRef t;
  t.id = id;
  height_field_corners(hf, id, t.p);
  t.normal = unit_normal(t.p);
  t.active_edges = static_cast<uint8_t>(hf.edge_bits[id >> 1] >> (8 * (id & 1)));
  // A fold has a neighbour (the bits were classified against it), so its
  // far corner is a sample inside the grid.
  const uint32_t cell = id >> 1;
  const uint32_t r = cell / (hf.cols - 1);
  const uint32_t c = cell % (hf.cols - 1);
  for (uint32_t e = 0; e < 3; ++e) {
    if (!edge_is_fold(t.active_edges, e)) continue;
    const Across& a = kAcross[id & 1][e];
    t.across[e] = height_field_point(hf, static_cast<uint32_t>(static_cast<int32_t>(r) + a.far_dr),
                                     static_cast<uint32_t>(static_cast<int32_t>(c) + a.far_dc));
  }
  return t;
}

bool height_field_raycast(const HeightField& hf, Vec3 origin, Vec3 dir, float max_t, float& t,
                          Vec3& normal, uint32_t& id) {
  if (!(max_t >= 0.0f)) return false;
  // Clip to the bounds widened by a cell and a little height, so rounding
  // at the bounds' faces cannot lose a hit there.
  const float pad_y =
      1e-5f * (1.0f + std::fmax(std::fabs(hf.bounds.lower.y), std::fabs(hf.bounds.upper.y)));
  const Aabb wide{
      {hf.bounds.lower.x - hf.scale.x, hf.bounds.lower.y - pad_y, hf.bounds.lower.z - hf.scale.z},
      {hf.bounds.upper.x + hf.scale.x, hf.bounds.upper.y + pad_y, hf.bounds.upper.z + hf.scale.z}};
  float s0 = 0.0f;
  float s1 = 0.0f;
  if (!SegmentSlabs(origin, dir).interval(wide, max_t, s0, s1)) return false;
  const float za = origin.z + dir.z * s0;
  const float zb = origin.z + dir.z * s1;
  uint32_t r_first = 0, r_last = 0;
  if (!height_field_detail::cell_range(za < zb ? za : zb, za < zb ? zb : za, hf.scale.z,
                                       hf.rows - 1, r_first, r_last)) {
    return false;
  }
  bool hit = false;
  float best_t = max_t;
  uint32_t best = 0;
  const uint32_t row_count = r_last - r_first + 1;
  for (uint32_t k = 0; k < row_count; ++k) {
    const uint32_t r = dir.z >= 0.0f ? r_first + k : r_last - k;
    // The row's slab widened by half a cell: the t range of the segment in it.
    const float z_lo = (static_cast<float>(r) - 0.5f) * hf.scale.z;
    const float z_hi = (static_cast<float>(r) + 1.5f) * hf.scale.z;
    float t0 = s0;
    float t1 = s1;
    if (dir.z != 0.0f) {
      float ta = (z_lo - origin.z) / dir.z;
      float tb = (z_hi - origin.z) / dir.z;
      if (ta > tb) std::swap(ta, tb);
      // Rows come in ray order, so once a row starts beyond the best hit
      // every later one does too.
      if (hit && ta > best_t) break;
      t0 = ta > s0 ? ta : s0;
      t1 = tb < s1 ? tb : s1;
      if (!(t0 <= t1)) continue;
    } else if (origin.z < z_lo || origin.z > z_hi) {
      continue;
    }
    const float xa = origin.x + dir.x * t0;
    const float xb = origin.x + dir.x * t1;
    uint32_t c_first = 0, c_last = 0;
    if (!height_field_detail::cell_range(xa < xb ? xa : xb, xa < xb ? xb : xa, hf.scale.x,
                                         hf.cols - 1, c_first, c_last)) {
      continue;
    }
    for (uint32_t c = c_first; c <= c_last; ++c) {
      const uint32_t cell = r * (hf.cols - 1) + c;
      if (height_field_is_hole(hf, cell)) continue;
      for (uint32_t half = 0; half < 2; ++half) {
        Vec3 p[3];
        height_field_corners(hf, cell * 2 + half, p);
        float tk = 0.0f;
        if (!ray_triangle(origin, dir, p[0], p[1], p[2], max_t, false, tk)) continue;
        const uint32_t tid = cell * 2 + half;
        if (!hit || tk < best_t || (tk == best_t && tid < best)) {
          hit = true;
          best_t = tk;
          best = tid;
        }
      }
    }
  }
  if (!hit) return false;
  Vec3 p[3];
  height_field_corners(hf, best, p);
  const Vec3 n = unit_normal(p);
  t = best_t;
  id = best;
  normal = dot(n, dir) > 0.0f ? -n : n;
  return true;
}

}  // namespace rwd::sim::d3
