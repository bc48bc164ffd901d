// SPDX-License-Identifier: MIT
// rewind-scene-sweep: runs the scene catalogue on Rewind and Bullet (and
// Jolt, when built with it: REWIND_JOLT_DIR) over a grid of solver
// settings and prints one CSV row per (run, metric) on stdout, with
// progress on stderr. scripts/charts.sh turns the rows into charts and
// docs/BENCHMARKS.md.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "bullet_engine.h"
#ifdef REWIND_HAVE_JOLT
#include "jolt_engine.h"
#endif
#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"
#include "rewind/tune/csv.h"
#include "rewind/tune/solver_setting.h"

namespace {

using rwd::bench::BulletEngine;
using rwd::bench::BulletSettings;
using rwd::scenes::Engine;
using rwd::scenes::RewindEngine;
using rwd::scenes::SceneEntry;
using rwd::scenes::SceneResult;
using rwd::tune::csv_quoted;
using rwd::tune::SolverSetting;

constexpr const char* kUsage =
    "usage: rewind-scene-sweep [--mode defaults|quick|full]\n"
    "                          [--engine rewind|bullet|both|jolt|all]\n"
    "                          [--scene NAME]... [--size N]... [--no-sleep]\n"
    "                          [--threads N] [--list]\n"
    "  Runs every scene of the catalogue (or the --scene ones) at its sizes (or\n"
    "  the --size ones) on Rewind and Bullet (both, the default) at their\n"
    "  default settings; quick and full also sweep the solver settings at each\n"
    "  scene's chart size. quick skips scenes of more than 2100 bodies (piles\n"
    "  over 2000 boxes) and sweeps fewer settings. jolt and all (Rewind,\n"
    "  Bullet and Jolt) need a build configured with -DREWIND_JOLT_DIR=...\n"
    "  Prints CSV on stdout, progress on stderr. Exit 0 on success (failing\n"
    "  criteria are data, not errors), 2 on bad usage. --no-sleep keeps every\n"
    "  body awake in every engine (the cost of the solver itself). --threads N\n"
    "  (2-31) also runs Rewind's defaults stepping on N threads (settings\n"
    "  \"... threads=N\"; the same results, so only the time differs).\n";

#ifdef REWIND_HAVE_JOLT
constexpr bool kHaveJolt = true;
#else
constexpr bool kHaveJolt = false;
#endif

struct Setting {
  std::string engine;
  bool is_default = false;
  std::function<std::unique_ptr<Engine>()> make;
};

Setting rewind_setting(bool sleep, int substeps, int relax, float hertz, uint32_t threads = 1) {
  rwd::sim::WorldConfig c;
  c.enable_sleep = sleep;
  const SolverSetting s{substeps, relax, hertz};
  const bool is_default = s == SolverSetting::of(c) && threads == 1;
  c = s.applied_to(c);
  return {"rewind", is_default,
          [c, threads] { return std::make_unique<RewindEngine>(c, threads); }};
}

Setting bullet_setting(bool sleep, int iterations, int substeps) {
  const BulletSettings d;
  BulletSettings s{iterations, substeps, sleep};
  const bool is_default = iterations == d.iterations && substeps == d.substeps;
  return {"bullet", is_default, [s] { return std::make_unique<BulletEngine>(s); }};
}

#ifdef REWIND_HAVE_JOLT
Setting jolt_setting(bool sleep, int velocity_iterations, int collision_steps) {
  const rwd::bench::JoltSettings d;
  rwd::bench::JoltSettings s;
  s.sleep = sleep;
  s.velocity_iterations = velocity_iterations;
  s.collision_steps = collision_steps;
  const bool is_default =
      velocity_iterations == d.velocity_iterations && collision_steps == d.collision_steps;
  return {"jolt", is_default, [s] { return std::make_unique<rwd::bench::JoltEngine>(s); }};
}
#endif

// Rewind's defaults, the centre of every sweep.
const rwd::sim::WorldConfig kRewindDefaults{};

Setting rewind_default(bool sleep, uint32_t threads = 1) {
  return rewind_setting(sleep, kRewindDefaults.substeps, kRewindDefaults.relax_iterations,
                        kRewindDefaults.contact_hertz, threads);
}

// The non-default settings swept at each scene's chart size: one knob at a
// time away from the defaults.
std::vector<Setting> sweep_settings(bool full, bool sleep) {
  const int sub = kRewindDefaults.substeps;
  const int relax = kRewindDefaults.relax_iterations;
  const float hertz = kRewindDefaults.contact_hertz;
  std::vector<Setting> s;
  const std::vector<int> substeps = full ? std::vector<int>{5, 6, 8, 16} : std::vector<int>{6, 8};
  for (int n : substeps) {
    if (n != sub) s.push_back(rewind_setting(sleep, n, relax, hertz));
  }
  if (full) {
    for (int r : {0, 1, 2, 4}) {
      if (r != relax) s.push_back(rewind_setting(sleep, sub, r, hertz));
    }
    for (float hz : {15.0f, 60.0f}) s.push_back(rewind_setting(sleep, sub, relax, hz));
  }
  const std::vector<int> iterations = full ? std::vector<int>{5, 20, 40} : std::vector<int>{5, 20};
  for (int it : iterations) s.push_back(bullet_setting(sleep, it, 1));
  if (full) {
    for (int n : {2, 4}) s.push_back(bullet_setting(sleep, 10, n));
  }
#ifdef REWIND_HAVE_JOLT
  // Jolt like Bullet: velocity iterations, then collision steps per tick.
  for (int it : iterations) s.push_back(jolt_setting(sleep, it, 1));
  if (full) {
    for (int n : {2, 4}) s.push_back(jolt_setting(sleep, 10, n));
  }
#endif
  return s;
}

void print_row(const SceneResult& r, bool is_default) {
  if (!r.error.empty()) {
    std::printf("%s,%d,%s,%s,%u,%d,,error,,,,,0,%d,%s\n", r.scene.c_str(), r.size, r.engine.c_str(),
                r.settings.c_str(), r.bodies, r.ticks, is_default ? 1 : 0,
                csv_quoted(r.error).c_str());
    return;
  }
  for (const auto& m : r.metrics) {
    std::printf("%s,%d,%s,%s,%u,%d,%.6g,%s,%s,%.6g,%s,%.6g,%d,%d,%s\n", r.scene.c_str(), r.size,
                r.engine.c_str(), r.settings.c_str(), r.bodies, r.ticks, r.ms_per_step,
                m.name.c_str(), m.unit.c_str(), m.value,
                m.bound == rwd::scenes::Metric::Bound::kAtMost ? "at_most" : "at_least", m.limit,
                m.pass() ? 1 : 0, is_default ? 1 : 0, csv_quoted(m.criterion).c_str());
  }
  std::fflush(stdout);
}

bool wanted(const std::vector<std::string>& list, std::string_view value) {
  if (list.empty()) return true;
  for (const auto& v : list) {
    if (v == value) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mode = "quick";
  std::string engines = "both";
  std::vector<std::string> scene_names;
  std::vector<int> sizes;
  bool sleep = true;
  int threads = 1;
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "rewind-scene-sweep: %s needs a value\n%s", argv[i], kUsage);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--mode") {
      mode = value();
    } else if (a == "--engine") {
      engines = value();
    } else if (a == "--scene") {
      scene_names.emplace_back(value());
    } else if (a == "--size") {
      sizes.push_back(std::atoi(value()));
    } else if (a == "--no-sleep") {
      sleep = false;
    } else if (a == "--threads") {
      const char* v = value();
      char* end = nullptr;
      const long n = std::strtol(v, &end, 10);
      if (end == v || *end != '\0' || n < 2 || n > 31) {
        std::fprintf(stderr, "rewind-scene-sweep: --threads must be 2 to 31, not '%s'\n", v);
        return 2;
      }
      threads = static_cast<int>(n);
    } else if (a == "--list") {
      for (const SceneEntry& e : rwd::scenes::scene_catalog()) {
        std::printf("%.*s: %.*s\n", static_cast<int>(e.name.size()), e.name.data(),
                    static_cast<int>(e.description.size()), e.description.data());
      }
      return 0;
    } else if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fprintf(stderr, "rewind-scene-sweep: unknown option '%s'\n%s", argv[i], kUsage);
      return 2;
    }
  }
  if (mode != "defaults" && mode != "quick" && mode != "full") {
    std::fprintf(stderr, "rewind-scene-sweep: --mode must be defaults, quick or full\n");
    return 2;
  }
  if (engines != "rewind" && engines != "bullet" && engines != "both" && engines != "jolt" &&
      engines != "all") {
    std::fprintf(stderr,
                 "rewind-scene-sweep: --engine must be rewind, bullet, both, jolt or all\n");
    return 2;
  }
  if (!kHaveJolt && (engines == "jolt" || engines == "all")) {
    std::fprintf(stderr,
                 "rewind-scene-sweep: built without Jolt: configure with "
                 "-DREWIND_JOLT_DIR=<Jolt source tree> (cmake --preset bench)\n");
    return 2;
  }
  for (const auto& n : scene_names) {
    bool known = false;
    for (const SceneEntry& e : rwd::scenes::scene_catalog()) known = known || e.name == n;
    if (!known) {
      std::fprintf(stderr, "rewind-scene-sweep: unknown scene '%s' (see --list)\n", n.c_str());
      return 2;
    }
  }

  struct Job {
    const SceneEntry* entry;
    int size;
    Setting setting;
  };
  std::vector<Job> jobs;
  std::vector<Setting> defaults = {rewind_default(sleep), bullet_setting(sleep, 10, 1)};
  if (threads > 1) defaults.push_back(rewind_default(sleep, static_cast<uint32_t>(threads)));
