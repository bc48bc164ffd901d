// SPDX-License-Identifier: MIT
// Islands and sleep. An island is a set of dynamic bodies connected by
// touching solid contacts and acting joints (static and kinematic bodies do
// not connect islands, or a whole level would be one island). Islands are found with a
// union-find over the contact cache in index order; roots are always the
// lowest index, so the result is a pure function of the state. Persistent
// islands (Box2D v3 style) were rejected for the first cut: recomputing is
// simpler to keep exact under rollback, and costs one pass over the contacts.
#include "d3/body_storage.h"
#include "d3/contact_cache_steady.h"
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

// A joint ties its bodies' islands while it acts and both are dynamic.
bool joint_links_island(const WorldState& state, const JointRecord& j) {
  return j.index_a != kJointWorld && joint_acts(state, j) &&
         state.infos[j.index_a].kind == BodyKind::kDynamic &&
         state.infos[j.index_b].kind == BodyKind::kDynamic;
}

void build_islands(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.island_parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) scratch.island_parent[i] = i;
  for (const ContactRecord& r : state.contacts) {
    if (links_island(state, r)) unite(scratch.island_parent, r.index_a, r.index_b);
  }
  if (state.live_joints == 0) return;
  for (const JointRecord& j : state.joints) {
    if (joint_links_island(state, j)) unite(scratch.island_parent, j.index_a, j.index_b);
  }
}

// The records this step solved: prepare made a constraint of every
// touching solid pair with an awake dynamic body (and of no resting pair).
template <class Fn>
void for_each_solved_record(const WorldState& state, const WorldScratch& scratch, Fn fn) {
  for (const ContactConstraint& c : scratch.constraints) fn(state.contacts[c.record]);
}

// Whether no solved record joins an awake dynamic body to a sleeping one,
// and no joint is there to: then every island with an awake body holds
// awake bodies only, and the solved records alone find those islands, the
// same ones (roots are the lowest index of a set, whatever the order of
// the unions) as a pass over the whole cache, which a level of sleeping
// bodies makes long.
bool awake_islands_closed(const WorldState& state, const WorldScratch& scratch) {
  if (state.live_joints != 0) return false;
  bool closed = true;
  for_each_solved_record(state, scratch, [&](const ContactRecord& r) {
    if (!links_island(state, r)) return;
    if (is_active(state.infos[r.index_a]) != is_active(state.infos[r.index_b])) closed = false;
  });
  return closed;
}

// build_islands over the solved records only (awake_islands_closed).
void build_awake_islands(const WorldState& state, WorldScratch& scratch) {
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.island_parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) scratch.island_parent[i] = i;
  for_each_solved_record(state, scratch, [&](const ContactRecord& r) {
    if (links_island(state, r)) unite(scratch.island_parent, r.index_a, r.index_b);
  });
}

// Whether an acting joint drives its bodies on its own: a motor with a
// non-zero target speed, or a grab whose anchor is off its target.
bool joint_drives(const WorldState& state, const JointRecord& j) {
  if (!joint_acts(state, j)) return false;
  if ((j.flags & kJointMotor) != 0 && (j.motor_speed != 0.0f || !(j.motor_velocity == Vec3{}))) {
    return true;
  }
  if (j.type != JointType::kGrab) return false;
  const BodySim& b = state.sims[j.index_b];
  const Vec3 anchor = b.position + rotate(b.rotation, j.local_anchor_b);
  const float slop = state.config.linear_slop_m;
  return length_squared(anchor - j.target) > slop * slop;
}

// The pair of bodies a joint acts between, as contact-like (a, b), or
// false for joints that act on one body alone or not at all.
bool joint_pair(const WorldState& state, const JointRecord& j, uint32_t& a, uint32_t& b) {
  if (j.index_a == kJointWorld || !joint_acts(state, j)) return false;
  a = j.index_a;
  b = j.index_b;
  return true;
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
  state.at_rest = false;
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
  // What hangs on it by a joint must move too.
  for (size_t k = 0; state.live_joints != 0 && k < state.joints.size(); ++k) {
    const JointRecord& j = state.joints[k];
    if (j.alive == 0) continue;
    if (j.index_b == id.index && j.generation_b == id.generation && j.index_a != kJointWorld) {
      wake_body(state, j.index_a);
    } else if (j.index_a == id.index && j.generation_a == id.generation) {
      wake_body(state, j.index_b);
    }
  }
}

