// SPDX-License-Identifier: MIT
// Rewind and Bullet stepping the same catalogue scenes in the same process,
// and Jolt Physics beside them in the small-world, fixed-cost and asleep
// families when the build has it (-DREWIND_JOLT_DIR=..., bench/jolt_engine).
// Each benchmark runs whole scenes (one iteration = one tick; a finished
// scene is rebuilt outside the timing), so a pile is measured over its fall
// and its settling alike. Pyramids keep every body awake (the solver's cost,
// not the sleeping system's); piles run with sleeping on, as a game would.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "bullet_engine.h"
#ifdef REWIND_HAVE_JOLT
#include "jolt_engine.h"
#endif
#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace {

using rwd::scenes::Engine;

void run_scene_ticks(benchmark::State& state, Engine& engine, const char* name, int size) {
  std::unique_ptr<rwd::scenes::Scene> scene;
  rwd::Tick tick = 0;
  auto rebuild = [&] {
    scene = rwd::scenes::make_scene(name, size);
    std::string error;
    engine.reset(scene->world(), scene->body_capacity());
    if (!scene->build(engine, error)) state.SkipWithError(error.c_str());
    tick = 0;
  };
  rebuild();
  for (auto _ : state) {
    if (tick == scene->ticks()) {
      state.PauseTiming();
      rebuild();
      state.ResumeTiming();
    }
    scene->before_step(tick, engine);
    engine.step();
    scene->after_step(tick, engine);
    ++tick;
  }
  state.counters["bodies"] = scene->body_capacity();
  state.counters["awake"] = engine.awake_count();
}
void run_scene_ticks(benchmark::State& state, Engine& engine, const char* name) {
  run_scene_ticks(state, engine, name, static_cast<int>(state.range(0)));
}

void BM_PyramidRewind(benchmark::State& state) {
  rwd::sim::WorldConfig config;
  config.enable_sleep = false;
  rwd::scenes::RewindEngine engine(config);
  run_scene_ticks(state, engine, "pyramid");
}
void BM_PyramidBullet(benchmark::State& state) {
  rwd::bench::BulletSettings settings;
  settings.sleep = false;
  rwd::bench::BulletEngine engine(settings);
  run_scene_ticks(state, engine, "pyramid");
}
void BM_PileRewind(benchmark::State& state) {
  rwd::scenes::RewindEngine engine;
  run_scene_ticks(state, engine, "pile");
}
void BM_PileBullet(benchmark::State& state) {
  rwd::bench::BulletEngine engine;
  run_scene_ticks(state, engine, "pile");
}

// Small worlds, where a step's fixed cost is most of it: a box sliding to
// a stop (2 bodies, 121 ticks at size 5), a box sliding down a 30-degree
// slope (2 bodies, 120 ticks), a heavy box on a light one (3 bodies, 600
// ticks), ten boxes created half inside each other (11 bodies, 180 ticks),
// the crates sample match with 8 players (30 bodies, 600 ticks).
// Default settings, sleep on, as a game runs them; a rollback server
// re-simulates worlds like these many times a tick. The scene name is the
// first argument's label.
constexpr const char* kSmallScenes[] = {"slide", "incline_slip", "mass_ratio", "overlap", "crates"};
constexpr int kSmallSizes[] = {5, 30, 100, 10, 8};

void small_scene(benchmark::State& state, Engine& engine) {
  const auto which = static_cast<size_t>(state.range(0));
  state.SetLabel(kSmallScenes[which]);
  run_scene_ticks(state, engine, kSmallScenes[which], kSmallSizes[which]);
}
void BM_SmallRewind(benchmark::State& state) {
  rwd::scenes::RewindEngine engine;
  small_scene(state, engine);
}
void BM_SmallBullet(benchmark::State& state) {
  rwd::bench::BulletEngine engine;
  small_scene(state, engine);
}
BENCHMARK(BM_SmallRewind)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SmallBullet)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);
#ifdef REWIND_HAVE_JOLT
void BM_SmallJolt(benchmark::State& state) {
  rwd::bench::JoltEngine engine;
  small_scene(state, engine);
}
BENCHMARK(BM_SmallJolt)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);
#endif

