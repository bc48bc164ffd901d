// SPDX-License-Identifier: MIT
// World2D's read-only queries. Each asks the bounds tree for the bodies
// whose bounds its own bounds overlap, skips what the filter refuses and
// runs the exact test on the rest. The tree visits bodies in an order of
// its own, so every comparison breaks ties by body index and every list is
// sorted before it is handed back: results depend on the state alone.
#include <algorithm>

#include "body_math2d.h"
#include "distance2d.h"
#include "query_cache2d.h"
#include "query_filter2d.h"
#include "ray_shape2d.h"
#include "rewind/sim2d/world2d.h"
#include "shape_bounds2d.h"
#include "shape_cast2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

using Item = World2D::QueryCache::Item;

struct Ray {
  V2 origin;
  V2 unit;
  W length = 0;
};

Ray make_ray(Vec2 origin, Vec2 translation) {
  Ray r;
  r.origin = v_from(origin);
  const UnitLength u = vnormalize(v_from(translation));
  r.unit = u.unit;
  r.length = u.length;
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

void sort_by_index(std::vector<BodyId2D>& out) {
  std::sort(out.begin(), out.end(),
            [](const BodyId2D& a, const BodyId2D& b) { return a.index < b.index; });
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
  const V2 far_end = vmul_add(ray.origin, ray.length, ray.unit);
  query_cache().query_segment(ray.origin, far_end, [&](const Item& item, V2 end) {
    const BodyRecord2D& b = state_.bodies[item.index];
    if (!passes_filter(b, item.index, filter)) return end;
    RayResult2 hit;
    if (!ray_shape(b.shape, origin_transform(b), ray.origin, ray.unit, best, hit)) return end;
    if (found && (hit.distance > best || (hit.distance == best && item.index > best_index))) {
      return end;
    }
    found = true;
    best = hit.distance;
    best_hit = hit;
    best_index = item.index;
    // Nothing beyond the best hit can beat it (a tie at it can, by index).
    return vmul_add(ray.origin, best, ray.unit);
  });
  if (!found) return std::nullopt;
  return to_hit(best_index, state_.bodies[best_index], best_hit, ray.length);
}

void World2D::raycast_all(Vec2 origin, Vec2 translation, const QueryFilter2D& filter,
                          std::vector<RayHit2D>& out) const {
  out.clear();
  const Ray ray = make_ray(origin, translation);
  if (ray.length == 0) return;
  const V2 far_end = vmul_add(ray.origin, ray.length, ray.unit);
  query_cache().query_segment(ray.origin, far_end, [&](const Item& item, V2 end) {
    const BodyRecord2D& b = state_.bodies[item.index];
    RayResult2 hit;
    if (passes_filter(b, item.index, filter) &&
        ray_shape(b.shape, origin_transform(b), ray.origin, ray.unit, ray.length, hit)) {
      out.push_back(to_hit(item.index, b, hit, ray.length));
    }
    return end;
  });
  // Near to far as the caller sees the distances (Fx), then by index.
  std::sort(out.begin(), out.end(), [](const RayHit2D& a, const RayHit2D& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.body.index < b.body.index;
  });
}

void World2D::query_aabb(Vec2 lower, Vec2 upper, const QueryFilter2D& filter,
                         std::vector<BodyId2D>& out) const {
  out.clear();
  query_cache().query({v_from(lower), v_from(upper)}, [&](const Item& item, const Box2W& cull) {
    const BodyRecord2D& b = state_.bodies[item.index];
    if (passes_filter(b, item.index, filter)) out.push_back({item.index, b.generation});
    return cull;
  });
  sort_by_index(out);
}

void World2D::overlap(const Shape2D& shape, Vec2 position, Fx angle, const QueryFilter2D& filter,
                      std::vector<BodyId2D>& out) const {
  out.clear();
  if (shape.count == 0 || shape.count > kMaxPolygonVertices) return;
  const Xf xf{v_from(position), rotation_from_angle(angle)};
  const WPoly core = shape_core(shape, xf);
  query_cache().query(shape_bounds(shape, xf), [&](const Item& item, const Box2W& cull) {
    const BodyRecord2D& b = state_.bodies[item.index];
    if (passes_filter(b, item.index, filter) &&
        shape_distance(core, shape_core(b.shape, origin_transform(b))).distance < 0) {
      out.push_back({item.index, b.generation});
    }
    return cull;
  });
  sort_by_index(out);
}

std::optional<ShapeHit2D> World2D::shape_cast(const Shape2D& shape, Vec2 position, Fx angle,
                                              Vec2 translation, const QueryFilter2D& filter) const {
  if (shape.count == 0 || shape.count > kMaxPolygonVertices) return std::nullopt;
  const Xf xf{v_from(position), rotation_from_angle(angle)};
  CastResult2 hit;
  if (!cast_core(*this, filter, shape_core(shape, xf), v_from(translation), 0, hit)) {
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
  const WPoly core = point_core(p);
  bool found = false;
  W best = reach;
  Distance2 best_d;
  uint32_t best_index = 0;
  const Box2W box{p - V2{reach, reach}, p + V2{reach, reach}};
  query_cache().query(box, [&](const Item& item, const Box2W& cull) {
    const BodyRecord2D& b = state_.bodies[item.index];
    if (!passes_filter(b, item.index, filter)) return cull;
    const Distance2 d = shape_distance(core, shape_core(b.shape, origin_transform(b)));
    const W dist = wmax(d.distance, 0);
    if (dist > best || (found && dist == best && item.index > best_index)) return cull;
    found = true;
    best = dist;
    best_d = d;
    best_index = item.index;
    return Box2W{p - V2{best, best}, p + V2{best, best}};
  });
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
  const V2 p = v_from(point);
  const WPoly core = point_core(p);
  bool found = false;
  W best = 0;
  // Everything, until a first body bounds the search (positions stay far
  // inside +-2^46 m, so the box cannot wrap).
  constexpr W kFar = W{1} << 62;
  query_cache().query({{-kFar, -kFar}, {kFar, kFar}}, [&](const Item& item, const Box2W& cull) {
    const BodyRecord2D& b = state_.bodies[item.index];
    if (!passes_filter(b, item.index, filter)) return cull;
    const W d = shape_distance(core, shape_core(b.shape, origin_transform(b))).distance;
    if (found && d >= best) return cull;
    found = true;
    best = d;
    const W r = wmax(best, 0);
    return Box2W{p - V2{r, r}, p + V2{r, r}};
  });
  return found ? w_to_fx(best) : Fx::max();
}

}  // namespace rwd::sim2d
