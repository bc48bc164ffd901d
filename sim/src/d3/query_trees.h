// SPDX-License-Identifier: MIT
#pragma once
// The trees the world's queries walk: one over the static bodies (rebuilt
// after an edit) and one over every other simulated body (rebuilt the first
// time a query needs it after a step), both on exact shape bounds. They are
// working memory: queries test each candidate exactly and sort what they
// report, so a tree's shape never shows in a result.
#include "d3/world_scratch.h"
#include "rewind/sim/query.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Makes scratch.query_static and scratch.query_movable current.
void refresh_query_trees(const WorldState& state, WorldScratch& scratch);

/// Whether a query with `filter` may report body i (simulated, on a layer
/// the filter takes, a sensor only when the filter asks for sensors).
bool query_accepts(const WorldState& state, const QueryFilter& filter, uint32_t i);

}  // namespace rwd::sim::d3
