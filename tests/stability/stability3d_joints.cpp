// SPDX-License-Identifier: MIT
// 3D scenes where jointed solvers fail, at the default world settings (60
// Hz, 4 substeps, sleeping on), built from the shared descriptions of
// rewind/scenes/joint_scenes.h (the same ones rewind-joint-bench runs on
// Bullet): a chain holding a mass a hundred times a link's, a loaded rope
// bridge and a 30 x 30 sheet of balls on ball joints. A joint's opening is
// the world distance between its two anchors, from the bodies' poses.
// Each test prints its measured figures and asserts its criterion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "rewind/scenes/joint_scene_meter.h"
#include "rewind/scenes/joint_scenes.h"
#include "rewind/sim/world3d.h"

namespace rwd::scenes {
namespace {

void report(const std::string& what, double value, const char* unit, const char* bound = "",
            double limit = 0.0) {
  std::cout << "[ measured ] " << what << " = " << value << " " << unit;
  if (*bound != '\0') std::cout << " (" << bound << " " << limit << ")";
  std::cout << "\n";
  std::string key = what;
  for (char& c : key) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

/// Runs `scene` on a default world for its ticks, observing every tick.
struct SceneRun {
  explicit SceneRun(const JointScene& s) : scene(s), meter(scene) {
    sim::WorldConfig config;
    config.gravity = scene.gravity;
    world = std::make_unique<sim::World3D>(config);
    built = build_rewind(*world, scene);
  }
  void run(int ticks) {
    built.states(*world, states);
    meter.observe(states, 0.0);
    for (int t = 1; t <= ticks; ++t) {
      world->step();
      built.states(*world, states);
      meter.observe(states, t * static_cast<double>(world->config().tick_seconds));
      if (asleep_at_s < 0.0 && awake_dynamic() == 0) {
        asleep_at_s = t * static_cast<double>(world->config().tick_seconds);
      }
    }
  }
  int awake_dynamic() const {
    int n = 0;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
      if (!scene.bodies[i].fixed && world->is_awake(built.bodies[i])) ++n;
    }
    return n;
  }
  JointScene scene;
  JointSceneMeter meter;
  std::unique_ptr<sim::World3D> world;
  RewindJointScene built;
  std::vector<JointBodyState> states;
  double asleep_at_s = -1.0;  ///< when every dynamic body first slept; -1: never
};

// 20 box links (0.5 m, 5 kg) on ball joints hanging from a fixed point,
// holding a 500 kg sphere: 100 times a link, let go hanging straight.
// Criterion: over 20 s the chain never stretches by more than 1% of its
// 10 m (pivot to the sphere's anchor), and it settles and falls asleep
// within 10 s.
TEST(Stability3DJoints, ChainHoldsAMassAHundredTimesALink) {
  SceneRun r(hanging_chain(20, 100.0f));
  ASSERT_TRUE(r.built.error.empty()) << r.built.error;
  const double ratio = r.world->mass(r.built.bodies[static_cast<size_t>(r.scene.heavy)]) /
                       r.world->mass(r.built.bodies[0]);
  r.run(20 * 60);
  report("chain3d mass_ratio", ratio, "x");
  report("chain3d worst_stretch_pct", r.meter.max_stretch_pct, "%", "<=", 1.0);
  report("chain3d final_stretch_pct", r.meter.final_stretch_pct, "%");
  report("chain3d worst_opening_m", r.meter.max_opening_m, "m");
  report("chain3d final_speed_mps", r.meter.final_speed_mps, "m/s");
  report("chain3d asleep_at_s", r.asleep_at_s, "s", "<=", 10.0);
  EXPECT_NEAR(ratio, 100.0, 0.5);
  EXPECT_LE(r.meter.max_stretch_pct, 1.0);
  EXPECT_GE(r.asleep_at_s, 0.0) << "the chain never fell asleep";
  EXPECT_LE(r.asleep_at_s, 10.0) << "the chain took longer than 10 s to fall asleep";
}

// A rope bridge: 20 planks (1 m, 48 kg) hinged end to end and to two
// static posts, hung with slack (a shallow V), its hinges resisting with a
// friction torque of 100 N m as rope does (without it the bridge is a
// nearly undamped chain of pendulums and swings for minutes), and 8 boxes
// of 125 kg dropped on it from 1 to 3 m above its ends. Criterion: no
// joint ever opens by more than 2 cm; it carries the load (every box ends
// on the deck: above the lowest plank's centre less 0.1 m, within its
// width and span); and by 15 s it has settled (every body slower than
// 0.05 m/s, the sleep threshold).
TEST(Stability3DJoints, RopeBridgeCarriesALoadWithoutOpening) {
  SceneRun r(rope_bridge(20, 8));
  ASSERT_TRUE(r.built.error.empty()) << r.built.error;
  r.run(15 * 60);
  double lowest_plank = 1e9;
  for (int p : r.scene.planks) {
    lowest_plank = std::min(lowest_plank, double{r.states[static_cast<size_t>(p)].position.y});
  }
  double lowest_load = 1e9;
  for (int l : r.scene.loads) {
    lowest_load = std::min(lowest_load, double{r.states[static_cast<size_t>(l)].position.y});
  }
  const int carried = r.meter.loads_carried;
  report("bridge3d worst_opening_m", r.meter.max_opening_m, "m", "<=", 0.02);
  report("bridge3d final_opening_m", r.meter.final_opening_m, "m");
  report("bridge3d loads_carried", carried, "", ">=", static_cast<double>(r.scene.loads.size()));
  report("bridge3d lowest_load_above_lowest_plank_m", lowest_load - lowest_plank, "m");
  report("bridge3d final_speed_mps", r.meter.final_speed_mps, "m/s", "<=", 0.05);
  report("bridge3d asleep_at_s", r.asleep_at_s, "s");
  EXPECT_LE(r.meter.max_opening_m, 0.02);
  EXPECT_EQ(carried, static_cast<int>(r.scene.loads.size()));
  EXPECT_LE(r.meter.final_speed_mps, 0.05);
}

// A 30 x 30 sheet of spheres (0.5 m apart, 14 kg) on 1711 ball joints,
// held along one edge and falling from horizontal. Criterion: it stays
// together (no joint ever opens by more than 5 cm, a tenth of the spacing)
// and its energy never grows: kinetic plus potential never rises above
// its start by more than 0.1% of the energy the fall can release (the
// dynamic mass lowered by half the sheet's side, m g L / 2), and it ends
// below its start. Also printed: the largest rebound of the energy above
// the lowest it had been, which counts the energy the soft joints take
// into their stretch when the sheet's free edge snaps taut and give back.
TEST(Stability3DJoints, JointGridStaysTogetherAndLosesEnergy) {
  SceneRun r(joint_grid(30));
  ASSERT_TRUE(r.built.error.empty()) << r.built.error;
  r.run(10 * 60);
  report("grid3d bodies", static_cast<double>(r.scene.bodies.size()), "");
  report("grid3d joints", static_cast<double>(r.scene.joints.size()), "");
  report("grid3d worst_opening_m", r.meter.max_opening_m, "m", "<=", 0.05);
  report("grid3d final_opening_m", r.meter.final_opening_m, "m");
  report("grid3d energy_growth_pct", r.meter.energy_growth_pct(), "%", "<=", 0.1);
  report("grid3d energy_rebound_pct", r.meter.energy_rebound_pct(), "%");
  report("grid3d energy_lost_pct",
         100.0 * (r.meter.start_energy_j - r.meter.final_energy_j) / r.scene.energy_scale_j, "%");
  report("grid3d final_speed_mps", r.meter.final_speed_mps, "m/s");
  EXPECT_LE(r.meter.max_opening_m, 0.05);
  EXPECT_LE(r.meter.energy_growth_pct(), 0.1);
  EXPECT_LE(r.meter.final_energy_j, r.meter.start_energy_j);
}

}  // namespace
}  // namespace rwd::scenes
