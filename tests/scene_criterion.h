// SPDX-License-Identifier: MIT
#pragma once
// Runs catalogue scenes on Rewind at default settings and checks one
// criterion each. Each scene runs once per test binary; its criteria share
// the result.
#include <gtest/gtest.h>

#include <map>
#include <ostream>
#include <string>
#include <utility>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace rwd::scenes::test {

/// One criterion of one scene that holds at default settings.
struct Criterion {
  const char* scene;
  int size;
  const char* metric;
};

inline void PrintTo(const Criterion& c, std::ostream* os) {
  *os << c.scene << "/" << c.size << "/" << c.metric;
}

inline std::string criterion_name(const ::testing::TestParamInfo<Criterion>& info) {
  return std::string(info.param.scene) + "_" + std::to_string(info.param.size) + "_" +
         info.param.metric;
}

/// The result of `scene` at `size` on Rewind with a default WorldConfig.
inline const SceneResult& default_run(const std::string& scene, int size) {
  static std::map<std::pair<std::string, int>, SceneResult> runs;
  auto key = std::make_pair(scene, size);
  auto it = runs.find(key);
  if (it != runs.end()) return it->second;
  SceneResult r;
  if (auto s = make_scene(scene, size)) {
    RewindEngine engine;
    r = run_scene(*s, engine);
  } else {
    r.error = "no such scene or size";
  }
  return runs.emplace(key, std::move(r)).first->second;
}

inline void expect_criterion(const Criterion& c) {
  const SceneResult& r = default_run(c.scene, c.size);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const Metric* m = r.metric(c.metric);
  ASSERT_NE(m, nullptr) << "scene " << c.scene << " has no metric " << c.metric;
  EXPECT_TRUE(m->pass()) << c.scene << " " << c.size << ": " << m->criterion << "\n  measured "
                         << m->name << " = " << m->value << " " << m->unit << ", limit "
                         << (m->bound == Metric::Bound::kAtMost ? "<= " : ">= ") << m->limit;
}

}  // namespace rwd::scenes::test
