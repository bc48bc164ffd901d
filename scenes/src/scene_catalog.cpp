// SPDX-License-Identifier: MIT
#include <chrono>

#include "rewind/scenes/scene.h"
#include "scene_factories.h"

namespace rwd::scenes {

bool SceneResult::pass() const {
  if (!error.empty()) return false;
  for (const Metric& m : metrics) {
    if (!m.pass()) return false;
  }
  return true;
}

const Metric* SceneResult::metric(std::string_view name) const {
  for (const Metric& m : metrics) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

SceneResult run_scene(Scene& scene, Engine& engine) {
  SceneResult r;
  r.scene = std::string(scene.name());
  r.size = scene.size();
  r.engine = engine.name();
  r.settings = engine.settings();
  r.ticks = scene.ticks();
  engine.reset(scene.world(), scene.body_capacity());
  if (!scene.build(engine, r.error)) {
    if (r.error.empty()) r.error = "scene could not be built";
    return r;
  }
  r.bodies = scene.body_capacity();
  using Clock = std::chrono::steady_clock;
  Clock::duration stepping{};
  for (Tick t = 0; t < r.ticks; ++t) {
    scene.before_step(t, engine);
    const Clock::time_point start = Clock::now();
    engine.step();
    const Clock::duration took = Clock::now() - start;
    stepping += took;
    scene.step_timed(t, std::chrono::duration<double, std::milli>(took).count());
    scene.after_step(t, engine);
  }
  if (r.ticks > 0) {
    r.ms_per_step = std::chrono::duration<double, std::milli>(stepping).count() / r.ticks;
  }
  r.metrics = scene.metrics();
  return r;
}

const std::vector<SceneEntry>& scene_catalog() {
  static const std::vector<SceneEntry> catalog = {
      {"stack", "vertical stack of N 1 m boxes, 60 s", {5, 10, 20, 40}, 20, make_stack},
      {"pyramid", "2D pyramid of 1 m boxes, base N, 10 s", {10, 20, 30}, 20, make_pyramid},
      {"card_house",
       "house of 2 cm cards leaning 25 degrees, N frames at the base, 10 s",
       {1, 2, 3},
       2,
       make_card_house},
      {"mass_ratio",
       "a box N times heavier resting on a 1 m box, 10 s",
       {10, 100},
       100,
       make_mass_ratio},
      {"incline_stick",
       "box on an N-degree slope, mu 0.6 (sticks), 3 s",
       {20},
       20,
       make_incline_stick},
      {"incline_slip",
       "box on an N-degree slope, mu 0.3 (slides), 2 s",
       {30},
       30,
       make_incline_slip},
      {"slide", "box sliding at N m/s on mu 0.5 until it stops", {2, 5}, 5, make_slide},
      {"bounce", "sphere dropped 2 m, restitution N%, first apex", {50, 90}, 50, make_bounce},
      {"roll", "sphere rolling down an N-degree slope, 2 s", {30}, 30, make_roll},
      {"roll_stop",
       "ball rolling at 2 m/s with rolling resistance N/10 until it stops",
       {1, 3},
       3,
       make_roll_stop},
      {"free_fall", "sphere falling freely for N s", {1, 3}, 1, make_free_fall},
      {"free_spin",
       "box spinning at N rad/s about its intermediate axis, no gravity, 10 s",
       {10},
       10,
       make_free_spin},
      {"projectile", "10 cm ball at N m/s against a 5 cm wall", {50, 200}, 200, make_projectile},
      {"pile",
       "N 0.5 m boxes dropped into a bin, 6 s",
       {250, 500, 1000, 2000, 4000, 8000},
       1000,
       make_pile},
      {"mixed_pile",
       "N bodies, boxes and capsules in turn, dropped into a bin, 6 s",
       {250, 500, 1000},
       500,
       make_mixed_pile},
      {"convex_pile",
       "N bodies cycling box, capsule, sphere, rock hull and prism hull, dropped into a bin, 6 s",
       {250, 500, 1000},
       500,
       make_convex_pile},
      {"compound_pile",
       "N compounds, tables (five boxes) and dumbbells (a capsule and two balls) in turn, "
       "dropped into a bin, 6 s",
       {200},
       200,
       make_compound_pile},
      {"mesh_pile",
       "N bodies of the convex pile's mix dropped into a bin on a bumpy triangle-mesh floor, 6 s",
       {250, 1000},
       1000,
       make_mesh_pile},
      {"field_boxes",
       "N 0.4 m boxes set down on the rolling hills of a height field, 10 s",
       {25, 100},
       100,
       make_field_boxes},
      {"hull_stack",
       "column of N hexagonal prism hulls, each turned 30 degrees from the one below, 10 s",
       {5, 10},
       10,
       make_hull_stack},
      {"compound_balance",
       "N lopsided compound props (cube and arm), each on a post under its centre of mass, 5 s",
       {4},
       4,
       make_compound_balance},
      {"hull_slip",
       "octagonal prism hull on an N-degree slope, mu 0.3 (slides), 2 s",
       {30},
       30,
       make_hull_slip},
      {"log_cabin",
       "N layers of two 2 m capsule logs, each layer across the one below, 10 s",
       {3, 6},
       6,
       make_log_cabin},
      {"overlap",
       "a column of N 1 m boxes created half inside each other, 3 s",
       {5, 10},
       10,
       make_overlap},
      {"kick", "stack of N boxes, the top one kicked at 1 m/s after 1 s", {5}, 5, make_kick},
      {"far_stack", "5-box stack N m from the origin, 20 s", {1000, 10000}, 10000, make_far_stack},
      {"crates",
       "the crates sample match with N players: a closed arena, a tower of 16 crates, N balls "
       "steered by scripted sticks, 10 s",
       {2, 8, 32},
       8,
       make_crates},
      {"sleep",
       "pyramid of base N until every body sleeps, then asleep, 10 s",
       {10, 20, 30},
       30,
       make_sleep},
  };
  return catalog;
}

std::unique_ptr<Scene> make_scene(std::string_view name, int size) {
  for (const SceneEntry& e : scene_catalog()) {
    if (e.name == name) return e.make(size);
  }
  return nullptr;
}

}  // namespace rwd::scenes
