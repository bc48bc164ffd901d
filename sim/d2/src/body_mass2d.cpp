// SPDX-License-Identifier: MIT
#include "body_mass2d.h"

namespace rwd::sim2d::detail {
namespace {

MassData2 circle_mass(const Shape2D& shape, W density) {
  const W r = w_from(shape.radius);
  const W rr = wmul(r, r);
  MassData2 out;
  out.mass = wmul(density, wmul(kWPi, rr));
  out.center = v_from(shape.vertices[0]);
  out.inertia = wmul(out.mass, rr) / 2;
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
  const W ll = wmul(length, length);
  const W circle_mass = wmul(density, wmul(kWPi, rr));
  const W box_mass = wmul(density, wmul(2 * r, length));
  const W lc = wdiv(4 * r, 3 * kWPi);
  const W h = length / 2;
  const W circle_inertia = wmul(circle_mass, rr / 2 + wmul(h, h) + wmul(2 * h, lc));
  const W box_inertia = wmul(box_mass, 4 * rr + ll) / 12;
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
  W area = 0;
  V2 center;
  W inertia = 0;  // about `origin`, per unit density
  for (int i = 1; i + 1 < n; ++i) {
    const V2 e1 = v[i] - origin;
    const V2 e2 = v[i + 1] - origin;
    const W d = vcross(e1, e2);
    const W triangle_area = d / 2;
    area += triangle_area;
    center.x += wmul(triangle_area, e1.x + e2.x);
    center.y += wmul(triangle_area, e1.y + e2.y);
    const W intx2 = wmul(e1.x, e1.x) + wmul(e2.x, e1.x) + wmul(e2.x, e2.x);
    const W inty2 = wmul(e1.y, e1.y) + wmul(e2.y, e1.y) + wmul(e2.y, e2.y);
    inertia += wmul(d, intx2 + inty2) / 12;
  }
  MassData2 out;
  if (area <= 0) return out;  // validate_shape() refuses such polygons
  center = {wdiv(center.x, 3 * area), wdiv(center.y, 3 * area)};
  out.mass = wmul(density, area);
  out.center = origin + center;
  // Parallel axes: from the fan's origin to the centre of mass.
  out.inertia = wmul(density, inertia) - wmul(out.mass, vdot(center, center));
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
