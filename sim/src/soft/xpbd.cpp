// SPDX-License-Identifier: MIT
#include "soft/xpbd.h"

namespace rwd::sim::soft {

void predict(std::span<Vec3> position, std::span<Vec3> previous, std::span<Vec3> velocity,
             std::span<const float> inverse_mass, Vec3 gravity, float dt) {
  for (size_t i = 0; i < position.size(); ++i) {
    previous[i] = position[i];
    if (inverse_mass[i] == 0.0f) continue;
    velocity[i] += gravity * dt;
    position[i] += velocity[i] * dt;
  }
}

void solve_distance(std::span<Vec3> position, std::span<const float> inverse_mass,
                    std::span<const DistanceLink> links, std::span<float> lambda,
                    const float (&compliance)[3], float dt) {
  const float inv_dt2 = 1.0f / (dt * dt);
  for (size_t k = 0; k < links.size(); ++k) {
    const DistanceLink& link = links[k];
    const float wa = inverse_mass[link.a];
    const float wb = inverse_mass[link.b];
    const float alpha = compliance[static_cast<uint8_t>(link.kind)] * inv_dt2;
    const float w = wa + wb;
    if (w + alpha == 0.0f) continue;  // both pinned and rigid: nothing can move
    const Vec3 d = position[link.a] - position[link.b];
    const float len = length(d);
    if (len == 0.0f) continue;  // no direction to push along
    const Vec3 n = d * (1.0f / len);
    const float c = len - link.rest;
    const float dlambda = (-c - alpha * lambda[k]) / (w + alpha);
    lambda[k] += dlambda;
    position[link.a] += n * (wa * dlambda);
    position[link.b] -= n * (wb * dlambda);
  }
}

void update_velocities(std::span<const Vec3> position, std::span<const Vec3> previous,
                       std::span<Vec3> velocity, float dt) {
  const float inv_dt = 1.0f / dt;
  for (size_t i = 0; i < position.size(); ++i) {
    velocity[i] = (position[i] - previous[i]) * inv_dt;
  }
}

}  // namespace rwd::sim::soft
