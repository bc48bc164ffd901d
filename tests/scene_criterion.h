// SPDX-License-Identifier: MIT
#pragma once
// Runs catalogue scenes on Rewind at default settings and checks one
// criterion each. Each scene runs once per test binary; its criteria share
// the result.
#include <gtest/gtest.h>

#include <map>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace rwd::scenes::test {

/// Solver settings other than the defaults (zero: keep the default).
struct Tuned {
  int substeps = 0;
  int relax_iterations = -1;
  float contact_hertz = 0.0f;
};

/// One criterion of one scene that holds at default settings, or at the
/// `tuned` ones (the settings rewind-tune recommends for that scene).
struct Criterion {
  const char* scene;
  int size;
  const char* metric;
  Tuned tuned{};
};

inline sim::WorldConfig config_of(const Tuned& t) {
  sim::WorldConfig c;
  if (t.substeps > 0) c.substeps = t.substeps;
  if (t.relax_iterations >= 0) c.relax_iterations = t.relax_iterations;
  if (t.contact_hertz > 0.0f) c.contact_hertz = t.contact_hertz;
  return c;
}

inline void PrintTo(const Criterion& c, std::ostream* os) {
  *os << c.scene << "/" << c.size << "/" << c.metric;
  if (c.tuned.substeps > 0) *os << " (tuned)";
}

inline std::string criterion_name(const ::testing::TestParamInfo<Criterion>& info) {
  return std::string(info.param.scene) + "_" + std::to_string(info.param.size) + "_" +
         info.param.metric + (info.param.tuned.substeps > 0 ? "_tuned" : "");
}

/// The result of `scene` at `size` on Rewind with a default WorldConfig (or
/// the tuned settings), run once per test binary.
inline const SceneResult& default_run(const std::string& scene, int size, const Tuned& tuned) {
  static std::map<std::tuple<std::string, int, int, int, float>, SceneResult> runs;
  auto key =
      std::make_tuple(scene, size, tuned.substeps, tuned.relax_iterations, tuned.contact_hertz);
  auto it = runs.find(key);
  if (it != runs.end()) return it->second;
  SceneResult r;
  if (auto s = make_scene(scene, size)) {
    RewindEngine engine(config_of(tuned));
    r = run_scene(*s, engine);
  } else {
    r.error = "no such scene or size";
  }
  return runs.emplace(key, std::move(r)).first->second;
}

inline void expect_criterion(const Criterion& c) {
  const SceneResult& r = default_run(c.scene, c.size, c.tuned);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const Metric* m = r.metric(c.metric);
  ASSERT_NE(m, nullptr) << "scene " << c.scene << " has no metric " << c.metric;
  EXPECT_TRUE(m->pass()) << c.scene << " " << c.size << ": " << m->criterion << "\n  measured "
                         << m->name << " = " << m->value << " " << m->unit << ", limit "
                         << (m->bound == Metric::Bound::kAtMost ? "<= " : ">= ") << m->limit;
}

}  // namespace rwd::scenes::test
