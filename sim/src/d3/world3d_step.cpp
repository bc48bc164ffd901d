// SPDX-License-Identifier: MIT
// World3D's step: the order of the pipeline's stages (d3/pipeline.h), the
// optional timing of each, and what the last step left to read (events,
// body events, stats).
#include <chrono>

#include "d3/pipeline.h"
#include "d3/world_scratch.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// The stages of a step, in order (d3/pipeline.h), once for the plain step
// and the timed one alike; `lap` runs after each group of them.
enum class Lap { kBroadphase, kNarrowphase, kWake, kSolve, kEvents, kSleep };
constexpr int kLaps = 6;

template <typename LapFn>
void run_stages(WorldState& state, WorldScratch& s, LapFn&& lap) {
  d3::find_pairs(state, s);
  lap(Lap::kBroadphase);
  d3::update_contacts(state, s);
  lap(Lap::kNarrowphase);
  d3::wake_touched_islands(state, s);
  lap(Lap::kWake);
  d3::solve(state, s);
  d3::apply_rolling_resistance(state, s);
  d3::continuous_collision(state, s);
  lap(Lap::kSolve);
  d3::mark_pushed_contacts(state, s);
  d3::build_events(state, s);
  d3::fill_event_details(state, s);
  lap(Lap::kEvents);
  d3::update_sleep(state, s);
  lap(Lap::kSleep);
}

}  // namespace

void World3D::step() {
  WorldScratch& s = *scratch_;
  s.body_events.clear();
  s.broken_joints.clear();
  // Scheduled queries bracket the stages: they read the state, never write
  // it, so a world with them steps exactly as one without.
  clear_step_queries();
  const bool queries = !state_.queries.empty();
  if (queries) run_scheduled_queries(QueryPhase::kPrePhysics);
  if (state_.at_rest) {
    // Nothing awake, nothing changed since a step that found it so: the
    // stages would change nothing and report nothing (a resting pair
    // reports no stay), so the step is its count. This is what a world
    // of sleeping bodies costs per step.
    s.stats = s.rest_stats;
  } else {
    s.stats = StepStats{};
    if (!s.stage_timing) {
      run_stages(state_, s, [](Lap) {});
    } else {
      timed_stages();
    }
    state_.at_rest = s.active.empty() && s.contacts_unchanged && s.events.empty() &&
                     s.body_events.empty() && s.broken_joints.empty();
    if (state_.at_rest) {
      s.rest_stats = s.stats;
      s.rest_stats.times = {};
    }
  }
  ++state_.step_count;
  if (queries) {
    run_scheduled_queries(QueryPhase::kPostPhysics);
    finish_scheduled_queries();
  }
}

void World3D::timed_stages() {
  // The same stages, each group timed (the times are diagnostics, never state).
  using Clock = std::chrono::steady_clock;
  double us[kLaps] = {};
  Clock::time_point last = Clock::now();
  run_stages(state_, *scratch_, [&](Lap lap) {
    const Clock::time_point now = Clock::now();
    us[static_cast<int>(lap)] = std::chrono::duration<double, std::micro>(now - last).count();
    last = now;
  });
  StepStats::StageTimes& t = scratch_->stats.times;
  t.broadphase_us = us[static_cast<int>(Lap::kBroadphase)];
  t.narrowphase_us = us[static_cast<int>(Lap::kNarrowphase)];
  t.events_us = us[static_cast<int>(Lap::kWake)] + us[static_cast<int>(Lap::kEvents)];
  t.solver_us = us[static_cast<int>(Lap::kSolve)];
  t.sleep_us = us[static_cast<int>(Lap::kSleep)];
}

void World3D::set_stage_timing(bool on) {
  scratch_->stage_timing = on;
}

void World3D::set_thread_pool(ThreadPool* pool) {
  scratch_->pool = pool;
}

std::span<const ContactEvent> World3D::events() const {
  return scratch_->events;
}
std::span<const BodyEvent> World3D::body_events() const {
  return scratch_->body_events;
}
const StepStats& World3D::stats() const {
  return scratch_->stats;
}
const WorldConfig& World3D::config() const {
  return state_.config;
}
uint64_t World3D::step_count() const {
  return state_.step_count;
}

}  // namespace rwd::sim
