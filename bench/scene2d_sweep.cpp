// SPDX-License-Identifier: MIT
// rewind-scene2d-sweep: runs the 2D scenes on Rewind's 2D lane, Box2D 2.4
// and, when built with it (REWIND_BOX2D3_DIR), Box2D v3 in one process
// (taking turns in blocks of ticks) and prints one CSV row per (scene,
// engine setting) on stdout, progress on stderr.
// scripts/charts2d.py turns the rows into charts and the 2D section of
// docs/BENCHMARKS.md.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "box2d_engine.h"
#include "rewind2d_engine.h"
#ifdef REWIND_HAVE_BOX2D3
#include "box2d3_engine.h"
#endif
#include "run2d.h"
#include "scene2d.h"

namespace {

using rwd::bench::Box2DEngine;
using rwd::bench::Engine2D;
using rwd::bench::Rewind2DEngine;
using rwd::bench::Scene2D;

constexpr const char* kUsage =
    "usage: rewind-scene2d-sweep [--scene NAME]... [--size N] [--ticks N] [--sweep]\n"
    "                            [--engine rewind|box2d|box2d3|both] [--threads N] [--list]\n"
    "  Runs each 2D scene (default: all) on Rewind (4 substeps, relax 1) and Box2D 2.4\n"
    "  (8/3 and 4/2 velocity/position iterations; 8/3 also without continuous\n"
    "  collision), and Box2D v3 (4 substeps) when built with it\n"
    "  (-DREWIND_BOX2D3_DIR=...), sleeping off in all. --sweep adds\n"
    "  Rewind substeps 6, 8, 16 (fewer than 4 at 60 Hz are refused), Box2D 2.4\n"
    "  velocity iterations 2, 16 (position 3) and Box2D v3 substeps 2, 8 for\n"
    "  the error-against-cost charts. --size replaces the scene's size, --ticks its\n"
    "  timed ticks. --engine runs one engine alone (for profiling; both: every\n"
    "  engine built in). --threads N (2-31) also runs Rewind's defaults with its\n"
    "  pairs collided on N threads (settings \"... threads=N\": the same results).\n"
    "  Prints CSV on stdout, progress on stderr. Exit 0 on success, 1 if\n"
    "  an engine refused a scene, 2 on bad usage.\n";

#ifdef REWIND_HAVE_BOX2D3
constexpr bool kHaveBox2D3 = true;
#else
constexpr bool kHaveBox2D3 = false;
#endif

std::vector<std::unique_ptr<Engine2D>> engines(const Scene2D& scene, bool sweep,
                                               const std::string& which, uint32_t threads) {
  std::vector<std::unique_ptr<Engine2D>> e;
  const bool rewind = which == "rewind" || which == "both";
  // Box2D 2.4.1's revolute joints have no spring: it sits out such scenes.
  const bool box2d = (which == "box2d" || which == "both") && !scene.joint_springs;
  if ((which == "box2d" || which == "both") && scene.joint_springs) {
    std::fprintf(stderr, "scene2d: %s: Box2D 2.4 sits out (its revolute joints have no spring)\n",
                 scene.name.c_str());
  }
  for (int substeps : {4, 6, 8, 16}) {
    if (rewind && (sweep || substeps == 4)) {
      e.push_back(std::make_unique<Rewind2DEngine>(substeps, 1));
    }
  }
  if (rewind && threads > 1) e.push_back(std::make_unique<Rewind2DEngine>(4, 1, threads));
  for (int velocity : {2, 4, 8, 16}) {
    if (box2d && (sweep || velocity == 8)) e.push_back(std::make_unique<Box2DEngine>(velocity, 3));
  }
  if (box2d) {
    e.push_back(std::make_unique<Box2DEngine>(4, 2));
    // Without Box2D's continuous collision: how much of its step that is.
    e.push_back(std::make_unique<Box2DEngine>(8, 3, false));
  }
#ifdef REWIND_HAVE_BOX2D3
  for (int substeps : {2, 4, 8}) {
    if ((which == "box2d3" || which == "both") && (sweep || substeps == 4)) {
      e.push_back(std::make_unique<rwd::bench::Box2D3Engine>(substeps));
    }
  }
#endif
  return e;
}

const char* describe(const std::string& name) {
  if (name == "large_pyramid") {
    return "a pyramid of base N (N(N+1)/2 boxes of half size 0.5 m) on a static ground box";
  }
  if (name == "pyramids") return "N pyramids of base 10 (55 boxes each) side by side, 2 m apart";
  if (name == "joint_grid") {
    return "an N x N grid of circles (radius 0.4 m, 1 m apart) joined to their neighbours by "
           "revolute joints, hanging from 7 static circles of the top row";
  }
  if (name == "rain") {
    return "Box2D v3's rain: every 8 ticks a column of 25 ragdolls (11 capsules, 10 revolute "
           "joints with limits, springs and friction; no feet) drops onto 5 floors of 0.5 m "
           "boxes; N columns, then the oldest column is replaced";
  }
  if (name == "smash") {
    return "no gravity: a 4 m box at 40 m/s into a wall of N x 80 boxes of half size 0.2 m "
           "that start asleep";
  }
  return "a hollow 20 m box (4 walls, 1 m thick) turning at 0.05 pi rad/s about its centre, "
         "filled at once with N boxes of half size 0.125 m";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  int size = 0;
  int ticks = 0;
  bool sweep = false;
  std::string which = "both";
  uint32_t threads = 1;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strcmp(a, "--scene") == 0 && i + 1 < argc) {
      names.emplace_back(argv[++i]);
    } else if (std::strcmp(a, "--size") == 0 && i + 1 < argc) {
      size = std::atoi(argv[++i]);
    } else if (std::strcmp(a, "--ticks") == 0 && i + 1 < argc) {
      ticks = std::atoi(argv[++i]);
    } else if (std::strcmp(a, "--engine") == 0 && i + 1 < argc) {
      which = argv[++i];
      if (which == "box2d3" && !kHaveBox2D3) {
        std::fputs(
            "rewind-scene2d-sweep: built without Box2D v3: configure with "
            "-DREWIND_BOX2D3_DIR=<Box2D v3 source tree>\n",
            stderr);
        return 2;
      }
      if (which != "rewind" && which != "box2d" && which != "box2d3" && which != "both") {
        std::fputs(kUsage, stderr);
        return 2;
      }
    } else if (std::strcmp(a, "--threads") == 0 && i + 1 < argc) {
      const char* v = argv[++i];
      char* end = nullptr;
      const long n = std::strtol(v, &end, 10);
      if (end == v || *end != '\0' || n < 2 || n > 31) {
        std::fprintf(stderr, "rewind-scene2d-sweep: --threads must be 2 to 31, not '%s'\n", v);
        return 2;
      }
      threads = static_cast<uint32_t>(n);
    } else if (std::strcmp(a, "--sweep") == 0) {
      sweep = true;
    } else if (std::strcmp(a, "--list") == 0) {
      for (const auto& n : rwd::bench::scene2d_names())
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
  if (names.empty()) names = rwd::bench::scene2d_names();

  std::printf(
      "scene,size,bodies,engine,settings,default,warmup_ticks,timed_ticks,ms_per_step,"
      "top_drift_m,top_peak_m,max_displacement_m,max_opening_m,escaped,checksum\n");
  int status = 0;
  for (const std::string& name : names) {
    Scene2D scene;
    if (!rwd::bench::make_scene2d(name, size, scene)) {
      std::fprintf(stderr, "rewind-scene2d-sweep: unknown scene '%s'\n", name.c_str());
      return 2;
    }
    if (ticks > 0) scene.timed_ticks = ticks;
    std::fprintf(stderr, "scene2d: %s %d (%zu bodies, %d + %d ticks)\n", name.c_str(), scene.size,
                 scene.bodies.size(), scene.warmup_ticks, scene.timed_ticks);
    const auto e = engines(scene, sweep, which, threads);
    const auto results = rwd::bench::run_lockstep(scene, e);
    for (size_t k = 0; k < e.size(); ++k) {
      const auto& r = results[k];
      if (!r.error.empty()) {
        std::fprintf(stderr, "scene2d: %s\n", r.error.c_str());
        status = 1;
        continue;
      }
      std::printf("%s,%d,%zu,%s,%s,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%d,%016llx\n", name.c_str(),
                  scene.size, scene.bodies.size(), e[k]->name().c_str(), e[k]->settings().c_str(),
                  e[k]->is_default() ? 1 : 0, scene.warmup_ticks, scene.timed_ticks, r.ms_per_step,
                  r.top_drift_m, r.top_peak_m, r.max_displacement_m, r.max_opening_m, r.escaped,
                  static_cast<unsigned long long>(r.checksum));
      std::fprintf(stderr, "scene2d:   %-6s %-22s %8.3f ms/step\n", e[k]->name().c_str(),
                   e[k]->settings().c_str(), r.ms_per_step);
    }
    std::fflush(stdout);
  }
  return status;
}
