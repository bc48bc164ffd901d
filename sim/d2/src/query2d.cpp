// SPDX-License-Identifier: MIT
// World2D's read-only queries. Each walks the body slots in index order,
// skips what the filter refuses, culls by world bounds and runs the exact
// test on the rest, so results come out in index order with no sort and
// "ties to the lower index" is a strict comparison.
#include <algorithm>

#include "body_math2d.h"
#include "distance2d.h"
#include "query_filter2d.h"
#include "ray_shape2d.h"
#include "rewind/sim2d/world2d.h"
#include "shape_bounds2d.h"
#include "shape_cast2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

struct Ray {
  V2 origin;
  V2 unit;
  W length = 0;
  Box2W box;
};

Ray make_ray(Vec2 origin, Vec2 translation) {
  Ray r;
  r.origin = v_from(origin);
  const UnitLength u = vnormalize(v_from(translation));
  r.unit = u.unit;
  r.length = u.length;
  const V2 end = r.origin + v_from(translation);
  r.box = {vmin(r.origin, end), vmax(r.origin, end)};
  return r;
}

RayHit2D to_hit(uint32_t index, const BodyRecord2D& body, const RayResult2& r, W length) {
  RayHit2D h;
  h.body = {index, body.generation};
  h.point = v_to_fx(r.point);
  h.normal = v_to_fx(r.normal);
  h.fraction = w_to_fx(wdiv(r.distance, length));
  h.distance = w_to_fx(r.distance);
  return h;
}

}  // namespace

std::optional<RayHit2D> World2D::raycast(Vec2 origin, Vec2 translation,
                                         const QueryFilter2D& filter) const {
  const Ray ray = make_ray(origin, translation);
  if (ray.length == 0) return std::nullopt;
  bool found = false;
  W best = ray.length;
  RayResult2 best_hit;
  uint32_t best_index = 0;
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    const Xf xf = origin_transform(b);
    if (!overlaps(ray.box, shape_bounds(b.shape, xf))) continue;
    RayResult2 hit;
    if (!ray_shape(b.shape, xf, ray.origin, ray.unit, best, hit)) continue;
    if (found && hit.distance >= best) continue;  // ties: the lower index
    found = true;
    best = hit.distance;
    best_hit = hit;
    best_index = i;
  }
  if (!found) return std::nullopt;
  return to_hit(best_index, state_.bodies[best_index], best_hit, ray.length);
}

void World2D::raycast_all(Vec2 origin, Vec2 translation, const QueryFilter2D& filter,
                          std::vector<RayHit2D>& out) const {
  out.clear();
  const Ray ray = make_ray(origin, translation);
  if (ray.length == 0) return;
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    const Xf xf = origin_transform(b);
    if (!overlaps(ray.box, shape_bounds(b.shape, xf))) continue;
    RayResult2 hit;
    if (ray_shape(b.shape, xf, ray.origin, ray.unit, ray.length, hit)) {
      out.push_back(to_hit(i, b, hit, ray.length));
    }
  }
  // Found in index order, so a stable sort by distance leaves equal
  // distances in index order. Distances are compared in Fx, what the
  // caller sees; std::stable_sort may allocate, insertion sort does not.
  for (size_t i = 1; i < out.size(); ++i) {
    const RayHit2D h = out[i];
    size_t j = i;
    for (; j > 0 && h.distance < out[j - 1].distance; --j) out[j] = out[j - 1];
    out[j] = h;
  }
}

void World2D::query_aabb(Vec2 lower, Vec2 upper, const QueryFilter2D& filter,
                         std::vector<BodyId2D>& out) const {
  out.clear();
  const Box2W box{v_from(lower), v_from(upper)};
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    if (overlaps(box, shape_bounds(b.shape, origin_transform(b)))) {
      out.push_back({i, b.generation});
    }
  }
}

void World2D::overlap(const Shape2D& shape, Vec2 position, Fx angle, const QueryFilter2D& filter,
                      std::vector<BodyId2D>& out) const {
  out.clear();
  if (shape.count == 0 || shape.count > kMaxPolygonVertices) return;
  const Xf xf{v_from(position), rotation_from_angle(angle)};
  const Box2W box = shape_bounds(shape, xf);
  const WPoly core = shape_core(shape, xf);
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    const Xf bxf = origin_transform(b);
    if (!overlaps(box, shape_bounds(b.shape, bxf))) continue;
    if (shape_distance(core, shape_core(b.shape, bxf)).distance < 0) {
      out.push_back({i, b.generation});
    }
  }
}

std::optional<ShapeHit2D> World2D::shape_cast(const Shape2D& shape, Vec2 position, Fx angle,
                                              Vec2 translation, const QueryFilter2D& filter) const {
  if (shape.count == 0 || shape.count > kMaxPolygonVertices) return std::nullopt;
  const Xf xf{v_from(position), rotation_from_angle(angle)};
  CastResult2 hit;
  if (!cast_core(state_, filter, shape_core(shape, xf), v_from(translation), 0, hit)) {
    return std::nullopt;
  }
  ShapeHit2D out;
  out.body = {hit.index, state_.bodies[hit.index].generation};
  out.point = v_to_fx(hit.point);
  out.normal = v_to_fx(hit.normal);
  out.fraction = w_to_fx(hit.fraction);
  return out;
}

std::optional<NearestBody2D> World2D::nearest_body(Vec2 point, Fx max_distance,
                                                   const QueryFilter2D& filter) const {
  const V2 p = v_from(point);
  const W reach = wmax(w_from(max_distance), 0);
  const Box2W box{p - V2{reach, reach}, p + V2{reach, reach}};
  const WPoly core = point_core(p);
  bool found = false;
  W best = reach;
  Distance2 best_d;
  uint32_t best_index = 0;
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    const Xf xf = origin_transform(b);
    if (!overlaps(box, shape_bounds(b.shape, xf))) continue;
    const Distance2 d = shape_distance(core, shape_core(b.shape, xf));
    const W dist = wmax(d.distance, 0);
    if (dist > best || (found && dist >= best)) continue;
    found = true;
    best = dist;
    best_d = d;
    best_index = i;
  }
  if (!found) return std::nullopt;
  NearestBody2D out;
  out.body = {best_index, state_.bodies[best_index].generation};
  out.distance = w_to_fx(best);
  out.point = best_d.distance <= 0 ? point : v_to_fx(best_d.point_b);
  return out;
}

Fx World2D::signed_distance(BodyId2D body, Vec2 point) const {
  if (!is_valid(body)) return Fx::max();
  const BodyRecord2D& b = state_.bodies[body.index];
  return w_to_fx(
      shape_distance(point_core(v_from(point)), shape_core(b.shape, origin_transform(b))).distance);
}

Fx World2D::signed_distance(Vec2 point, const QueryFilter2D& filter) const {
  const WPoly core = point_core(v_from(point));
  bool found = false;
  W best = 0;
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& b = state_.bodies[i];
    if (!passes_filter(b, i, filter)) continue;
    // A body whose bounds are farther than the best so far cannot beat it.
    const Xf xf = origin_transform(b);
    const Box2W box = shape_bounds(b.shape, xf);
    const W gap = wmax(wmax(box.lower.x - core.vertices[0].x, core.vertices[0].x - box.upper.x),
                       wmax(box.lower.y - core.vertices[0].y, core.vertices[0].y - box.upper.y));
    if (found && gap > best) continue;
    const W d = shape_distance(core, shape_core(b.shape, xf)).distance;
    if (!found || d < best) best = d;
    found = true;
  }
  return found ? w_to_fx(best) : Fx::max();
}

}  // namespace rwd::sim2d
