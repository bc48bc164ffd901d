// SPDX-License-Identifier: MIT
#pragma once
// The stages of one 2D step, in the order World2D::step() runs them.
#include "rewind/sim2d/world2d.h"
#include "step_scratch2d.h"

namespace rwd::sim2d::detail {

/// A bounding-box tree over the bodies' bounds (grown by half the
/// speculative distance), walked against itself: scratch.pairs gets every
/// overlapping pair with a moving body whose layers agree, sorted by (a, b).
void find_pairs(const World2DState& state, StepScratch2D& scratch);

/// Rebuilds state.contacts from scratch.pairs: a manifold per pair, each
/// point keeping the impulses of the point with the same feature id last
/// step (warm starting). Pairs without points are dropped.
void update_contacts(World2DState& state, StepScratch2D& scratch);

/// Appends the enter, stay and exit events between the touching contacts
/// of state.contacts (last step) and `next` (this step) to `events`.
void collect_events(const World2DState& state, const std::vector<ContactRecord2D>& next,
                    std::vector<ContactEvent2D>& events);

/// Removes every contact of body `index`; the touching ones become pending
/// exits, reported by the next step.
void drop_contacts_of(World2DState& state, uint32_t index);
/// Removes the contacts of every body whose turn_of[body] is below `turns`
/// (UINT32_MAX for the others) exactly as drop_contacts_of for each of them
/// in turn order would, in one pass.
void drop_contacts_of(World2DState& state, const std::vector<uint32_t>& turn_of, uint32_t turns);

/// This step's events: the pending exits, then the contacts' enter, stay
/// and exit events, ordered by (a, b); clears the pending exits.
void begin_events(World2DState& state, std::vector<ContactEvent2D>& events);

/// Orders events by (a, b), exits first where a pair ended and began again.
void sort_events(std::vector<ContactEvent2D>& events);

/// Wakes every sleeping body touched by or joined to a moving one, with
/// its whole island (sleep2d.cpp).
void wake_touched(World2DState& state, StepScratch2D& scratch);

/// Counts each awake body's slow time and puts islands that have all been
/// slow for time_to_sleep to sleep.
void update_sleep(World2DState& state, StepScratch2D& scratch);

/// Moves each continuous body that would have crossed a static or
/// kinematic shape this step back to its first touch (continuous2d.cpp).
/// Needs the step's translations, scratch.bodies[i].dp.
void solve_continuous(World2DState& state, const StepScratch2D& scratch);

/// The soft-step solve of the contacts: substeps of integrate velocities,
/// warm start, solve, integrate positions and relax, then restitution;
/// impulses are stored back into state.contacts for the next step.
void solve_step(World2DState& state, StepScratch2D& scratch, StepStats2D& stats);

}  // namespace rwd::sim2d::detail
