// SPDX-License-Identifier: MIT
// What one tick of the sample match costs, and what rollback adds on top:
// save, restore, checksum, and re-simulating a window of ticks.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <vector>

#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"
#include "rewind/net/rollback_session.h"
#include "rewind/sim/world3d.h"

namespace {

using rwd::PlayerInput;
using rwd::game::Simulation;

std::vector<PlayerInput> inputs_for(uint32_t players, rwd::Tick tick) {
  std::vector<PlayerInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    inputs[p] = rwd::stick_input(static_cast<int16_t>(((tick / 30 + p) % 3 - 1) * 1000),
                                 static_cast<int16_t>(((tick / 45 + 2 * p) % 3 - 1) * 1000));
  }
  return inputs;
}

std::unique_ptr<Simulation> warmed_up(uint32_t players, int ticks) {
  auto sim = std::move(*Simulation::create("crates", {players, 1}));
  for (int t = 0; t < ticks; ++t) {
    if (!sim->step(inputs_for(players, t)).ok()) std::abort();  // the built-in rules never fail
  }
  return sim;
}

void BM_CratesTick(benchmark::State& state) {
  const auto players = static_cast<uint32_t>(state.range(0));
  auto sim = warmed_up(players, 120);
  for (auto _ : state) {
    if (!sim->step(inputs_for(players, sim->tick())).ok()) state.SkipWithError("the rules failed");
  }
  // The tower's crates fall asleep: most of the world is at rest, as in a
  // real match, and the step's cost is mostly its fixed part.
  const auto* world = rwd::game::world_of<rwd::sim::World3D>(sim->lane());
  state.counters["bodies"] = world->body_count();
  state.counters["awake"] = world->stats().awake_bodies;
  state.counters["contact_points"] = world->stats().contact_points;
}
BENCHMARK(BM_CratesTick)->Arg(2)->Arg(8)->Arg(32);

// A whole joust match (raycast cars, jointed riders thrown on a hit, a
// wrecking ball on a chain) from its start: ten seconds of four players
// steering and charging, the same inputs every run. Time per iteration is
// 600 ticks; the "ticks" counter is the rate, ticks per second.
void BM_JoustMatch(benchmark::State& state) {
  constexpr uint32_t kPlayers = 4;
  constexpr int kTicks = 600;
  for (auto _ : state) {
    auto sim = std::move(*Simulation::create("joust", {kPlayers, 1}));
    for (int t = 0; t < kTicks; ++t) {
      if (!sim->step(inputs_for(kPlayers, t)).ok()) state.SkipWithError("the rules failed");
    }
    benchmark::DoNotOptimize(sim->checksum());
  }
  state.counters["ticks"] =
      benchmark::Counter(kTicks, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_JoustMatch)->Unit(benchmark::kMillisecond);

void BM_SaveRestore(benchmark::State& state) {
  auto sim = warmed_up(8, 120);
  rwd::game::SimSnapshot snapshot;
  sim->save(snapshot);
  for (auto _ : state) {
    sim->save(snapshot);
    sim->restore(snapshot);
  }
}
BENCHMARK(BM_SaveRestore);

void BM_Checksum(benchmark::State& state) {
  auto sim = warmed_up(8, 120);
  for (auto _ : state) benchmark::DoNotOptimize(sim->checksum());
}
BENCHMARK(BM_Checksum);

// A misprediction 8 ticks back: restore and re-simulate 8 ticks.
void BM_Rollback8(benchmark::State& state) {
  rwd::net::RollbackSession session(warmed_up(8, 0), {});
  for (int t = 0; t < 120; ++t) session.advance();
  uint32_t flip = 0;
  for (auto _ : state) {
    const rwd::Tick target = session.current_tick() - 8;
    (void)session.add_final_input(
        0, target, rwd::stick_input(static_cast<int16_t>(++flip % 2 ? 1000 : -1000), 0));
    session.synchronize();
    session.finalize_through(target);
    session.advance();
  }
  state.counters["rollbacks"] = static_cast<double>(session.stats().rollbacks);
}
BENCHMARK(BM_Rollback8);

}  // namespace
