// SPDX-License-Identifier: MIT
#pragma once
// The stages of World3D::step(), one file each, in the order they run:
//   find_pairs.cpp     find_pairs: candidate pairs from the broadphase
//   narrowphase.cpp    update_contacts: manifolds, feature-id warm starting,
//                      sleeping contacts carried over
//   island_sleep.cpp   wake_touched_islands: sleeping islands touched by an
//                      awake body wake before solving
//   contact_solver.cpp solve: TGS-Soft substeps, restitution, write back
//                      (support_order.cpp orders its push-out,
//                      angular_momentum.cpp the gyroscopic term)
//   continuous.cpp     continuous_collision: sweeps of fast bodies
//   contact_events.cpp mark_pushed_contacts, build_events: enter/stay/exit
//                      from old vs new cache; fill_event_details
//   island_sleep.cpp   update_sleep: islands at rest fall asleep
// Scheduled queries (scheduled_queries.cpp) run before the first stage and
// after the last; they read the state and never write it.
#include "d3/world_scratch.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Fills scratch.pairs with candidate pairs sorted by (a, b), without the
/// pairs an intact joint keeps from colliding. The first stage of a step:
/// it starts the step's body frames (body_axes).
void find_pairs(const WorldState& state, WorldScratch& scratch);
/// The world was edited (create, destroy, teleport, enable, restore): the
/// broadphase rebuilds its trees before their next use.
inline void mark_world_edited(WorldScratch& scratch) {
  scratch.broadphase.mark_edited();
  ++scratch.edit_serial;
  ++scratch.joint_serial;
}
/// Joints were created, destroyed or broken: the pairs they keep from
/// colliding are found again before the next step's pairs are kept.
inline void mark_joints_edited(WorldScratch& scratch) {
  ++scratch.joint_serial;
}

/// Readies the broadphase's query side for the poses in `state`.
inline void prepare_queries(const WorldState& state, WorldScratch& scratch) {
  scratch.broadphase.prepare_queries(state, scratch.step_serial);
}

/// Replaces state.contacts with this step's cache (old one kept in
/// scratch.other_contacts) and fills scratch.geometry.
void update_contacts(WorldState& state, WorldScratch& scratch);
/// Computes the manifold of record `index` (used when a sleeping contact
/// wakes up) and refreshes its points, keeping impulses of matching ids.
void refresh_contact(WorldState& state, WorldScratch& scratch, uint32_t index);

/// Wakes every sleeping island that touches an awake body.
void wake_touched_islands(WorldState& state, WorldScratch& scratch);
/// Sweeps the continuous bodies that moved this tick from where they
/// started and moves any that would cross a shape back to the first touch
/// (continuous.cpp). Runs after solve, which leaves each body's motion in
/// scratch.solver_bodies.
void continuous_collision(WorldState& state, WorldScratch& scratch);

/// Takes rolling out of touching contacts whose materials resist it, after
/// the solve (rolling_resistance.cpp).
void apply_rolling_resistance(WorldState& state, WorldScratch& scratch);

/// Advances sleep timers and puts islands at rest to sleep.
void update_sleep(WorldState& state, WorldScratch& scratch);
/// Wakes one body (no island propagation: the next step does that).
void wake_body(WorldState& state, uint32_t index);
/// Wakes every live body with a touching contact with `id`.
void wake_touching(WorldState& state, BodyId id);

/// After the solve: a solid pair not yet touching (its points beyond the
/// speculative distance) that the solver pushed apart this tick touches
/// from now on (until the next narrowphase decides again); its records are
/// listed in scratch.pushed_records, in record order.
void mark_pushed_contacts(WorldState& state, WorldScratch& scratch);
/// Fills scratch.events from scratch.other_contacts (last step) and
/// state.contacts (this step), and scratch.event_records with each event's
/// record in state.contacts (kNoRecord for exits).
void build_events(const WorldState& state, WorldScratch& scratch);
/// Fills the point, normal, depth and impulse of the enter and stay events
/// once the solve has stored the tick's impulses.
void fill_event_details(const WorldState& state, WorldScratch& scratch);

/// Levels the solver bodies by contacts from the immovable ones and fills
/// scratch.push_order and each constraint's push_fixed (support_order.cpp).
void order_push_out(WorldScratch& scratch);

/// Runs the TGS-Soft solver over all awake bodies for one tick.
void solve(WorldState& state, WorldScratch& scratch);

}  // namespace rwd::sim::d3
