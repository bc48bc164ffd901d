// SPDX-License-Identifier: MIT
#include "body_mass2d.h"

namespace rwd::sim2d::detail {
namespace {

// a * b rounded once, half up, exactly as wmul rounds: b is split at its
// 32nd bit (b = hi 2^32 + lo, 0 <= lo < 2^32), so that
// floor((a b + 1/2) / 2^32) = a hi + floor((a lo + 1/2) / 2^32) and no
// partial product leaves 128 bits. Needs |a| < 2^94 and |a b| < 2^158.
constexpr WW wwmul(WW a, WW b) {
  const WW hi = b >> kWFrac;
  const WW lo = b - hi * kWOne;
  return a * hi + ((a * lo + kWHalf) >> kWFrac);
}

// a / b truncated toward zero, as wdiv; b != 0 and |a| < 2^94.
constexpr WW wwdiv(WW a, WW b) {
  return a * kWOne / b;
}

// vcross and vdot without the narrowing to int64.
constexpr WW wwcross(V2 a, V2 b) {
  return (static_cast<I128>(a.x) * b.y - static_cast<I128>(a.y) * b.x + kWHalf) >> kWFrac;
}
constexpr WW wwdot(V2 a, V2 b) {
  return (static_cast<I128>(a.x) * b.x + static_cast<I128>(a.y) * b.y + kWHalf) >> kWFrac;
}

MassData2 circle_mass(const Shape2D& shape, W density) {
  const W r = w_from(shape.radius);
  const W rr = wmul(r, r);  // r < 2^15 m: r^2 < 2^30 m^2 fits
  MassData2 out;
  out.mass = wwmul(density, wwmul(kWPi, rr));
  out.center = v_from(shape.vertices[0]);
  out.inertia = wwmul(out.mass, rr) / 2;
  return out;
}

// A rectangle of the segment's length and twice the radius, with a half
// disc at each end whose centroid sits 4r / (3 pi) beyond the end point.
MassData2 capsule_mass(const Shape2D& shape, W density) {
  const W r = w_from(shape.radius);
  const W rr = wmul(r, r);
  const V2 p1 = v_from(shape.vertices[0]);
  const V2 p2 = v_from(shape.vertices[1]);
  const W length = vlength(p2 - p1);
  const WW ll = wwmul(length, length);
  const WW circle_mass = wwmul(density, wwmul(kWPi, rr));
  const WW box_mass = wwmul(density, wwmul(2 * WW{r}, length));
  const W lc = wdiv(4 * r, 3 * kWPi);
  const W h = length / 2;
  const WW circle_inertia = wwmul(circle_mass, rr / 2 + wwmul(h, h) + wwmul(2 * WW{h}, lc));
  const WW box_inertia = wwmul(box_mass, 4 * WW{rr} + ll) / 12;
  MassData2 out;
  out.mass = circle_mass + box_mass;
  out.center = {(p1.x + p2.x) / 2, (p1.y + p2.y) / 2};
  out.inertia = circle_inertia + box_inertia;
  return out;
}

// Triangle fan from the first vertex. A rounded polygon is approximated by
// pushing each vertex out along its corner's bisector by sqrt(2) radius.
MassData2 polygon_mass(const Shape2D& shape, W density) {
  const int n = shape.count;
  V2 v[kMaxPolygonVertices];
  for (int i = 0; i < n; ++i) v[i] = v_from(shape.vertices[i]);
  if (shape.radius > Fx()) {
    const W push = wmul(6074001000, w_from(shape.radius));  // sqrt(2) in Q32.32
    V2 pushed[kMaxPolygonVertices];
    for (int i = 0; i < n; ++i) {
      const int prev = i == 0 ? n - 1 : i - 1;
      const V2 bisector = vnormalize(v_from(shape.normals[prev]) + v_from(shape.normals[i])).unit;
      pushed[i] = vmul_add(v[i], push, bisector);
    }
    for (int i = 0; i < n; ++i) v[i] = pushed[i];
  }
  const V2 origin = v[0];
  WW area = 0;
  WW center_x = 0;
  WW center_y = 0;
  WW inertia = 0;  // about `origin`, per unit density
  for (int i = 1; i + 1 < n; ++i) {
    const V2 e1 = v[i] - origin;
    const V2 e2 = v[i + 1] - origin;
    const WW d = wwcross(e1, e2);
    const WW triangle_area = d / 2;
    area += triangle_area;
    center_x += wwmul(triangle_area, e1.x + e2.x);
    center_y += wwmul(triangle_area, e1.y + e2.y);
    const WW intx2 = wwmul(e1.x, e1.x) + wwmul(e2.x, e1.x) + wwmul(e2.x, e2.x);
    const WW inty2 = wwmul(e1.y, e1.y) + wwmul(e2.y, e1.y) + wwmul(e2.y, e2.y);
    inertia += wwmul(d, intx2 + inty2) / 12;
  }
  MassData2 out;
  if (area <= 0) return out;  // validate_shape() refuses such polygons
  // The centroid lies inside the polygon, so it fits the int64 range.
  const V2 center{static_cast<W>(wwdiv(center_x, 3 * area)),
                  static_cast<W>(wwdiv(center_y, 3 * area))};
  out.mass = wwmul(density, area);
  out.center = origin + center;
  // Parallel axes: from the fan's origin to the centre of mass.
  out.inertia = wwmul(density, inertia) - wwmul(out.mass, wwdot(center, center));
  return out;
}

}  // namespace

MassData2 compute_mass(const Shape2D& shape, W density) {
  switch (shape.type) {
    case ShapeType2D::kCircle:
      return circle_mass(shape, density);
    case ShapeType2D::kCapsule:
      return capsule_mass(shape, density);
    case ShapeType2D::kPolygon:
      return polygon_mass(shape, density);
    case ShapeType2D::kSegment:
    case ShapeType2D::kChainSegment: {
      MassData2 out;  // no area: only static and kinematic bodies use segments
      out.center = {(w_from(shape.vertices[0].x) + w_from(shape.vertices[1].x)) / 2,
                    (w_from(shape.vertices[0].y) + w_from(shape.vertices[1].y)) / 2};
      return out;
    }
  }
  return {};
}

}  // namespace rwd::sim2d::detail
