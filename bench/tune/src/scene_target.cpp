// SPDX-License-Identifier: MIT
#include "rewind/tune/scene_target.h"

#include "rewind/scenes/rewind_engine.h"
#include "rewind/sim/world3d.h"

namespace rwd::tune {

Result<std::unique_ptr<SceneTarget>> SceneTarget::create(const std::string& name, int size,
                                                         bool sleep) {
  const scenes::SceneEntry* entry = nullptr;
  std::string known;
  for (const scenes::SceneEntry& e : scenes::scene_catalog()) {
    if (e.name == name) entry = &e;
    if (!known.empty()) known += ", ";
    known += e.name;
  }
  if (entry == nullptr) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "unknown scene '" + name + "' (scenes: " + known + ")");
  }
  if (size == 0) size = entry->chart_size;
  const std::unique_ptr<scenes::Scene> probe = entry->make(size);
  if (!probe) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "scene " + name + " cannot take size " + std::to_string(size));
  }
  return std::unique_ptr<SceneTarget>(
      new SceneTarget(name, size, std::string(entry->description), probe->ticks(), sleep));
}

SceneTarget::SceneTarget(std::string name, int size, std::string what, Tick ticks, bool sleep)
    : name_(std::move(name)), size_(size), what_(std::move(what)), ticks_(ticks) {
  base_.enable_sleep = sleep;
}

std::string SceneTarget::description() const {
  return "scene " + name_ + " " + std::to_string(size_) + " (" + what_ + "), " +
         std::to_string(ticks_) + " ticks per run" +
         (base_.enable_sleep ? "" : ", every body kept awake") +
         "; ms/step is the world's step alone";
}

SolverSetting SceneTarget::default_setting() const {
  return SolverSetting::of(base_);
}

Measurement SceneTarget::measure(const SolverSetting& setting) {
  const sim::WorldConfig config = setting.applied_to(base_);
  if (const auto s = sim::World3D::validate_config(config); !s.ok()) {
    return {0.0, {}, "refused: " + s.message()};
  }
  std::unique_ptr<scenes::Scene> scene = scenes::make_scene(name_, size_);
  scenes::RewindEngine engine(config);
  const scenes::SceneResult r = scenes::run_scene(*scene, engine);
  return {r.ms_per_step, r.metrics, r.error};
}

}  // namespace rwd::tune
