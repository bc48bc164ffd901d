// SPDX-License-Identifier: MIT
#include "shape_bounds2d.h"

namespace rwd::sim2d::detail {

Box2W shape_bounds(const Shape2D& shape, const Xf& xf) {
  // Circle: one vertex; capsule, segment and chain segment: two (a chain
  // segment's ghosts are not part of its surface); polygon: count. Each is
  // then grown by the radius (zero for segments and sharp polygons).
  const int n = shape.count < 1 ? 1 : shape.count;
  V2 lower = transform_point(xf, v_from(shape.vertices[0]));
  V2 upper = lower;
  for (int i = 1; i < n; ++i) {
    const V2 p = transform_point(xf, v_from(shape.vertices[i]));
    lower = vmin(lower, p);
    upper = vmax(upper, p);
  }
  const W r = w_from(shape.radius);
  return {{lower.x - r, lower.y - r}, {upper.x + r, upper.y + r}};
}

}  // namespace rwd::sim2d::detail