#ifdef REWIND_HAVE_JOLT
  defaults.push_back(jolt_setting(sleep, 10, 1));
#endif
  const std::vector<Setting> swept =
      mode == "defaults" ? std::vector<Setting>{} : sweep_settings(mode == "full", sleep);
  // both: Rewind and Bullet, the peers every build has; all: every engine built in.
  auto engine_wanted = [&](const Setting& s) {
    return engines == "all" || (engines == "both" && s.engine != "jolt") || engines == s.engine;
  };
  for (const SceneEntry& e : rwd::scenes::scene_catalog()) {
    if (!wanted(scene_names, e.name)) continue;
    const std::vector<int>& scene_sizes = sizes.empty() ? e.sizes : sizes;
    for (int size : scene_sizes) {
      auto probe = e.make(size);
      if (!probe) {
        std::fprintf(stderr, "rewind-scene-sweep: %.*s cannot take size %d\n",
                     static_cast<int>(e.name.size()), e.name.data(), size);
        return 2;
      }
      if (mode == "quick" && probe->body_capacity() > 2100) continue;
      for (const Setting& s : defaults) {
        if (engine_wanted(s)) jobs.push_back({&e, size, s});
      }
      if (size != e.chart_size) continue;
      for (const Setting& s : swept) {
        if (engine_wanted(s)) jobs.push_back({&e, size, s});
      }
    }
  }

  std::printf(
      "scene,size,engine,settings,bodies,ticks,ms_per_step,metric,unit,value,bound,limit,pass,"
      "default,criterion\n");
  for (size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    auto scene = job.entry->make(job.size);
    auto engine = job.setting.make();
    std::fprintf(stderr, "[%zu/%zu] %.*s %d %s %s ...", j + 1, jobs.size(),
                 static_cast<int>(job.entry->name.size()), job.entry->name.data(), job.size,
                 engine->name().c_str(), engine->settings().c_str());
    std::fflush(stderr);
    const SceneResult r = rwd::scenes::run_scene(*scene, *engine);
    if (!r.error.empty()) {
      std::fprintf(stderr, " error: %s\n", r.error.c_str());
    } else {
      std::fprintf(stderr, " %.3f ms/step, %s\n", r.ms_per_step, r.pass() ? "pass" : "FAIL");
    }
    print_row(r, job.setting.is_default);
  }
  return 0;
}
