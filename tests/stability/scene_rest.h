// SPDX-License-Identifier: MIT
#pragma once
// How long a catalogue scene takes to fall asleep on Rewind at default
// settings (sleep on, as a game runs).
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace rwd::scenes::test {

/// Builds scene `name` of `size` and steps it until every body sleeps:
/// the number of ticks that took, or -1 when bodies are still awake after
/// `max_ticks` (their number in `awake`). A scene that cannot be built
/// fails the calling test and gives -1.
inline int ticks_until_asleep(const char* name, int size, int max_ticks, uint32_t& awake) {
  std::unique_ptr<Scene> scene = make_scene(name, size);
  EXPECT_NE(scene, nullptr) << name << " " << size;
  awake = 0;
  if (scene == nullptr) return -1;
  RewindEngine engine;
  engine.reset(scene->world(), scene->body_capacity());
  std::string error;
  const bool built = scene->build(engine, error);
  EXPECT_TRUE(built) << error;
  if (!built) return -1;
  for (int t = 1; t <= max_ticks; ++t) {
    engine.step();
    if (engine.awake_count() == 0) return t;
  }
  awake = engine.awake_count();
  return -1;
}

}  // namespace rwd::scenes::test
