// SPDX-License-Identifier: MIT
// rewind-joint-bench: the jointed scenes of rewind/scenes/joint_scenes.h
// (a hinge pendulum, a 20-link chain holding 100 times a link, a loaded
// rope bridge, a 30 x 30 grid of balls on ball joints, a pile of 50
// ragdolls) on Rewind and on Bullet 3 (joint_engines.h says how each scene
// becomes Bullet), in one process, one thread, the engines taking turns in
// blocks of 10 ticks so that a shared machine's load falls on both alike.
// Prints one CSV row per (scene, engine setting) on stdout: the wall time
// per step and the joint errors measured from the poses each engine
// reports (the widest anchor opening, the chain's stretch, the pendulum's
// period against the analytic one, the energy's rise, the boxes the
// bridge still carries), progress on stderr.
// The ragdoll pile is the costly one (551 bodies, 500 joints, 480 ticks):
// its six settings take about 25 s of a full run on a 2-core machine,
// longer than the other four scenes together. It runs the whole sweep all
// the same, since how its openings fall with substeps and iterations is
// what its chart shows; --quick keeps a run to seconds.
// scripts/charts_joints.py turns the rows into charts and the "3D joints"
// section of docs/BENCHMARKS.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "joint_engines.h"
#include "rewind/scenes/joint_scene_meter.h"

