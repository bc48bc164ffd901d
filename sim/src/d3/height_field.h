// SPDX-License-Identifier: MIT
#pragma once
// Height fields: a regular grid of heights, two triangles per cell, as a
// static triangle source like TriangleMesh but without stored triangles.
// Everything is in the field's local frame: sample (r, c) sits at
// (c * scale.x, height * scale.y, r * scale.z), so rows run along z and
// columns along x, and the surface faces +y.
//
// Cell (r, c), 0 <= r < rows - 1, 0 <= c < cols - 1, has corners
// p00 = (r, c), p01 = (r + 1, c), p11 = (r + 1, c + 1), p10 = (r, c + 1) (row,
// column) and the fixed diagonal p00-p11. Half 0 is (p00, p01, p11), half 1
// is (p00, p11, p10), both counter-clockwise about +y. The triangle id is
// cell * 2 + half with cell = r * (cols - 1) + c.
//
// Active edges are computed once when the field is built, from the
// neighbouring triangle across each edge (the same rule as the mesh's,
// triangle.h); an edge next to a hole or the border is a boundary. They are
// derived from the heights and holes alone, so a field loaded from a
// snapshot recomputes the same bits.
#include <cstdint>
#include <span>
#include <vector>

#include "d3/aabb_tree.h"
#include "d3/triangle.h"
#include "rewind/core/status.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

inline constexpr uint32_t kHeightFieldMinSamples = 2;
inline constexpr uint32_t kHeightFieldMaxSamples = 4096;
/// Largest |height * scale.y| and largest extent along x and z, metres.
inline constexpr float kHeightFieldMaxCoordinate = 1e5f;

struct HeightField {
  uint32_t rows = 0;           ///< samples along z, >= 2
  uint32_t cols = 0;           ///< samples along x, >= 2
  Vec3 scale;                  ///< x spacing, y multiplier, z spacing (metres), all > 0
  std::vector<float> heights;  ///< rows * cols, row-major (index r * cols + c)
  std::vector<uint8_t> holes;  ///< (rows - 1) * (cols - 1) cells, 1 = hole; may be empty
  Aabb bounds;
  /// Per cell, TriangleRef::active_edges of half 0 (low byte) and half 1
  /// (high byte): derived at build (a triangle near a body is produced
  /// every substep, its neighbours' normals only once).
  std::vector<uint16_t> edge_bits;
};

/// Validates and builds. Refuses (kInvalidArgument): rows or cols outside
/// 2..4096, a heights span of another size than rows * cols, a holes span
/// neither empty nor (rows - 1) * (cols - 1) long or holding a value other
/// than 0 and 1 (naming the cell), a scale component not finite and
/// positive, an extent (cols - 1) * scale.x or (rows - 1) * scale.z beyond
/// 1e5 m, a height not finite or with |height * scale.y| > 1e5 (naming the
/// sample).
Result<HeightField> build_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                       std::span<const float> heights,
                                       std::span<const uint8_t> holes);

/// Sample (r, c) in the local frame.
inline Vec3 height_field_point(const HeightField& hf, uint32_t r, uint32_t c) {
  return {static_cast<float>(c) * hf.scale.x, hf.heights[r * hf.cols + c] * hf.scale.y,
          static_cast<float>(r) * hf.scale.z};
}

inline bool height_field_is_hole(const HeightField& hf, uint32_t cell) {
  return !hf.holes.empty() && hf.holes[cell] != 0;
}

/// The corners of the triangle with id cell * 2 + half (see above).
inline void height_field_corners(const HeightField& hf, uint32_t id, Vec3 p[3]) {
  const uint32_t cell = id >> 1;
  const uint32_t r = cell / (hf.cols - 1);
  const uint32_t c = cell % (hf.cols - 1);
  p[0] = height_field_point(hf, r, c);
  p[1] = (id & 1) == 0 ? height_field_point(hf, r + 1, c) : height_field_point(hf, r + 1, c + 1);
  p[2] = (id & 1) == 0 ? height_field_point(hf, r + 1, c + 1) : height_field_point(hf, r, c + 1);
}

/// The triangle with id cell * 2 + half, with its normal and active-edge
/// bits (the cell must not be a hole).
TriangleRef height_field_triangle(const HeightField& hf, uint32_t id);

/// Calls visit(const TriangleRef&) for every triangle of a cell that is not
/// a hole whose bounds overlap `local_box` (closed boxes), in ascending id.
/// No allocation.
template <class Visit>
void height_field_query(const HeightField& hf, const Aabb& local_box, Visit&& visit);

/// Closest hit of the ray origin + t * dir, 0 <= t <= max_t (local frame).
/// On a hit fills t, the unit face normal facing the ray and the triangle
/// id; ties in t go to the lower id. Both sides are hit (a height field is
/// seen from above, but a ray from below still finds the surface). Exact:
/// the same answer as testing every triangle (tested against that).
bool height_field_raycast(const HeightField& hf, Vec3 origin, Vec3 dir, float max_t, float& t,
                          Vec3& normal, uint32_t& id);

/// The signed distance from q to the field's surface (local frame, metres),
/// into `out`; false when every cell is a hole. The magnitude is the
/// distance to the nearest point of the surface. Negative when q is under
/// the surface: within the footprint (0 <= x <= (cols - 1) * scale.x,
/// 0 <= z <= (rows - 1) * scale.z), over a cell that is not a hole, and
/// below the surface's height there. Positive everywhere else, beside the
/// field and under a hole included (height_field_distance.cpp). Ties
/// between equally near triangles go to the lower id; a pure function of
/// the field and q. No allocation.
bool height_field_signed_distance(const HeightField& hf, Vec3 q, SurfaceDistance& out);

namespace height_field_detail {
/// Range of cells along one axis whose span [i * spacing, (i + 1) *
/// spacing] may meet [lo, hi], widened by one cell against rounding;
/// false when empty. cells = samples - 1.
bool cell_range(float lo, float hi, float spacing, uint32_t cells, uint32_t& first, uint32_t& last);
}  // namespace height_field_detail

template <class Visit>
void height_field_query(const HeightField& hf, const Aabb& local_box, Visit&& visit) {
  if (!overlaps(hf.bounds, local_box)) return;
  uint32_t r0 = 0, r1 = 0, c0 = 0, c1 = 0;
  if (!height_field_detail::cell_range(local_box.lower.z, local_box.upper.z, hf.scale.z,
                                       hf.rows - 1, r0, r1) ||
      !height_field_detail::cell_range(local_box.lower.x, local_box.upper.x, hf.scale.x,
                                       hf.cols - 1, c0, c1)) {
    return;
  }
  for (uint32_t r = r0; r <= r1; ++r) {
    for (uint32_t c = c0; c <= c1; ++c) {
      const uint32_t cell = r * (hf.cols - 1) + c;
      if (height_field_is_hole(hf, cell)) continue;
      for (uint32_t half = 0; half < 2; ++half) {
        // The cheap corner box first; the neighbours (active edges) only
        // for triangles that pass.
        Vec3 p[3];
        height_field_corners(hf, cell * 2 + half, p);
        const Aabb box{min(min(p[0], p[1]), p[2]), max(max(p[0], p[1]), p[2])};
        if (overlaps(box, local_box)) visit(height_field_triangle(hf, cell * 2 + half));
      }
    }
  }
}

}  // namespace rwd::sim::d3
