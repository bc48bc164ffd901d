// SPDX-License-Identifier: MIT
#pragma once
// Rays against one shape, in Q32.32. A ray is origin + s * unit for s in
// [0, max_length] (m). Shared rules: a ray starting strictly inside a
// shape does not hit it (it reports surfaces it enters); an origin on the
// surface moving inward hits at s = 0; a graze hits; segments are hit from
// either side.
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

struct RayResult2 {
  W distance = 0;  ///< s, m along the ray
  V2 point;        ///< world, on the surface
  V2 normal;       ///< world, unit, out of the surface the ray entered
};

/// The first hit of the ray on `shape` placed at `xf` (the body origin's
/// transform). `unit` must be a unit vector; `max_length` >= 0.
bool ray_shape(const Shape2D& shape, const Xf& xf, V2 origin, V2 unit, W max_length,
               RayResult2& out);

/// The ray against a disc (centre c, radius r > 0) in one frame: s and the
/// unit normal at the hit.
bool ray_circle(V2 origin, V2 unit, W max_length, V2 center, W radius, W& s, V2& normal);

/// The ray against the front side of the edge p0..p1 whose outward unit
/// normal is n (the ray must travel against n and start on its outer side).
bool ray_edge(V2 origin, V2 unit, W max_length, V2 p0, V2 p1, V2 n, W& s);

}  // namespace rwd::sim2d::detail
