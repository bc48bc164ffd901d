// SPDX-License-Identifier: MIT
// Sphere-sphere and box-sphere manifolds (one point each).
#include <cmath>

#include "d3/manifold.h"

namespace rwd::sim::d3 {

void collide_spheres(Vec3 center_a, float radius_a, Vec3 center_b, float radius_b,
                     float speculative_m, Manifold& out) {
  out.point_count = 0;
  Vec3 d = center_b - center_a;
  float dist_sq = length_squared(d);
  float reach = radius_a + radius_b + speculative_m;
  if (dist_sq > reach * reach) return;
  float dist = std::sqrt(dist_sq);
  // Coincident centres: any normal is right; pick +y so the result is defined.
  Vec3 n = dist > 1e-9f ? d * (1.0f / dist) : Vec3{0.0f, 1.0f, 0.0f};
  float separation = dist - radius_a - radius_b;
  Vec3 surface_a = center_a + n * radius_a;
  Vec3 surface_b = center_b - n * radius_b;
  out.normal = n;
  out.point_count = 1;
  out.points[0].point = (surface_a + surface_b) * 0.5f;
  out.points[0].separation = separation;
  out.points[0].feature_id = 0;
}

void collide_box_sphere(const BoxPose& box, Vec3 center, float radius, float speculative_m,
                        Manifold& out) {
  out.point_count = 0;
  Vec3 h = box.half_extents;
  Vec3 c = inv_rotate(box.rotation, center - box.center);
  Vec3 clamped = min(max(c, -h), h);
  Vec3 d = c - clamped;
  float dist_sq = length_squared(d);
  Vec3 n_local;
  Vec3 box_point_local;
  float separation = 0.0f;
  uint32_t id = 0;
  if (dist_sq > 0.0f) {
    float reach = radius + speculative_m;
    if (dist_sq > reach * reach) return;
    float dist = std::sqrt(dist_sq);
    n_local = d * (1.0f / dist);
    separation = dist - radius;
    box_point_local = clamped;
    auto region = [](float v, float half) -> uint32_t {
      return v < -half ? 0u : (v > half ? 2u : 1u);
    };
    id = region(c.x, h.x) + 3u * region(c.y, h.y) + 9u * region(c.z, h.z);
  } else {
    // Centre inside the box: push out through the nearest face (ties go to
    // the lower axis so the choice is a function of the input bits).
    int axis = 0;
    float best = h.x - std::fabs(c.x);
    for (int i = 1; i < 3; ++i) {
      float depth = component(h, i) - std::fabs(component(c, i));
      if (depth < best) {
        best = depth;
        axis = i;
      }
    }
    float sign = component(c, axis) >= 0.0f ? 1.0f : -1.0f;
    float coords[3] = {c.x, c.y, c.z};
    float normal[3] = {0.0f, 0.0f, 0.0f};
    normal[axis] = sign;
    coords[axis] = sign * component(h, axis);
    n_local = {normal[0], normal[1], normal[2]};
    box_point_local = {coords[0], coords[1], coords[2]};
    separation = -best - radius;
    id = 27u + static_cast<uint32_t>(axis) * 2u + (sign > 0.0f ? 1u : 0u);
  }
  Vec3 n = rotate(box.rotation, n_local);
  Vec3 surface_a = box.center + rotate(box.rotation, box_point_local);
  Vec3 surface_b = center - n * radius;
  out.normal = n;
  out.point_count = 1;
  out.points[0].point = (surface_a + surface_b) * 0.5f;
  out.points[0].separation = separation;
  out.points[0].feature_id = id;
}

}  // namespace rwd::sim::d3
