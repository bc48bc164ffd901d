// SPDX-License-Identifier: MIT
// The jointed scenes of rewind/scenes/joint_scenes.h on Rewind and Bullet,
// one engine at a time: one iteration is one tick, a finished scene is
// rebuilt outside the timing, so each scene is measured over its whole run
// (the chain and bridge settling, the grid falling). Sleeping is off in
// both engines. rewind-joint-bench runs the same scenes in turns and adds
// the joint errors.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "joint_engines.h"

namespace {

using rwd::bench::JointEngine;

void run_joint_scene(benchmark::State& state, JointEngine& engine, const std::string& name) {
  const rwd::scenes::JointScene scene = rwd::scenes::make_joint_scene(name);
  int tick = 0;
  auto rebuild = [&] {
    std::string error;
    if (!engine.build(scene, error)) state.SkipWithError(error.c_str());
    tick = 0;
  };
  rebuild();
  for (auto _ : state) {
    if (tick == scene.ticks) {
      state.PauseTiming();
      rebuild();
      state.ResumeTiming();
    }
    engine.step();
    ++tick;
  }
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
  state.counters["joints"] = static_cast<double>(scene.joints.size());
}

void register_all() {
  for (const std::string& name : rwd::scenes::joint_scene_names()) {
    const int ticks = rwd::scenes::make_joint_scene(name).ticks;
    benchmark::RegisterBenchmark(("BM_Joints_" + name + "_Rewind").c_str(),
                                 [name](benchmark::State& state) {
                                   auto engine = rwd::bench::make_rewind_joint_engine(4);
                                   run_joint_scene(state, *engine, name);
                                 })
        ->Iterations(ticks)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Joints_" + name + "_Bullet").c_str(),
                                 [name](benchmark::State& state) {
                                   auto engine = rwd::bench::make_bullet_joint_engine(10);
                                   run_joint_scene(state, *engine, name);
                                 })
        ->Iterations(ticks)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
