// SPDX-License-Identifier: MIT
// Prints one line per tick, "<tick> <checksum as 16 hex digits>", for a
// 4-player "crates" match driven by a scripted input stream. The matrix
// (run_matrix.sh) builds this file with several compilers, flags and
// architectures and diffs the outputs: any difference is a determinism bug.
//
// Every 10 ticks it also exercises the rollback path the server and clients
// take: save, step 5 ticks, restore, step the same 5 ticks with mispredicted
// inputs, restore again, and step them with the real inputs. The checksums of
// the re-simulated ticks must equal the first pass bit for bit; otherwise it
// prints "ROLLBACK-MISMATCH <tick>" and exits 3.
//
// Before the match it prints "edge <tick> <checksum>" lines for an engine
// scene at the edge of the world: small bounds, bodies flung out of them
// (disabled, reported) and respawned, the world reloaded from its own
// serialized bytes every 50 ticks, so the bounds rule, disabled bodies and
// the snapshot codec are part of the matrix too; then "heap <tick>
// <checksum> <points>" lines for a heap with deep and shallow overlaps that
// sleeps and is kicked awake, so the push-out and the broadphase's trees are
// part of it. The very first line, "fixed <digest>", is the golden digest
// of the fixed-point library (tests/unit/fixed/golden_digest.h), so the
// integer-only 2D foundation is part of the matrix as well.
//
// Links only the engine and the game seam: no I/O beyond stdout, no clock.
//
// Then "lane2d <tick> <checksum> <query digest>" lines for the 2D lane's
// engine scene (tests/determinism/lane2d_scene.h): every shape, joint and
// query, a character, sleeping, continuous bullets, restores and reloads;
// and "joints3d <tick> <checksum> <broken>" lines for the 3D lane's joint
// scene (tests/determinism/joints3d_scene.h): every joint type, joint
// trees and a loop, a break, a raycast car and a character.
// Before the "crates" match it plays a scripted 2D "arena" match the same
// way, its lines prefixed "arena ", so the fixed-point lane and its
// rollback are part of the matrix too; then a scripted 3D "joust" match,
// its lines prefixed "joust ", so the height field, the raycast vehicles,
// welds that break, jointed riders and the wrecking ball's chain are.
//
// Usage: det_checksums [TICKS]   (default 600)
// Exit codes: 0 ok, 2 bad usage or the game could not be created, 3 rollback
// mismatch.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "golden_digest.h"
#include "joints3d_scene.h"
#include "lane2d_scene.h"
#include "rewind/core/player_input.h"
#include "rewind/core/splitmix64.h"
#include "rewind/core/thread_pool.h"
#include "rewind/game/simulation.h"
#include "rewind/sim/hash_math.h"
#include "rewind/sim/world3d.h"