namespace {

// Whether one of a and b is an awake mover and the other a sleeping
// dynamic body.
bool wakes_other(const BodyInfo& a, const BodyInfo& b) {
  const bool a_sleeps = a.kind == BodyKind::kDynamic && a.awake == 0;
  const bool b_sleeps = b.kind == BodyKind::kDynamic && b.awake == 0;
  return (a_sleeps && is_active(b)) || (b_sleeps && is_active(a));
}

}  // namespace

void wake_touched_islands(WorldState& state, WorldScratch& scratch) {
  // Nothing awake (the broadphase's list of awake movers is empty) wakes
  // nothing.
  if (scratch.active.empty()) return;
  // Cheap test first: does any touching contact or joint join an awake
  // mover and a sleeping dynamic body? Usually not, and then no island
  // work is done.
  // Only a record with an awake body can, and update_contacts evaluated
  // every one of those this step (the records it carried join two resting
  // bodies).
  bool needed = false;
  for (const uint32_t k : scratch.evaluated_records) {
    const ContactRecord& r = state.contacts[k];
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) continue;
    if (wakes_other(state.infos[r.index_a], state.infos[r.index_b])) {
      needed = true;
      break;
    }
  }
  for (size_t k = 0; !needed && state.live_joints != 0 && k < state.joints.size(); ++k) {
    uint32_t a = 0;
    uint32_t b = 0;
    if (joint_pair(state, state.joints[k], a, b)) {
      needed = wakes_other(state.infos[a], state.infos[b]);
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
  auto flag_driven = [&](uint32_t a, uint32_t b) {
    if (is_moving_kinematic(state, a) && state.infos[b].kind == BodyKind::kDynamic) {
      scratch.island_flag[find_root(scratch.island_parent, b)] = 1;
    }
    if (is_moving_kinematic(state, b) && state.infos[a].kind == BodyKind::kDynamic) {
      scratch.island_flag[find_root(scratch.island_parent, a)] = 1;
    }
  };
  for (const ContactRecord& r : state.contacts) {
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) continue;
    flag_driven(r.index_a, r.index_b);
  }
  for (size_t k = 0; state.live_joints != 0 && k < state.joints.size(); ++k) {
    uint32_t a = 0;
    uint32_t b = 0;
    if (joint_pair(state, state.joints[k], a, b)) flag_driven(a, b);
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
  scratch.woke_bodies = true;
  // The refresh changes records the steady path left out of its view: the
  // events then compare the whole caches.
  unfold_steady(state, scratch);
  // Contacts carried over while both sides slept have no geometry yet.
  for (uint32_t k = 0; k < state.contacts.size(); ++k) {
    const ContactRecord& r = state.contacts[k];
    if (scratch.geometry[k].valid != 0 || !live_record(state, r)) continue;
    if (is_active(state.infos[r.index_a]) || is_active(state.infos[r.index_b])) {
      refresh_contact(state, scratch, k);
      scratch.refreshed_records.push_back(k);
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

  const bool closed = awake_islands_closed(state, scratch);
  if (closed) {
    build_awake_islands(state, scratch);
  } else {
    build_islands(state, scratch);
  }
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
  auto hold_driven = [&](uint32_t a, uint32_t b) {
    if (is_moving_kinematic(state, a) && state.infos[b].kind == BodyKind::kDynamic) {
      min_time[find_root(parent, b)] = 0.0f;
    }
    if (is_moving_kinematic(state, b) && state.infos[a].kind == BodyKind::kDynamic) {
      min_time[find_root(parent, a)] = 0.0f;
    }
  };
  // A moving kinematic body holds the island of a dynamic one it touches;
  // with the awake islands closed, only a solved record can join one to an
  // awake body.
  const auto hold = [&](const ContactRecord& r) {
    if (r.touching == 0 || r.sensor != 0 || !live_record(state, r)) return;
    hold_driven(r.index_a, r.index_b);
  };
  if (closed) {
    for_each_solved_record(state, scratch, hold);
  } else {
    for (const ContactRecord& r : state.contacts) hold(r);
  }
  for (size_t k = 0; state.live_joints != 0 && k < state.joints.size(); ++k) {
    const JointRecord& j = state.joints[k];
    uint32_t a = 0;
    uint32_t b = 0;
    if (joint_pair(state, j, a, b)) hold_driven(a, b);
    // A motor with somewhere to go, or a grab short of its target, keeps
    // its bodies awake however slowly they move.
    if (joint_drives(state, j)) {
      if (state.infos[j.index_b].kind == BodyKind::kDynamic)
        min_time[find_root(parent, j.index_b)] = 0.0f;
      if (j.index_a != kJointWorld && state.infos[j.index_a].kind == BodyKind::kDynamic) {
        min_time[find_root(parent, j.index_a)] = 0.0f;
      }
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
