// SPDX-License-Identifier: MIT
#include "d3/query_trees.h"

#include "d3/body_storage.h"

namespace rwd::sim::d3 {
namespace {

void build(const WorldState& state, WorldScratch& scratch, bool statics, AabbTree& tree) {
  scratch.query_bodies.clear();
  scratch.query_boxes.clear();
  for (uint32_t i = 0; i < state.infos.size(); ++i) {
    const BodyInfo& info = state.infos[i];
    if (!is_simulated(info) || (info.kind == BodyKind::kStatic) != statics) continue;
    const BodySim& sim = state.sims[i];
    scratch.query_bodies.push_back(i);
    scratch.query_boxes.push_back(shape_aabb(info.shape, sim.position, sim.rotation));
  }
  tree.build(scratch.query_boxes, scratch.query_bodies, scratch.query_proxies);
}

}  // namespace

void refresh_query_trees(const WorldState& state, WorldScratch& scratch) {
  if (scratch.query_edited) build(state, scratch, true, scratch.query_static);
  if (scratch.query_edited || scratch.query_serial != scratch.step_serial) {
    build(state, scratch, false, scratch.query_movable);
  }
  scratch.query_edited = false;
  scratch.query_serial = scratch.step_serial;
}

bool query_accepts(const WorldState& state, const QueryFilter& filter, uint32_t i) {
  const BodyInfo& info = state.infos[i];
  if (!is_simulated(info) || (info.layer & filter.layer_mask) == 0) return false;
  return info.sensor == 0 || filter.include_sensors;
}

}  // namespace rwd::sim::d3