// A step's fixed cost: what a world pays per step whatever it holds, so
// what a rollback server pays again for each re-simulated tick of a small
// match. Sleep is off (nothing may leave the step's work by sleeping), and
// the bodies: 0, a static floor alone; 1, the floor and a box spinning in
// the air without gravity (a body, no contact); 2, the floor and a box
// resting on it (one four-point manifold); 3, the floor and a sphere
// resting on it (one point). One iteration = one step.
void fixed_cost(benchmark::State& state, Engine& engine) {
  const int which = static_cast<int>(state.range(0));
  constexpr const char* kLabels[] = {"floor", "spinning box", "resting box", "resting sphere"};
  state.SetLabel(kLabels[which]);
  rwd::scenes::WorldSpec world;
  if (which == 1) world.gravity = {};
  engine.reset(world, 2);
  std::string error;
  rwd::scenes::BodySpec floor;
  floor.kind = rwd::sim::BodyKind::kStatic;
  floor.shape = rwd::sim::Shape::make_box({20.0f, 0.5f, 20.0f});
  floor.position = {0.0f, -0.5f, 0.0f};
  rwd::scenes::BodyHandle handle = 0;
  bool ok = engine.add_body(floor, handle, error);
  if (ok && which > 0) {
    rwd::scenes::BodySpec body;
    body.shape = which == 3 ? rwd::sim::Shape::make_sphere(0.5f)
                            : rwd::sim::Shape::make_box({0.5f, 0.5f, 0.5f});
    body.position = {0.0f, which == 1 ? 5.0f : 0.5f, 0.0f};
    if (which == 1) body.angular_velocity = {0.3f, 1.0f, 0.2f};
    ok = engine.add_body(body, handle, error);
  }
  if (!ok) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (int t = 0; t < 60; ++t) engine.step();
  for (auto _ : state) engine.step();
  state.counters["awake"] = engine.awake_count();
}
void BM_FixedCostRewind(benchmark::State& state) {
  rwd::sim::WorldConfig config;
  config.enable_sleep = false;
  rwd::scenes::RewindEngine engine(config);
  fixed_cost(state, engine);
}
void BM_FixedCostBullet(benchmark::State& state) {
  rwd::bench::BulletSettings settings;
  settings.sleep = false;
  rwd::bench::BulletEngine engine(settings);
  fixed_cost(state, engine);
}
BENCHMARK(BM_FixedCostRewind)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FixedCostBullet)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
#ifdef REWIND_HAVE_JOLT
void BM_FixedCostJolt(benchmark::State& state) {
  rwd::bench::JoltSettings settings;
  settings.sleep = false;
  rwd::bench::JoltEngine engine(settings);
  fixed_cost(state, engine);
}
BENCHMARK(BM_FixedCostJolt)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
#endif

// A world at rest: the sleep scene's pyramid of base N stepped until every
// body sleeps (untimed), then the steps of the asleep world: what a world
// costs per step for being there. With spinning:1, a ball is then set
// spinning in place on the ground beside the pyramid (about the vertical,
// which no friction stops): one awake body in a level of sleeping ones,
// what most of a game's ticks look like. One iteration = one step.
void asleep_world(benchmark::State& state, Engine& engine) {
  const int size = static_cast<int>(state.range(0));
  const bool spinning = state.range(1) != 0;
  auto scene = rwd::scenes::make_scene("sleep", size);
  std::string error;
  engine.reset(scene->world(), scene->body_capacity() + 1);
  if (!scene->build(engine, error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (int t = 0; t < 600 && engine.awake_count() > 0; ++t) engine.step();
  if (engine.awake_count() > 0) {
    state.SkipWithError("the pyramid did not fall asleep in 10 s");
    return;
  }
  if (spinning) {
    rwd::scenes::BodySpec ball;
    ball.shape = rwd::sim::Shape::make_sphere(0.5f);
    ball.position = {-5.0f, 0.5f, 5.0f};
    ball.angular_velocity = {0.0f, 5.0f, 0.0f};
    rwd::scenes::BodyHandle handle = 0;
    if (!engine.add_body(ball, handle, error)) {
      state.SkipWithError(error.c_str());
      return;
    }
    for (int t = 0; t < 10; ++t) engine.step();
  }
  for (auto _ : state) engine.step();
  state.counters["bodies"] = scene->body_capacity() + (spinning ? 1 : 0);
  state.counters["awake"] = engine.awake_count();
}
void BM_AsleepRewind(benchmark::State& state) {
  rwd::scenes::RewindEngine engine;
  asleep_world(state, engine);
}
void BM_AsleepBullet(benchmark::State& state) {
  rwd::bench::BulletEngine engine;
  asleep_world(state, engine);
}
BENCHMARK(BM_AsleepRewind)
    ->ArgNames({"base", "spinning"})
    ->ArgsProduct({{10, 30}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AsleepBullet)
    ->ArgNames({"base", "spinning"})
    ->ArgsProduct({{10, 30}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
#ifdef REWIND_HAVE_JOLT
void BM_AsleepJolt(benchmark::State& state) {
  rwd::bench::JoltEngine engine;
  asleep_world(state, engine);
}
BENCHMARK(BM_AsleepJolt)
    ->ArgNames({"base", "spinning"})
    ->ArgsProduct({{10, 30}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
#endif

// One whole scene per benchmark: a pyramid runs 600 ticks, a pile 360.
BENCHMARK(BM_PyramidRewind)
    ->Arg(20)
    ->Arg(30)
    ->Arg(40)
    ->Iterations(600)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PyramidBullet)
    ->Arg(20)
    ->Arg(30)
    ->Arg(40)
    ->Iterations(600)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PileRewind)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(4000)
    ->Arg(8000)
    ->Iterations(360)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PileBullet)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(4000)
    ->Arg(8000)
    ->Iterations(360)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
