// SPDX-License-Identifier: MIT
#pragma once
// The steady contact cache (WorldScratch::steady_*): a step in which no body
// woke and nothing was edited collides only against the records the last
// step evaluated, and writes its own back where those were. The full merge
// (narrowphase.cpp) would carry every other record as it is, since both its
// bodies rested then and still do; so the result is the same cache, bit for
// bit, at a cost that follows the awake bodies instead of the whole cache.
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

/// Whether this step takes the steady path: at most a quarter of the cache
/// was evaluated last step, the cache is the one the last narrowphase left
/// (no edit of the world since), and every body awake now was awake then,
/// so every record it carried still joins two resting bodies.
bool steady_cache_usable(const WorldState& state, const WorldScratch& scratch);
/// Copies the records the last step evaluated into scratch.other_contacts
/// (their positions in scratch.steady_view): the plan's "last step's cache".
void steady_old_records(const WorldState& state, WorldScratch& scratch);
/// Puts this step's records of those pairs (scratch.steady_new) into the
/// cache: where the old ones were when the keys match one for one
/// (contacts_in_place), else merged with the carried records into a new
/// cache, with the whole old one in other_contacts as a full step leaves it.
/// evaluated_records then index state.contacts.
void place_steady_records(WorldState& state, WorldScratch& scratch);
/// Remembers what the next step's steady path needs.
void remember_steady(WorldScratch& scratch);
/// Turns an in-place step back into the full form (other_contacts = last
/// step's whole cache), for a stage about to change records outside
/// steady_view (the wake refreshing the records of bodies it woke).
void unfold_steady(const WorldState& state, WorldScratch& scratch);

}  // namespace rwd::sim::d3
