// SPDX-License-Identifier: MIT
#pragma once
// A scene: bodies, world, a number of ticks, scripted actions, and the error
// metrics it measures on itself with their pass criteria. Scenes are shared
// by the stability and accuracy suites, the benchmarks and the charts.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/tick.h"
#include "rewind/scenes/engine.h"

namespace rwd::scenes {

/// One measured error of a scene run, with its criterion.
struct Metric {
  enum class Bound : uint8_t { kAtMost, kAtLeast };
  std::string name;  ///< e.g. "apex_error_pct"
  std::string unit;  ///< e.g. "%", "mm", "s"
  double value = 0.0;
  Bound bound = Bound::kAtMost;
  double limit = 0.0;
  /// What the metric is and why the limit, in one sentence.
  std::string criterion;
  bool pass() const { return bound == Bound::kAtMost ? value <= limit : value >= limit; }
};

/// A scene instance of one size. Build it, then for each tick: before_step,
/// engine step, after_step; then read metrics(). A Scene object runs once.
class Scene {
 public:
  virtual ~Scene() = default;

  /// Catalogue name, e.g. "stack".
  virtual std::string_view name() const = 0;
  /// The size parameter it was made with (boxes, base width, ratio, ...).
  int size() const { return size_; }
  virtual WorldSpec world() const { return WorldSpec{}; }
  /// Ticks the scene runs for.
  virtual Tick ticks() const = 0;
  /// Upper bound on the bodies build() creates.
  virtual uint32_t body_capacity() const = 0;

  /// Creates the bodies. False (with a reason) if the engine refused one.
  virtual bool build(Engine& engine, std::string& error) = 0;
  /// Scripted actions (impulses, velocity changes) before tick `tick` is stepped.
  virtual void before_step(Tick tick, Engine& engine) {
    (void)tick;
    (void)engine;
  }
  /// Observes the world after tick `tick` (0-based) has been stepped.
  virtual void after_step(Tick tick, const Engine& engine) = 0;
  /// The wall time the engine's step of tick `tick` took, ms (called by
  /// run_scene just before after_step; scenes that judge cost use it).
  virtual void step_timed(Tick tick, double ms) {
    (void)tick;
    (void)ms;
  }
  /// The metrics, valid after the last after_step.
  virtual std::vector<Metric> metrics() const = 0;

 protected:
  explicit Scene(int size) : size_(size) {}

 private:
  int size_;
};

/// What a run of a scene on an engine measured.
struct SceneResult {
  std::string scene;
  int size = 0;
  std::string engine;
  std::string settings;
  uint32_t bodies = 0;
  Tick ticks = 0;
  double ms_per_step = 0.0;  ///< wall time of the engine's step() alone, averaged
  std::vector<Metric> metrics;
  std::string error;  ///< non-empty when the scene could not be built
  bool pass() const;
  /// The metric called `name`, or nullptr.
  const Metric* metric(std::string_view name) const;
};

/// Runs `scene` on `engine` from an empty world to its last tick.
SceneResult run_scene(Scene& scene, Engine& engine);

/// A catalogue entry: how to make a scene of a given size.
struct SceneEntry {
  std::string_view name;
  std::string_view description;
  /// Sizes the tables and the suites use.
  std::vector<int> sizes;
  /// The size whose error-versus-cost chart sweeps every setting.
  int chart_size = 0;
  std::unique_ptr<Scene> (*make)(int size);
};

/// Every scene, in a fixed order.
const std::vector<SceneEntry>& scene_catalog();
/// The scene `name` of `size`, or nullptr for an unknown name or a size the
/// scene cannot take.
std::unique_ptr<Scene> make_scene(std::string_view name, int size);

}  // namespace rwd::scenes
