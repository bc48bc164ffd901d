// SPDX-License-Identifier: MIT
// Islands and sleep. An island is a set of dynamic bodies connected by
// touching solid contacts (static and kinematic bodies do not connect
// islands, or a whole level would be one island). Islands are found with a
// union-find over the contact cache in index order; roots are always the
// lowest index, so the result is a pure function of the state. Persistent
// islands (Box2D v3 style) were rejected for the first cut: recomputing is
// simpler to keep exact under rollback, and costs one pass over the contacts.
#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
  uint32_t ra = find_root(parent, a);
  uint32_t rb = find_root(parent, b);
  if (ra == rb) return;
  if (ra < rb) {
    parent[rb] = ra;
  } else {
    parent[ra] = rb;
  }
}

bool live_record(const WorldState& state, const ContactRecord& r) {
  const BodyInfo& a = state.infos[r.index_a];
  const BodyInfo& b = state.infos[r.index_b];
  return is_simulated(a) && is_simulated(b) && a.generation == r.generation_a &&
         b.generation == r.generation_b;
}

bool links_island(const WorldState& state, const ContactRecord& r) {
  return r.touching != 0 && r.sensor == 0 && live_record(state, r) &&
         state.infos[r.index_a].kind == BodyKind::kDynamic &&
         state.infos[r.index_b].kind == BodyKind::kDynamic;
}

void build_islands(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.island_parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) scratch.island_parent[i] = i;
  for (const ContactRecord& r : state.contacts) {
    if (links_island(state, r)) unite(scratch.island_parent, r.index_a, r.index_b);
  }
}

// A moving kinematic body keeps what it touches awake.
bool is_moving_kinematic(const WorldState& state, uint32_t i) {
  const BodyInfo& info = state.infos[i];
  return info.kind == BodyKind::kKinematic && info.awake != 0 && state.sims[i].sleep_time == 0.0f;
}

}  // namespace

void wake_body(WorldState& state, uint32_t index) {
  BodyInfo& info = state.infos[index];
  if (!is_simulated(info) || info.kind == BodyKind::kStatic) return;
  state.sims[index].sleep_time = 0.0f;
  info.awake = 1;
}

void wake_touching(WorldState& state, BodyId id) {
  for (const ContactRecord& r : state.contacts) {
    if (r.touching == 0 || !live_record(state, r)) continue;
    if (r.index_a == id.index && r.generation_a == id.generation) {
      wake_body(state, r.index_b);
    } else if (r.index_b == id.index && r.generation_b == id.generation) {
      wake_body(state, r.index_a);
    }
  }
}

void wake_touched_islands(WorldState& state, WorldScratch& scratch) {
  // Nothing awake (the broadphase's list of awake movers is empty) wakes
  // nothing.
  if (scratch.active.empty()) return;
  // Cheap test first: does any touching contact join an awake mover and a
  // sleeping dynamic body? Usually not, and then no island work is done.
  bool needed = false;
  for (const ContactRecord& r : state.contacts) {
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) continue;
    const BodyInfo& a = state.infos[r.index_a];
    const BodyInfo& b = state.infos[r.index_b];
    bool a_sleeps = a.kind == BodyKind::kDynamic && a.awake == 0;
    bool b_sleeps = b.kind == BodyKind::kDynamic && b.awake == 0;
    if ((a_sleeps && is_active(b)) || (b_sleeps && is_active(a))) {
      needed = true;
      break;
    }
  }
  if (!needed) return;
  build_islands(state, scratch);
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.island_flag.assign(n, 0);
  for (uint32_t i = 0; i < n; ++i) {
    const BodyInfo& info = state.infos[i];
    if (info.alive != 0 && info.kind == BodyKind::kDynamic && info.awake != 0) {
      scratch.island_flag[find_root(scratch.island_parent, i)] = 1;
    }
  }
  for (const ContactRecord& r : state.contacts) {
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) continue;
    if (is_moving_kinematic(state, r.index_a) &&
        state.infos[r.index_b].kind == BodyKind::kDynamic) {
      scratch.island_flag[find_root(scratch.island_parent, r.index_b)] = 1;
    }
    if (is_moving_kinematic(state, r.index_b) &&
        state.infos[r.index_a].kind == BodyKind::kDynamic) {
      scratch.island_flag[find_root(scratch.island_parent, r.index_a)] = 1;
    }
  }
  bool woke = false;
  for (uint32_t i = 0; i < n; ++i) {
    BodyInfo& info = state.infos[i];
    if (!is_simulated(info) || info.kind != BodyKind::kDynamic || info.awake != 0) continue;
    if (scratch.island_flag[find_root(scratch.island_parent, i)] == 0) continue;
    wake_body(state, i);
    woke = true;
  }
  if (!woke) return;
  // Contacts carried over while both sides slept have no geometry yet.
  for (uint32_t k = 0; k < state.contacts.size(); ++k) {
    const ContactRecord& r = state.contacts[k];
    if (scratch.geometry[k].valid != 0 || !live_record(state, r)) continue;
    if (is_active(state.infos[r.index_a]) || is_active(state.infos[r.index_b])) {
      refresh_contact(state, scratch, k);
    }
  }
}

void update_sleep(WorldState& state, WorldScratch& scratch) {
  const WorldConfig& config = state.config;
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  // The bodies this tick solved, in ascending index (solver body 0 is the
  // shared immovable one): every body awake now was among them (the stages
  // after the solve wake nobody), so a level's thousands of static bodies
  // are never scanned here.
  const std::vector<uint32_t>& solved = scratch.solver_body_ids;
  uint32_t awake = 0;
  for (size_t s = 1; s < solved.size(); ++s) {
    if (is_active(state.infos[solved[s]])) ++awake;
  }
  scratch.stats.awake_bodies = awake;
  if (!config.enable_sleep || awake == 0) return;

  build_islands(state, scratch);
  scratch.island_sleep_time.assign(n, config.time_to_sleep_s);
  auto& parent = scratch.island_parent;
  auto& min_time = scratch.island_sleep_time;
  for (size_t s = 1; s < solved.size(); ++s) {
    const uint32_t i = solved[s];
    const BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    float t = state.sims[i].sleep_time;
    uint32_t root = info.kind == BodyKind::kDynamic ? find_root(parent, i) : i;
    if (t < min_time[root]) min_time[root] = t;
  }
  for (const ContactRecord& r : state.contacts) {
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) continue;
    if (is_moving_kinematic(state, r.index_a) &&
        state.infos[r.index_b].kind == BodyKind::kDynamic) {
      min_time[find_root(parent, r.index_b)] = 0.0f;
    }
    if (is_moving_kinematic(state, r.index_b) &&
        state.infos[r.index_a].kind == BodyKind::kDynamic) {
      min_time[find_root(parent, r.index_a)] = 0.0f;
    }
  }
  for (size_t s = 1; s < solved.size(); ++s) {
    const uint32_t i = solved[s];
    BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    uint32_t root = info.kind == BodyKind::kDynamic ? find_root(parent, i) : i;
    if (min_time[root] < config.time_to_sleep_s) continue;
    info.awake = 0;
    state.sims[i].linear_velocity = {};
    state.sims[i].angular_velocity = {};
  }
}

}  // namespace rwd::sim::d3
