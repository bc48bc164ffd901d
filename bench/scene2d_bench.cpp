// SPDX-License-Identifier: MIT
// Rewind's 2D lane and Box2D 2.4 stepping the same 2D scenes (bench/
// scene2d.h), every body awake in both. One iteration is one tick after the
// scene's warm-up; a scene that reaches its last timed tick is rebuilt
// outside the timing.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "box2d_engine.h"
#include "rewind2d_engine.h"
#include "scene2d.h"

namespace {

using rwd::bench::Engine2D;

void run(benchmark::State& state, Engine2D& engine, const char* name) {
  rwd::bench::Scene2D scene;
  rwd::bench::make_scene2d(name, static_cast<int>(state.range(0)), scene);
  int tick = 0;
  auto rebuild = [&] {
    std::string error;
    if (!engine.build(scene, error)) state.SkipWithError(error.c_str());
    for (int i = 0; i < scene.warmup_ticks; ++i) engine.step();
    tick = 0;
  };
  rebuild();
  for (auto _ : state) {
    if (tick == scene.timed_ticks) {
      state.PauseTiming();
      rebuild();
      state.ResumeTiming();
    }
    engine.step();
    ++tick;
  }
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
}

// range(0) is the scene's size; the rest are the engine's settings.
void BM_Rewind(benchmark::State& state, const char* name) {
  rwd::bench::Rewind2DEngine engine(static_cast<int>(state.range(1)), 1);
  run(state, engine, name);
}
void BM_Box2D(benchmark::State& state, const char* name) {
  rwd::bench::Box2DEngine engine(static_cast<int>(state.range(1)),
                                 static_cast<int>(state.range(2)));
  run(state, engine, name);
}

// Sizes: the large pyramid's base, the number of base-10 pyramids, the
// tumbler's boxes, the joint grid's side. Rewind: substeps (relax 1); Box2D: velocity and position
// iterations. 300 timed ticks per scene.
BENCHMARK_CAPTURE(BM_Rewind, large_pyramid, "large_pyramid")
    ->Args({100, 4})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Box2D, large_pyramid, "large_pyramid")
    ->Args({100, 8, 3})
    ->Args({100, 4, 2})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rewind, pyramids, "pyramids")
    ->Args({20, 4})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Box2D, pyramids, "pyramids")
    ->Args({20, 8, 3})
    ->Args({20, 4, 2})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rewind, tumbler, "tumbler")
    ->Args({800, 4})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Box2D, tumbler, "tumbler")
    ->Args({800, 8, 3})
    ->Args({800, 4, 2})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Rewind, joint_grid, "joint_grid")
    ->Args({100, 4})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Box2D, joint_grid, "joint_grid")
    ->Args({100, 8, 3})
    ->Args({100, 4, 2})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