namespace {

using rwd::bench::JointEngine;
using rwd::scenes::JointBodyState;
using rwd::scenes::JointScene;
using rwd::scenes::JointSceneMeter;

constexpr int kBlockTicks = 10;
constexpr double kTickSeconds = 1.0 / 60.0;

constexpr const char* kUsage =
    "usage: rewind-joint-bench [--scene NAME]... [--size N] [--ticks N] [--quick] [--list]\n"
    "  Runs each jointed scene (default: pendulum, chain, bridge, grid,\n"
    "  ragdoll_pile) on Rewind (substeps 4, 8, 16; relax 1) and Bullet 3 (solver\n"
    "  iterations 10, 20, 40), sleeping off in both, in turns of 10 ticks in one\n"
    "  process. --quick runs the defaults only (Rewind 4 substeps, Bullet 10\n"
    "  iterations); --size replaces the scene's size (links, planks, grid side,\n"
    "  ragdolls: at most 372, which Rewind's default 4096 bodies hold); --ticks\n"
    "  its ticks.\n"
    "  The ragdoll pile (50 ragdolls, 480 ticks) is the slow one: about 25 s of a\n"
    "  full run and 6 s of a --quick one on 2 cores.\n"
    "  Prints CSV on stdout (ms per step and joint errors), progress on stderr.\n"
    "  Exit 0 on success, 1 if an engine refused a scene, 2 on bad usage.\n";

std::vector<std::unique_ptr<JointEngine>> engines(bool quick) {
  std::vector<std::unique_ptr<JointEngine>> e;
  for (int substeps : {4, 8, 16}) {
    if (!quick || substeps == 4) e.push_back(rwd::bench::make_rewind_joint_engine(substeps));
  }
  for (int iterations : {10, 20, 40}) {
    if (!quick || iterations == 10) e.push_back(rwd::bench::make_bullet_joint_engine(iterations));
  }
  return e;
}

const char* describe(const std::string& name) {
  if (name == "pendulum") {
    return "a 0.1 x 1 x 0.1 m box rod on a hinge at its end, let go 0.05 rad from straight down";
  }
  if (name == "chain") {
    return "N box links (0.5 m, 5 kg) on ball joints hanging from a fixed point, holding a "
           "sphere of 100 times a link's mass";
  }
  if (name == "bridge") {
    return "N planks (1 m, 48 kg) hinged end to end between two static posts, in a shallow V, "
           "hinge friction 100 N m, 8 boxes of 125 kg dropped on them";
  }
  if (name == "ragdoll_pile") {
    return "N of Rewind's ragdolls (11 capsules, cone-twist and hinge limits; 1.8 m, 70 kg) in "
           "crossed layers of five, dropped from 0.4 to 4.5 m onto a floor";
  }
  return "an N x N sheet of spheres (0.5 m apart) on ball joints to their neighbours, held "
         "along one edge, falling from horizontal";
}

/// One (scene, engine) run: its meter and timing.
struct Lane {
  std::unique_ptr<JointSceneMeter> meter;
  std::vector<JointBodyState> states;
  double seconds = 0.0;
  int ticks = 0;
  bool ok = true;
};

std::string cell(double v, bool present) {
  if (!present) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  int size = 0;
  int ticks = 0;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strcmp(a, "--scene") == 0 && i + 1 < argc) {
      names.emplace_back(argv[++i]);
    } else if (std::strcmp(a, "--size") == 0 && i + 1 < argc) {
      size = std::atoi(argv[++i]);
    } else if (std::strcmp(a, "--ticks") == 0 && i + 1 < argc) {
      ticks = std::atoi(argv[++i]);
    } else if (std::strcmp(a, "--quick") == 0) {
      quick = true;
    } else if (std::strcmp(a, "--list") == 0) {
      for (const auto& n : rwd::scenes::joint_scene_names())
        std::printf("%s: %s\n", n.c_str(), describe(n));
      return 0;
    } else if (std::strcmp(a, "--help") == 0 || std::strcmp(a, "-h") == 0) {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fputs(kUsage, stderr);
      return 2;
    }
  }
  if (names.empty()) names = rwd::scenes::joint_scene_names();

  std::printf(
      "scene,size,bodies,joints,engine,settings,default,ticks,ms_per_step,max_opening_m,"
      "final_opening_m,max_stretch_pct,final_stretch_pct,period_s,analytic_period_s,"
      "period_error_pct,energy_growth_pct,energy_rebound_pct,final_speed_mps,loads,loads_"
      "carried\n");
  int status = 0;
  for (const std::string& name : names) {
    const JointScene scene = rwd::scenes::make_joint_scene(name, size);
    if (scene.name.empty()) {
      std::fprintf(stderr, "rewind-joint-bench: unknown scene '%s'\n", name.c_str());
      return 2;
    }
    const int run_ticks = ticks > 0 ? ticks : scene.ticks;
    std::fprintf(stderr, "joints: %s %d (%zu bodies, %zu joints, %d ticks)\n", name.c_str(),
                 scene.size, scene.bodies.size(), scene.joints.size(), run_ticks);
    auto e = engines(quick);
    std::vector<Lane> lanes(e.size());
    for (size_t k = 0; k < e.size(); ++k) {
      std::string error;
      if (!e[k]->build(scene, error)) {
        std::fprintf(stderr, "joints: %s %s refused: %s\n", e[k]->name().c_str(), name.c_str(),
                     error.c_str());
        lanes[k].ok = false;
        status = 1;
        continue;
      }
      lanes[k].meter = std::make_unique<JointSceneMeter>(scene);
      e[k]->states(lanes[k].states);
      lanes[k].meter->observe(lanes[k].states, 0.0);
    }
    for (int done = 0; done < run_ticks; done += kBlockTicks) {
      const int block = std::min(kBlockTicks, run_ticks - done);
      for (size_t k = 0; k < e.size(); ++k) {
        Lane& lane = lanes[k];
        if (!lane.ok) continue;
        for (int t = 0; t < block; ++t) {
          const auto start = std::chrono::steady_clock::now();
          e[k]->step();
          lane.seconds +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          ++lane.ticks;
          e[k]->states(lane.states);
          lane.meter->observe(lane.states, lane.ticks * kTickSeconds);
        }
      }
    }
    for (size_t k = 0; k < e.size(); ++k) {
      const Lane& lane = lanes[k];
      if (!lane.ok) continue;
      const JointSceneMeter& m = *lane.meter;
      const bool chain = scene.heavy >= 0;
      const bool pendulum = scene.rod >= 0;
      const bool energy = scene.energy_scale_j > 0.0;
      const bool loads = !scene.loads.empty();
      const double ms = 1e3 * lane.seconds / lane.ticks;
      std::printf(
          "%s,%d,%zu,%zu,%s,%s,%d,%d,%.6f,%.6g,%.6g,%s,%s,%s,%s,%s,%s,%s,%.6g,%s,%s\n",
          name.c_str(), scene.size, scene.bodies.size(), scene.joints.size(), e[k]->name().c_str(),
          e[k]->settings().c_str(), e[k]->is_default() ? 1 : 0, lane.ticks, ms, m.max_opening_m,
          m.final_opening_m, cell(m.max_stretch_pct, chain).c_str(),
          cell(m.final_stretch_pct, chain).c_str(), cell(m.period_s(), pendulum).c_str(),
          cell(scene.analytic_period_s, pendulum).c_str(),
          cell(m.period_error_pct(), pendulum).c_str(), cell(m.energy_growth_pct(), energy).c_str(),
          cell(m.energy_rebound_pct(), energy).c_str(), m.final_speed_mps,
          cell(static_cast<double>(scene.loads.size()), loads).c_str(),
          cell(m.loads_carried, loads).c_str());
      std::fprintf(stderr, "joints:   %-6s %-14s %8.3f ms/step  max opening %.4f m\n",
                   e[k]->name().c_str(), e[k]->settings().c_str(), ms, m.max_opening_m);
    }
    std::fflush(stdout);
  }
  return status;
}
