// SPDX-License-Identifier: MIT
// Narrowphase: one manifold per broadphase pair, merged with last step's
// contact cache. Both lists are sorted by (index_a, index_b), so matching is
// a linear merge (no hash map, no search). Points keep their impulses when
// their feature id reappears (warm starting); new points start at zero.
// Contacts whose bodies both sleep are carried over as they are: nothing
// moved, so their manifold is still valid and costs nothing.
#include <cmath>

#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

uint64_t key(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(a) << 32) | b;
}

// Extra speculative reach for a pair: how far the two bodies can close in
// one tick. The config's speculative distance alone would let a body faster
// than speculative/tick sink deep before its contact exists.
float pair_speculative(const WorldState& state, uint32_t a, uint32_t b) {
  const BodySim& sa = state.sims[a];
  const BodySim& sb = state.sims[b];
  float reach = length(sb.linear_velocity - sa.linear_velocity) +
                length(sa.angular_velocity) * state.masses[a].extent +
                length(sb.angular_velocity) * state.masses[b].extent;
  return state.config.speculative_distance_m + state.config.tick_seconds * reach;
}

// Computes the manifold and fills `rec` (ids, touching, impulses matched by
// feature id against `old`, which may be null or `rec` itself).
void evaluate(const WorldState& state, ContactRecord& rec, const ContactRecord* old,
              ContactGeometry& geo) {
  const BodyInfo& ia = state.infos[rec.index_a];
  const BodyInfo& ib = state.infos[rec.index_b];
  const BodySim& sa = state.sims[rec.index_a];
  const BodySim& sb = state.sims[rec.index_b];
  collide_shapes(ia.shape, sa.position, sa.rotation, ib.shape, sb.position, sb.rotation,
                 pair_speculative(state, rec.index_a, rec.index_b), geo.manifold);
  geo.friction = std::sqrt(ia.material.friction * ib.material.friction);
  geo.restitution = ia.material.restitution > ib.material.restitution ? ia.material.restitution
                                                                      : ib.material.restitution;
  geo.valid = 1;
  rec.sensor = (ia.sensor != 0 || ib.sensor != 0) ? 1 : 0;
  // Touching is geometric and independent of speed: sensors need a real
  // overlap, solid pairs a point within the configured speculative distance
  // (the contact the solver is holding apart), as in Box2D.
  float limit = rec.sensor != 0 ? 0.0f : state.config.speculative_distance_m;
  uint8_t touching = 0;
  CachedContactPoint points[kMaxManifoldPoints];
  const Manifold& m = geo.manifold;
  for (uint32_t i = 0; i < m.point_count; ++i) {
    if (rec.sensor != 0 ? m.points[i].separation < limit : m.points[i].separation <= limit) {
      touching = 1;
    }
    points[i] = CachedContactPoint{m.points[i].feature_id, 0.0f, 0.0f, 0.0f};
    if (old == nullptr || rec.sensor != 0) continue;
    for (uint32_t j = 0; j < old->point_count; ++j) {
      if (old->points[j].feature_id == points[i].feature_id) {
        points[i] = old->points[j];
        break;
      }
    }
  }
  rec.touching = touching;
  rec.point_count = rec.sensor != 0 ? 0 : static_cast<uint8_t>(m.point_count);
  for (uint32_t i = 0; i < kMaxManifoldPoints; ++i) {
    rec.points[i] = i < rec.point_count ? points[i] : CachedContactPoint{};
  }
}

bool both_resting(const WorldState& state, const ContactRecord& r) {
  const BodyInfo& a = state.infos[r.index_a];
  const BodyInfo& b = state.infos[r.index_b];
  return is_simulated(a) && is_simulated(b) && a.generation == r.generation_a &&
         b.generation == r.generation_b && !is_active(a) && !is_active(b);
}

}  // namespace

void update_contacts(WorldState& state, WorldScratch& scratch) {
  std::vector<ContactRecord>& old = scratch.other_contacts;
  old.swap(state.contacts);  // old = last step's cache; state.contacts is rebuilt
  std::vector<ContactRecord>& out = state.contacts;
  out.clear();
  const std::vector<BodyPair>& pairs = scratch.pairs;
  // geometry[k] belongs to out[k]. Its slots are kept from step to step and
  // written in place (only grown here), so a carried record costs one byte
  // and an evaluated one no copy.
  std::vector<ContactGeometry>& geometry = scratch.geometry;
  if (geometry.size() < old.size() + pairs.size()) geometry.resize(old.size() + pairs.size());
  size_t i = 0;
  size_t j = 0;
  while (i < pairs.size() || j < old.size()) {
    uint64_t kp = i < pairs.size() ? key(pairs[i].a, pairs[i].b) : ~uint64_t{0};
    uint64_t ko = j < old.size() ? key(old[j].index_a, old[j].index_b) : ~uint64_t{0};
    if (j < old.size() && (i == pairs.size() || ko < kp)) {
      if (both_resting(state, old[j])) {
        geometry[out.size()].valid = 0;
        out.push_back(old[j]);
      }
      ++j;
      continue;
    }
    ContactRecord rec;
    rec.index_a = pairs[i].a;
    rec.index_b = pairs[i].b;
    rec.generation_a = state.infos[rec.index_a].generation;
    rec.generation_b = state.infos[rec.index_b].generation;
    const ContactRecord* prior = nullptr;
    if (kp == ko) {
      if (old[j].generation_a == rec.generation_a && old[j].generation_b == rec.generation_b) {
        prior = &old[j];
      }
      ++j;
    }
    ++i;
    ContactGeometry& geo = geometry[out.size()];
    evaluate(state, rec, prior, geo);
    // Pairs whose bounds overlap but whose shapes are out of reach are not
    // kept: the cache holds only pairs that have (or had) points.
    if (geo.manifold.point_count == 0 && rec.touching == 0) continue;
    out.push_back(rec);
  }
}

void refresh_contact(WorldState& state, WorldScratch& scratch, uint32_t index) {
  ContactRecord& rec = state.contacts[index];
  ContactRecord prior = rec;
  evaluate(state, rec, &prior, scratch.geometry[index]);
}

}  // namespace rwd::sim::d3
