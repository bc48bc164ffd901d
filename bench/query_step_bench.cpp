// SPDX-License-Identifier: MIT
// The step families of rewind_query_bench: what a large static level adds
// to a step.
//
// Step families: 200 dynamic boxes and spheres dropped over the level (plus a
// ground slab under it) vs over the ground slab alone; 60 warm-up ticks, then
// 240 timed ticks (the fall into the level and the first landings). Rewind
// uses the default WorldConfig except max_bodies (the default 4096 refuses a
// 10,000-body level). Bullet is set up like bench/bullet_engine.cpp: same
// gravity, one 1/60 s step per tick, btDbvtBroadphase, 10 iterations, its
// default margins, Rewind's friction and restitution combination, damping
// and sleeping thresholds. One difference: setForceUpdateAllAabbs(false),
// what a Bullet game with a large static level sets; by default Bullet
// recomputes every static box's bounds every step and moves each one back
// into the broadphase's dynamic tree.
//
// Built with Jolt (REWIND_JOLT_DIR), the same drop runs on Jolt Physics
// through the scene adapter (jolt_engine.h) with the same materials.
#include "query_step_bench.h"

#include <string>
#include <vector>

#include "query_level.h"
#ifdef REWIND_HAVE_JOLT
#include "jolt_engine.h"
#include "jolt_query_level.h"
#endif

namespace rwd::bench::query_level {
namespace {

// Half boxes, half spheres over the middle 300 m x 300 m, just above the
// level's top, drifting slowly.
std::vector<BodyDef> dropped_bodies() {
  SplitMix64 rng{0xD809ull};
  std::vector<BodyDef> out(kDynamicBodies);
  for (size_t i = 0; i < out.size(); ++i) {
    BodyDef& d = out[i];
    d.shape = i % 2 == 0 ? Shape::make_box({rng.uniform(0.2f, 0.5f), rng.uniform(0.2f, 0.5f),
                                            rng.uniform(0.2f, 0.5f)})
                         : Shape::make_sphere(rng.uniform(0.2f, 0.5f));
    d.position = {rng.uniform(-150.0f, 150.0f), rng.uniform(45.0f, 60.0f),
                  rng.uniform(-150.0f, 150.0f)};
    d.rotation = rng.rotation();
    d.linear_velocity = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 0.0f),
                         rng.uniform(-1.0f, 1.0f)};
    d.angular_velocity = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f),
                          rng.uniform(-1.0f, 1.0f)};
  }
  return out;
}

// A ground slab whose top is y = 0, under the whole level.
constexpr Vec3 kGroundHalf{250.0f, 1.0f, 250.0f};
constexpr Vec3 kGroundCentre{0.0f, -1.0f, 0.0f};

void step_rewind(benchmark::State& state, bool with_level) {
  World3D world(level_config());
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box(kGroundHalf);
  ground.position = kGroundCentre;
  bool ok = world.create_body(ground).ok();
  if (with_level) add_level(world, nullptr, 0.0f);
  for (const BodyDef& def : dropped_bodies()) {
    ok = ok && world.create_body(def).ok();
  }
  if (!ok) {
    state.SkipWithError("a body was refused");
    return;
  }
  for (int t = 0; t < kWarmupTicks; ++t) world.step();
  for (auto _ : state) world.step();
  state.counters["bodies"] = world.body_count();
  state.counters["awake_at_end"] = world.stats().awake_bodies;
  state.counters["contacts_at_end"] = world.stats().contact_points;
}

