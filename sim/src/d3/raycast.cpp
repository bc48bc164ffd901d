// SPDX-License-Identifier: MIT
// Ray queries, through the broadphase (broadphase.h): the bodies whose
// bounds the ray's segment touches are tested exactly, in index order, so
// ties go to the lower index and no tree shape reaches a result. Rays that
// start inside a shape hit it at distance 0 with the normal facing back
// along the ray.
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

bool prepare_ray(const Ray& ray, Vec3& dir) {
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !std::isfinite(ray.max_distance) ||
      ray.max_distance < 0.0f) {
    return false;
  }
  dir = normalize_or_zero(ray.direction);
  return !(dir == Vec3{});
}

// Calls visit(hit) for every body the ray hits, in index order: the
// candidates the broadphase gives for the ray's segment, sorted, each
// tested exactly.
template <class Visit>
void cast(const WorldState& state, WorldScratch& scratch, const Ray& ray, Vec3 dir,
          const QueryFilter& filter, Visit&& visit) {
  d3::prepare_queries(state, scratch);
  std::vector<uint32_t>& candidates = scratch.query_hits;
  candidates.clear();
  const auto collect = [&](uint32_t i) {
    if (d3::query_accepts(state, filter, i)) candidates.push_back(i);
  };
  scratch.broadphase.ray_query(ray.origin, dir, ray.max_distance, collect);
  std::sort(candidates.begin(), candidates.end());
  for (const uint32_t i : candidates) {
    const BodyInfo& info = state.infos[i];
    const BodySim& sim = state.sims[i];
    float t = 0.0f;
    Vec3 normal;
    if (!d3::shape_ops(info.shape.type)
             .raycast(info.shape, *scratch.store, sim.position, sim.rotation, ray.origin, dir,
                      ray.max_distance, t, normal)) {
      continue;
    }
    visit(RayHit{BodyId{i, info.generation}, t, ray.origin + dir * t, normal});
  }
}

}  // namespace

std::optional<RayHit> World3D::raycast(const Ray& ray, const QueryFilter& filter) const {
  Vec3 dir;
  if (!prepare_ray(ray, dir)) return std::nullopt;
  d3::prepare_queries(state_, *scratch_);
  std::optional<RayHit> best;
  // The trees are walked near to far, the segment cut short at the best hit
  // so far; the nearest hit wins, ties to the lower index, as if every
  // body the segment reaches were tested.
  float reach = ray.max_distance;
  const auto test = [&](uint32_t i) {
    if (!d3::query_accepts(state_, filter, i)) return;
    const BodyInfo& info = state_.infos[i];
    const BodySim& sim = state_.sims[i];
    float t = 0.0f;
    Vec3 normal;
    if (!d3::shape_ops(info.shape.type)
             .raycast(info.shape, *scratch_->store, sim.position, sim.rotation, ray.origin, dir,
                      ray.max_distance, t, normal)) {
      return;
    }
    if (best && (t > best->distance || (t == best->distance && i > best->body.index))) return;
    best = RayHit{BodyId{i, info.generation}, t, ray.origin + dir * t, normal};
    reach = t;
  };
  scratch_->broadphase.ray_query_nearest(ray.origin, dir, reach, test);
  return best;
}

void World3D::raycast_all(const Ray& ray, const QueryFilter& filter,
                          std::vector<RayHit>& out) const {
  out.clear();
  Vec3 dir;
  if (!prepare_ray(ray, dir)) return;
  cast(state_, *scratch_, ray, dir, filter, [&](const RayHit& hit) { out.push_back(hit); });
  std::sort(out.begin(), out.end(), [](const RayHit& l, const RayHit& r) {
    return l.distance < r.distance || (l.distance == r.distance && l.body.index < r.body.index);
  });
}

}  // namespace rwd::sim