namespace {

using rwd::PlayerInput;
using rwd::SplitMix64;
using rwd::StickInput;
using rwd::Tick;
using rwd::game::MatchSetup;
using rwd::game::SimSnapshot;
using rwd::game::Simulation;

constexpr uint32_t kPlayers = 4;
constexpr uint64_t kSeed = 7;
constexpr uint64_t kScriptSeed = 0x5EED'0F'DE7E'2A11ull;
constexpr Tick kRollbackEvery = 10;
constexpr Tick kRollbackDepth = 5;

// SplitMix64 (rewind/core/splitmix64.h): integer operations only, identical
// on every compiler and architecture, so the input script itself can never
// be the difference.

// inputs[t * kPlayers + p] is player p's input for tick t. Each player holds
// an input for 1..6 ticks and then switches to a new random one.
std::vector<PlayerInput> make_script(Tick ticks) {
  std::vector<PlayerInput> inputs(static_cast<size_t>(ticks) * kPlayers);
  SplitMix64 rng{kScriptSeed};
  StickInput current[kPlayers] = {};
  uint32_t hold[kPlayers] = {};
  for (Tick t = 0; t < ticks; ++t) {
    for (uint32_t p = 0; p < kPlayers; ++p) {
      if (hold[p] == 0) {
        current[p].axis_x = static_cast<int16_t>(static_cast<int32_t>(rng.below(2001)) - 1000);
        current[p].axis_y = static_cast<int16_t>(static_cast<int32_t>(rng.below(2001)) - 1000);
        current[p].buttons = static_cast<uint32_t>(rng.next());
        hold[p] = 1 + rng.below(6);
      }
      --hold[p];
      inputs[static_cast<size_t>(t) * kPlayers + p] = PlayerInput::of(current[p]);
    }
  }
  return inputs;
}

// The joust drivers: the same stream, with the throttle mostly forward
// (cars that only dither never meet), charging on bit 1 as it comes and
// braking on one tick in eight.
std::vector<PlayerInput> make_joust_script(Tick ticks) {
  std::vector<PlayerInput> inputs = make_script(ticks);
  for (PlayerInput& input : inputs) {
    StickInput in = input.as<StickInput>();
    const int32_t y = in.axis_y < 0 ? -in.axis_y : in.axis_y;
    in.axis_y = static_cast<int16_t>(300 + y * 7 / 10);
    in.buttons = (in.buttons & 2u) | ((in.buttons >> 8) % 8 == 0 ? 1u : 0u);
    input = PlayerInput::of(in);
  }
  return inputs;
}

std::span<const PlayerInput> inputs_for(const std::vector<PlayerInput>& script, Tick t) {
  return std::span<const PlayerInput>(script).subspan(static_cast<size_t>(t) * kPlayers, kPlayers);
}

// What a client predicts when a remote input is late: the previous tick's
// input repeated, with the buttons flipped so that the prediction is wrong.
std::vector<PlayerInput> mispredict(const std::vector<PlayerInput>& script, Tick t) {
  std::vector<PlayerInput> guess(kPlayers);
  for (uint32_t p = 0; p < kPlayers; ++p) {
    const StickInput prev =
        script[static_cast<size_t>(t > 0 ? t - 1 : 0) * kPlayers + p].as<StickInput>();
    guess[p] = rwd::stick_input(static_cast<int16_t>(-prev.axis_y), prev.axis_x, ~prev.buttons);
  }
  return guess;
}

// A uniform value in [-half, half] from the stream.
float uniform(SplitMix64& rng, float half) {
  return (static_cast<float>(rng.below(20001)) / 10000.0f - 1.0f) * half;
}

// A 40 m square floor whose top is at y = 0.
rwd::sim::BodyDef floor_def() {
  rwd::sim::BodyDef ground;
  ground.kind = rwd::sim::BodyKind::kStatic;
  ground.shape = rwd::sim::Shape::make_box({20.0f, 0.5f, 20.0f});
  ground.position = {0.0f, -0.5f, 0.0f};
  return ground;
}

// Two hulls every scene registers: a wedge (a triangular prism whose points'
// origin is its corner, so its centre of mass is off the origin) and an
// irregular gem of eight corners.
void add_hulls(rwd::sim::GeometryStore& store, rwd::sim::GeometryId& wedge,
               rwd::sim::GeometryId& gem) {
  using rwd::sim::Vec3;
  const Vec3 wedge_points[] = {{0.0f, 0.0f, 0.0f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
                               {0.0f, 0.0f, 0.6f}, {0.8f, 0.0f, 0.6f}, {0.0f, 0.5f, 0.6f}};
  const Vec3 gem_points[] = {{0.35f, 0.0f, 0.0f},   {-0.3f, 0.05f, 0.1f}, {0.0f, 0.4f, 0.05f},
                             {0.05f, -0.35f, 0.0f}, {0.0f, 0.0f, 0.3f},   {0.1f, 0.0f, -0.32f},
                             {0.2f, 0.2f, 0.2f},    {-0.2f, -0.2f, -0.2f}};
  wedge = *store.add_hull(wedge_points);
  gem = *store.add_hull(gem_points);
}

// Steps the world four ticks, restores it and steps them again: the second
// pass must print the first pass's checksums. Leaves the world restored.
// Prints "ROLLBACK-MISMATCH <scene> <tick>" and returns false otherwise.
bool restep_matches(rwd::sim::World3D& world, const char* scene, Tick t) {
  rwd::sim::WorldState saved;
  world.save(saved);
  uint64_t first_pass[4] = {};
  for (uint64_t& sum : first_pass) {
    world.step();
    sum = world.checksum();
  }
  world.restore(saved);
  for (const uint64_t sum : first_pass) {
    world.step();
    if (world.checksum() != sum) {
      std::printf("ROLLBACK-MISMATCH %s %d\n", scene, static_cast<int>(t));
      return false;
    }
  }
  world.restore(saved);
  return true;
}

// The edge-of-the-world scene. Returns false (after saying why) when a
// snapshot of its own state does not load or a restore does not re-step.
bool run_edge_scene(Tick ticks) {
  namespace sim = rwd::sim;
  sim::WorldConfig config;
  config.bounds_lower = {-30.0f, -30.0f, -30.0f};
  config.bounds_upper = {30.0f, 30.0f, 30.0f};
  auto world = std::make_unique<sim::World3D>(config);
  sim::GeometryId wedge;
  sim::GeometryId gem;
  add_hulls(world->geometry(), wedge, gem);
  SplitMix64 rng{0xED6E'0F'7E11'0001ull};
  auto coord = [&rng](float half) { return uniform(rng, half); };
  (void)world->create_body(floor_def());
  std::vector<sim::BodyId> bodies;
  for (int i = 0; i < 24; ++i) {
    sim::BodyDef def;
    def.shape = i % 4 == 1   ? sim::Shape::make_sphere(0.4f)
                : i % 4 == 3 ? sim::Shape::make_hull(i % 8 == 3 ? wedge : gem)
                             : sim::Shape::make_box({0.3f, 0.5f, 0.4f});
    def.position = {coord(8.0f), 1.0f + static_cast<float>(i) * 0.5f, coord(8.0f)};
    def.material.restitution = i % 3 == 0 ? 0.5f : 0.0f;
    bodies.push_back(*world->create_body(def));
  }
  std::vector<uint8_t> bytes;
  for (Tick t = 0; t < ticks; ++t) {
    const sim::BodyId id = bodies[rng.below(static_cast<uint32_t>(bodies.size()))];
    const float kick = rng.below(8) == 0 ? 40000.0f : 2000.0f;  // sometimes out of the world
    (void)world->apply_linear_impulse(id, {coord(kick), coord(kick), coord(kick)},
                                      world->position(id));
    if (t % 40 == 39) {
      for (const sim::BodyId b : bodies) {
        if (world->is_enabled(b)) continue;
        (void)world->set_transform(b, {coord(5.0f), 4.0f, coord(5.0f)}, {});
        (void)world->set_enabled(b, true);
      }
    }
    if (t % 50 == 0) {
      world->serialize(bytes);
      // A snapshot loads into a world with the same geometry.
      auto loaded = std::make_unique<sim::World3D>(sim::WorldConfig{}, world->shared_geometry());
      if (rwd::Status s = loaded->deserialize(bytes); !s.ok()) {
        std::fprintf(stderr, "det_checksums: edge scene tick %d does not load: %s\n",
                     static_cast<int>(t), s.message().c_str());
        return false;
      }
      world = std::move(loaded);
    }
    if (t % 25 == 0 && !restep_matches(*world, "edge", t)) return false;
    world->step();
    uint32_t left = static_cast<uint32_t>(world->body_events().size());
    std::printf("edge %d %016" PRIx64 " %u\n", static_cast<int>(t), world->checksum(), left);
  }
  return true;
}

// The heap scene: a column of boxes built half inside each other (deep
// overlaps, pushed out one at a time from the ground up) beside a heap of
// boxes, spheres, capsules and hulls dropped into a corner overlapping a little (shallow
// overlaps, pushed out in the solver's lanes), with sleeping on, so bodies
// fall asleep, are kicked awake and pile up again (resting contacts carry
// their manifolds forward in between). Every 30 ticks a restore
// must re-step bit for bit. Returns false (after saying why) otherwise.
// The heap scene on `pool` (null: the stepping thread alone), its lines
// appended to `out`: the same lines on any number of threads.
bool run_heap_scene(Tick ticks, rwd::ThreadPool* pool, std::string& out) {
  namespace sim = rwd::sim;
  sim::World3D world;
  world.set_thread_pool(pool);
  sim::GeometryId wedge;
  sim::GeometryId gem;
  add_hulls(world.geometry(), wedge, gem);
  // A compound of a box, a sphere and the gem, off-centre.
  const sim::CompoundChild dumbbell_parts[] = {
      {sim::Shape::make_box({0.2f, 0.15f, 0.15f}), {0.0f, 0.0f, 0.0f}, {}},
      {sim::Shape::make_sphere(0.18f), {0.4f, 0.05f, 0.0f}, {}},
      {sim::Shape::make_hull(gem), {-0.3f, 0.0f, 0.1f}, {}}};
  const sim::GeometryId dumbbell = *world.geometry().add_compound(dumbbell_parts);
  SplitMix64 rng{0x4EA9'0F'B0C5'0002ull};
  auto coord = [&rng](float half) { return uniform(rng, half); };
  const sim::BodyDef ground = floor_def();
  (void)world.create_body(ground);
  for (int w = 0; w < 2; ++w) {  // two walls make a corner
    sim::BodyDef wall = ground;
    wall.shape =
        sim::Shape::make_box(w == 0 ? sim::Vec3{0.5f, 3.0f, 6.0f} : sim::Vec3{6.0f, 3.0f, 0.5f});
    wall.position = w == 0 ? sim::Vec3{-6.5f, 3.0f, 0.0f} : sim::Vec3{0.0f, 3.0f, -6.5f};
    (void)world.create_body(wall);
  }
  // Terrain under the heap: a bumpy height field patch, and a mesh ramp
  // beside it, so bodies meet triangles (internal edges, folds, and the
  // blended normals of bodies across them) on every build.
  {
    std::vector<float> heights(9 * 9);
    for (size_t k = 0; k < heights.size(); ++k) {
      heights[k] = 0.02f * static_cast<float>((k * 7) % 5) + 0.01f;
    }
    const sim::GeometryId field =
        *world.geometry().add_height_field(9, 9, {0.5f, 1.0f, 0.5f}, heights);
    sim::BodyDef patch;
    patch.kind = sim::BodyKind::kStatic;
    patch.shape = sim::Shape::make_height_field(field);
    patch.position = {-6.0f, 0.0f, -6.0f};
    (void)world.create_body(patch);
    const sim::Vec3 ramp_points[] = {{0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 2.0f},
                                     {0.0f, 0.0f, 2.0f}, {0.0f, 0.8f, 0.0f}, {0.0f, 0.8f, 2.0f}};
    const uint32_t ramp_indices[] = {0, 4, 1, 1, 4, 5, 1, 5, 2, 0, 3, 4, 3, 5, 4};
    const sim::GeometryId ramp = *world.geometry().add_mesh(ramp_points, ramp_indices);
    sim::BodyDef r;
    r.kind = sim::BodyKind::kStatic;
    r.shape = sim::Shape::make_mesh(ramp);
    r.position = {1.0f, 0.0f, -5.5f};
    (void)world.create_body(r);
  }
  std::vector<sim::BodyId> bodies;
  for (int i = 0; i < 8; ++i) {  // the column: each box half inside the one below
    sim::BodyDef def;
    def.shape = sim::Shape::make_box({0.5f, 0.5f, 0.5f});
    def.position = {4.0f, 0.5f + 0.5f * static_cast<float>(i), 4.0f};
    bodies.push_back(*world.create_body(def));
  }
  for (int i = 0; i < 40; ++i) {  // the heap: a loose lattice, a little overlapping
    sim::BodyDef def;
    // Boxes, spheres, capsules, hulls and compounds: every pair of shape
    // types meets.
    def.shape = i % 4 == 3    ? sim::Shape::make_sphere(0.35f)
                : i % 4 == 1  ? sim::Shape::make_capsule(0.2f, 0.15f)
                : i % 8 == 2  ? sim::Shape::make_hull(wedge)
                : i % 8 == 6  ? sim::Shape::make_hull(gem)
                : i % 16 == 4 ? sim::Shape::make_compound(dumbbell)
                              : sim::Shape::make_box({0.35f, 0.35f, 0.35f});
    // Spheres and capsules resist rolling (a few more than others).
    if (i % 2 == 1) def.material.rolling_resistance = 0.05f * static_cast<float>(i % 5);
    // Every other capsule is a character: locked upright.
    if (i % 8 == 1) def.lock_rotation = sim::kLockRotationX | sim::kLockRotationZ;
    def.position = {-5.0f + 0.65f * static_cast<float>(i % 4),
                    0.4f + 0.65f * static_cast<float>(i / 16),
                    -5.0f + 0.65f * static_cast<float>((i / 4) % 4)};
    bodies.push_back(*world.create_body(def));
  }
  // Bullets (continuous collision), a ball and a dumbbell (swept by its
  // children), fired at the corner's walls now and then.
  sim::BodyDef bullet_def;
  bullet_def.shape = sim::Shape::make_sphere(0.05f);
  bullet_def.position = {3.0f, 1.0f, 2.0f};
  bullet_def.continuous = true;
  const sim::BodyId bullet = *world.create_body(bullet_def);
  bullet_def.shape = sim::Shape::make_compound(dumbbell);
  bullet_def.position = {5.0f, 2.0f, 2.0f};
  const sim::BodyId heavy_bullet = *world.create_body(bullet_def);
  for (Tick t = 0; t < ticks; ++t) {
    if (t % 60 == 30) {
      (void)world.set_transform(bullet, {3.0f, 1.0f + 0.1f * static_cast<float>(t % 7), 2.0f}, {});
      (void)world.set_linear_velocity(bullet, {coord(40.0f), 3.0f, -400.0f});
    }
    if (t % 60 == 45) {
      (void)world.set_transform(heavy_bullet, {5.0f, 2.0f, 2.0f}, {});
      (void)world.set_linear_velocity(heavy_bullet, {-300.0f, coord(5.0f), coord(30.0f)});
    }
    if (t % 90 == 60) {  // a kick wakes part of the heap
      const sim::BodyId id = bodies[8 + rng.below(40)];
      (void)world.apply_linear_impulse(id, {coord(30.0f), 20.0f, coord(30.0f)}, world.position(id));
      // ... and a push off-centre, with a twist.
      const sim::BodyId other = bodies[8 + rng.below(40)];
      (void)world.apply_force_at(other, {coord(900.0f), 0.0f, coord(900.0f)},
                                 world.position(other) + sim::Vec3{0.0f, 0.2f, 0.0f});
      (void)world.apply_torque(other, {0.0f, coord(200.0f), 0.0f});
    }
    if (t % 30 == 0 && !restep_matches(world, "heap", t)) return false;
    world.step();
    // Contact points and reused manifolds too: every build must carry the
    // same manifolds forward on the same ticks; and the events a game reads
    // (with their points, normals, depths and impulses) must agree as well.
    rwd::StateHasher events;
    for (const sim::ContactEvent& e : world.events()) {
      events.add_u8(static_cast<uint8_t>(e.type));
      events.add_u32(e.a.index);
      events.add_u32(e.b.index);
      sim::hash_vec3(events, e.point);
      sim::hash_vec3(events, e.normal);
      events.add_f32(e.depth);
      events.add_f32(e.impulse);
    }
    char line[128];
    std::snprintf(line, sizeof line, "heap %d %016" PRIx64 " %u %u %016" PRIx64 "\n",
                  static_cast<int>(t), world.checksum(), world.stats().contact_points,
                  world.stats().reused_manifolds, events.digest());
    out += line;
  }
  return true;
}

// One tick; the built-in games' rules never fail, so a failure is reported
// and ends the run.
bool stepped(Simulation& sim, std::span<const PlayerInput> inputs) {
  if (rwd::Status status = sim.step(inputs); !status.ok()) {
    std::fprintf(stderr, "det_checksums: %s\n", status.message().c_str());
    return false;
  }
  return true;
}

bool parse_ticks(const char* text, Tick& out) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < 1 || value > 1'000'000) return false;
  out = static_cast<Tick>(value);
  return true;
}

// A scripted match of `game`, one line per tick prefixed by `prefix`,
// with the save / mispredict / restore / re-step check every
// kRollbackEvery ticks. Returns 0, 2 (the game cannot be created) or 3.
int run_match(const char* game, const char* prefix, Tick ticks,
              std::vector<PlayerInput> (*script_for)(Tick) = make_script) {
  MatchSetup setup;
  setup.player_count = kPlayers;
  setup.seed = kSeed;
  auto created = Simulation::create(game, setup);
  if (!created.ok()) {
    std::fprintf(stderr, "det_checksums: cannot create \"%s\": %s\n", game,
                 created.status().message().c_str());
    return 2;
  }
  Simulation& sim = **created;

  const std::vector<PlayerInput> script = script_for(ticks);
  SimSnapshot snapshot;
  uint64_t first_pass[kRollbackDepth] = {};

  Tick t = 0;
  while (t < ticks) {
    if (t % kRollbackEvery == 0 && t + kRollbackDepth <= ticks) {
      sim.save(snapshot);
      const uint64_t saved_checksum = sim.checksum();
      for (Tick i = 0; i < kRollbackDepth; ++i) {
        if (!stepped(sim, inputs_for(script, t + i))) return 3;
        first_pass[i] = sim.checksum();
      }
      // A wrong prediction first, as on a real client, so that restore() has
      // to undo a diverged world (contacts, sleep state, game state).
      sim.restore(snapshot);
      for (Tick i = 0; i < kRollbackDepth; ++i) {
        const std::vector<PlayerInput> guess = mispredict(script, t + i);
        if (!stepped(sim, guess)) return 3;
      }
      sim.restore(snapshot);
      if (sim.tick() != t || sim.checksum() != saved_checksum) {
        std::printf("%sROLLBACK-MISMATCH %d\n", prefix, static_cast<int>(t));
        std::fprintf(stderr,
                     "det_checksums: restore() at tick %d did not bring back the saved state\n",
                     static_cast<int>(t));
        return 3;
      }
      for (Tick i = 0; i < kRollbackDepth; ++i) {
        if (!stepped(sim, inputs_for(script, t + i))) return 3;
        const uint64_t again = sim.checksum();
        if (again != first_pass[i]) {
          std::printf("%sROLLBACK-MISMATCH %d\n", prefix, static_cast<int>(t + i));
          std::fprintf(stderr,
                       "det_checksums: tick %d re-simulated after restore: %016" PRIx64
                       ", first pass: %016" PRIx64 "\n",
                       static_cast<int>(t + i), again, first_pass[i]);
          return 3;
        }
        std::printf("%s%d %016" PRIx64 "\n", prefix, static_cast<int>(t + i), again);
      }
      t += kRollbackDepth;
      continue;
    }
    if (!stepped(sim, inputs_for(script, t))) return 3;
    std::printf("%s%d %016" PRIx64 "\n", prefix, static_cast<int>(t), sim.checksum());
    ++t;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Tick ticks = 600;
  if (argc > 2 || (argc == 2 && !parse_ticks(argv[1], ticks))) {
    std::fprintf(stderr, "usage: det_checksums [TICKS]   (1..1000000, default 600)\n");
    return 2;
  }

  std::printf("fixed %016" PRIx64 "\n", rwd::fixed::golden_digest());
  if (!run_edge_scene(300)) return 3;
  {
    // The heap alone, then on three threads (the narrowphase's pairs cut
    // across them): the lines must be the same.
    std::string alone;
    if (!run_heap_scene(400, nullptr, alone)) return 3;
    std::fputs(alone.c_str(), stdout);
    rwd::ThreadPool pool(3);
    std::string threaded;
    if (!run_heap_scene(400, &pool, threaded)) return 3;
    if (threaded != alone) {
      std::printf("THREADS-MISMATCH heap\n");
      std::fprintf(stderr, "det_checksums: the heap stepped on %u threads differs from one\n",
                   pool.threads());
      return 3;
    }
  }

  // The 2D lane's engine scene: every shape, joint and query.
  if (!rwd::determinism::run_lane2d_scene(300)) return 3;
  // The 3D lane's joints, a raycast car and a character.
  if (!rwd::determinism::run_joints3d_scene(300)) return 3;
  // The 2D lane's sample game: the fixed-point world through the same
  // seam, with the same rollback check.
  if (const int rc = run_match("arena", "arena ", ticks); rc != 0) return rc;
  // The 3D vehicle game: cars on raycast wheels over a height field,
  // breakable seat welds, jointed riders thrown and re-seated, a chain.
  if (const int rc = run_match("joust", "joust ", ticks, make_joust_script); rc != 0) return rc;
  if (const int rc = run_match("crates", "", ticks); rc != 0) return rc;
  return std::fflush(stdout) == 0 ? 0 : 2;
}
