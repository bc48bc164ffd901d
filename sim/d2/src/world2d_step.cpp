// SPDX-License-Identifier: MIT
#include <algorithm>

#include "pipeline2d.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

// A body whose centre left the bounds is stopped where it crossed and
// disabled, so positions never grow toward the integer range's edge.
void enforce_bounds(World2DState& state) {
  const V2 lower = v_from(state.config.bounds_lower);
  const V2 upper = v_from(state.config.bounds_upper);
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled) ||
        body.kind == BodyKind2D::kStatic) {
      continue;
    }
    const V2 c = body.center;
    if (c.x >= lower.x && c.x <= upper.x && c.y >= lower.y && c.y <= upper.y) continue;
    body.center = {wclamp(c.x, lower.x, upper.x), wclamp(c.y, lower.y, upper.y)};
    body.flags &= static_cast<uint8_t>(~kBodyEnabled);
    body.velocity = {};
    body.angular_velocity = 0;
    drop_contacts_of(state, i);
  }
}

}  // namespace

void World2D::step() {
  stats_ = {};
  const bool had_pending = !state_.pending_exits.empty();
  begin_events(state_, scratch_->events);
  find_pairs(state_, *scratch_);
  stats_.broadphase_pairs = static_cast<uint32_t>(scratch_->pairs.size());
  update_contacts(state_, *scratch_);
  if (had_pending) sort_events(scratch_->events);
  wake_touched(state_, *scratch_);
  solve_step(state_, *scratch_, stats_);
  solve_continuous(state_, *scratch_);
  enforce_bounds(state_);
  update_sleep(state_, *scratch_);
  ++state_.step_count;
}

std::span<const ContactEvent2D> World2D::events() const {
  return scratch_->events;
}

}  // namespace rwd::sim2d