void step_bullet(benchmark::State& state, bool with_level) {
  BulletWorld world(kLevelBoxes + kDynamicBodies + 1);
  world.add(Shape::make_box(kGroundHalf), BodyKind::kStatic, kGroundCentre, Quat{}, {}, {}, -1);
  if (with_level) {
    World3D rewind(level_config());  // the source of the quantized level poses
    add_level(rewind, &world, 0.0f);
  }
  // The same quantized start state Rewind gets.
  World3D source(level_config());
  for (const BodyDef& def : dropped_bodies()) {
    const auto id = source.create_body(def);
    if (!id.ok()) {
      state.SkipWithError("a body was refused");
      return;
    }
    world.add(*source.shape(*id), BodyKind::kDynamic, source.position(*id), source.rotation(*id),
              source.linear_velocity(*id), source.angular_velocity(*id), -1);
  }
  for (int t = 0; t < kWarmupTicks; ++t) world.step();
  for (auto _ : state) world.step();
  uint32_t awake = 0;
  for (const auto& b : world.bodies) awake += !b->isStaticOrKinematicObject() && b->isActive();
  int contacts = 0;
  for (int m = 0; m < world.dispatcher.getNumManifolds(); ++m) {
    contacts += world.dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
  }
  state.counters["bodies"] = static_cast<double>(world.bodies.size());
  state.counters["awake_at_end"] = awake;
  state.counters["contacts_at_end"] = contacts;
}

#ifdef REWIND_HAVE_JOLT
// The same drop on Jolt through the scene adapter: Jolt's defaults, with
// BulletWorld's materials (friction 0.6, restitution 0, angular damping
// 0.05 /s, density 1000 kg/m^3) and the same quantized start state.
void step_jolt(benchmark::State& state, bool with_level) {
  using rwd::scenes::BodySpec;
  rwd::bench::JoltEngine engine;
  engine.reset(rwd::scenes::WorldSpec{}, kLevelBoxes + kDynamicBodies + 1);
  std::string error;
  rwd::scenes::BodyHandle handle = 0;
  const auto add = [&](const Shape& shape, BodyKind kind, Vec3 position, Quat rotation,
                       Vec3 velocity, Vec3 spin) {
    BodySpec b;
    b.kind = kind;
    b.shape = shape;
    b.position = position;
    b.rotation = rotation;
    b.linear_velocity = velocity;
    b.angular_velocity = spin;
    b.angular_damping = 0.05f;
    return engine.add_body(b, handle, error);
  };
  bool ok = add(Shape::make_box(kGroundHalf), BodyKind::kStatic, kGroundCentre, Quat{}, {}, {});
  if (with_level) {
    World3D rewind(level_config());
    const LevelIds ids = add_level(rewind, nullptr, 0.0f);
    for (const JoltLevelBox& b : kept_boxes(rewind, ids.body_of_box)) {
      ok = ok &&
           add(Shape::make_box(b.half_extents), BodyKind::kStatic, b.position, b.rotation, {}, {});
    }
  }
  World3D source(level_config());
  for (const BodyDef& def : dropped_bodies()) {
    const auto id = source.create_body(def);
    ok = ok && id.ok() &&
         add(*source.shape(*id), BodyKind::kDynamic, source.position(*id), source.rotation(*id),
             source.linear_velocity(*id), source.angular_velocity(*id));
  }
  if (!ok) {
    state.SkipWithError("a body was refused");
    return;
  }
  for (int t = 0; t < kWarmupTicks; ++t) engine.step();
  for (auto _ : state) engine.step();
  state.counters["bodies"] = static_cast<double>(handle + 1);
  state.counters["awake_at_end"] = engine.awake_count();
}
#endif

}  // namespace

void register_step_benchmarks() {
  using benchmark::RegisterBenchmark;
  // One iteration is one tick, and every run times the same 240 ticks of the
  // same drop (ticks 60-300), so the fall, the first touches and the landings
  // weigh the same in both engines' averages.
  for (auto* b : {
           RegisterBenchmark("Step/level/Rewind", step_rewind, true),
           RegisterBenchmark("Step/level/Bullet", step_bullet, true),
           RegisterBenchmark("Step/ground/Rewind", step_rewind, false),
           RegisterBenchmark("Step/ground/Bullet", step_bullet, false),
       }) {
    b->Iterations(kTimedTicks)->Unit(benchmark::kMillisecond);
  }
#ifdef REWIND_HAVE_JOLT
  for (auto* b : {
           RegisterBenchmark("Step/level/Jolt", step_jolt, true),
           RegisterBenchmark("Step/ground/Jolt", step_jolt, false),
       }) {
    b->Iterations(kTimedTicks)->Unit(benchmark::kMillisecond);
  }
#endif
}

}  // namespace rwd::bench::query_level
