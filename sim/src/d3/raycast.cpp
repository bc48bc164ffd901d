// SPDX-License-Identifier: MIT
// Ray queries. A linear scan over live bodies in index order: queries are
// rare next to the step and the scan is exactly reproducible; a BVH over the
// broadphase bounds is the planned replacement when scenes grow. Rays that
// start inside a shape hit it at distance 0 with the normal facing back
// along the ray.
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

bool ray_sphere(Vec3 origin, Vec3 dir, float max_distance, Vec3 center, float radius, float& t,
                Vec3& normal) {
  Vec3 m = origin - center;
  float b = dot(m, dir);
  float c = dot(m, m) - radius * radius;
  if (c <= 0.0f) {  // inside
    t = 0.0f;
    normal = -dir;
    return true;
  }
  if (b > 0.0f) return false;  // outside and pointing away
  float disc = b * b - c;
  if (disc < 0.0f) return false;
  t = -b - std::sqrt(disc);
  if (t < 0.0f) t = 0.0f;
  if (t > max_distance) return false;
  normal = normalize_or_zero(origin + dir * t - center);
  return true;
}

bool ray_box(Vec3 origin, Vec3 dir, float max_distance, Vec3 center, Quat rotation, Vec3 half,
             float& t, Vec3& normal) {
  Vec3 o = inv_rotate(rotation, origin - center);
  Vec3 d = inv_rotate(rotation, dir);
  float t_enter = -1.0f;  // below any real entry: origin inside until proven outside
  float t_exit = max_distance;
  int enter_axis = -1;
  float enter_sign = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float oi = component(o, i);
    float di = component(d, i);
    float hi = component(half, i);
    if (std::fabs(di) < 1e-12f) {
      if (oi < -hi || oi > hi) return false;
      continue;
    }
    float inv = 1.0f / di;
    float t1 = (-hi - oi) * inv;
    float t2 = (hi - oi) * inv;
    float sign = -1.0f;  // entering through the -axis face
    if (t1 > t2) {
      float tmp = t1;
      t1 = t2;
      t2 = tmp;
      sign = 1.0f;
    }
    if (t1 > t_enter) {
      t_enter = t1;
      enter_axis = i;
      enter_sign = sign;
    }
    if (t2 < t_exit) t_exit = t2;
    if (t_enter > t_exit) return false;
  }
  if (t_exit < 0.0f) return false;
  if (t_enter <= 0.0f) {  // origin inside the box
    t = 0.0f;
    normal = -dir;
    return true;
  }
  t = t_enter;
  float n[3] = {0.0f, 0.0f, 0.0f};
  n[enter_axis] = enter_sign;
  normal = rotate(rotation, Vec3{n[0], n[1], n[2]});
  return true;
}

bool prepare_ray(const Ray& ray, Vec3& dir) {
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !std::isfinite(ray.max_distance) ||
      ray.max_distance < 0.0f) {
    return false;
  }
  dir = normalize_or_zero(ray.direction);
  return !(dir == Vec3{});
}

template <class Visit>
void cast(const WorldState& state, const Ray& ray, Vec3 dir, const QueryFilter& filter,
          Visit&& visit) {
  for (uint32_t i = 0; i < state.infos.size(); ++i) {
    const BodyInfo& info = state.infos[i];
    if (!d3::is_simulated(info) || (info.layer & filter.layer_mask) == 0) continue;
    if (info.sensor != 0 && !filter.include_sensors) continue;
    const BodySim& sim = state.sims[i];
    float t = 0.0f;
    Vec3 normal;
    bool hit = info.shape.type == ShapeType::kSphere
                   ? ray_sphere(ray.origin, dir, ray.max_distance, sim.position, info.shape.radius,
                                t, normal)
                   : ray_box(ray.origin, dir, ray.max_distance, sim.position, sim.rotation,
                             info.shape.half_extents, t, normal);
    if (!hit) continue;
    visit(RayHit{BodyId{i, info.generation}, t, ray.origin + dir * t, normal});
  }
}

}  // namespace

std::optional<RayHit> World3D::raycast(const Ray& ray, const QueryFilter& filter) const {
  Vec3 dir;
  if (!prepare_ray(ray, dir)) return std::nullopt;
  std::optional<RayHit> best;
  // Index order plus a strict comparison: ties go to the lower index.
  cast(state_, ray, dir, filter, [&](const RayHit& hit) {
    if (!best || hit.distance < best->distance) best = hit;
  });
  return best;
}

void World3D::raycast_all(const Ray& ray, const QueryFilter& filter,
                          std::vector<RayHit>& out) const {
  out.clear();
  Vec3 dir;
  if (!prepare_ray(ray, dir)) return;
  cast(state_, ray, dir, filter, [&](const RayHit& hit) { out.push_back(hit); });
  std::sort(out.begin(), out.end(), [](const RayHit& l, const RayHit& r) {
    return l.distance < r.distance || (l.distance == r.distance && l.body.index < r.body.index);
  });
}

}  // namespace rwd::sim
