// SPDX-License-Identifier: MIT
#pragma once
// A catalogue scene as a tuning target: each run builds the scene afresh on
// Rewind with the setting applied to a default WorldConfig (sleeping on, as
// in rewind-scene-sweep), and the scene measures its own metrics with its
// own criteria as limits.
#include <memory>
#include <string>

#include "rewind/core/status.h"
#include "rewind/sim/world_config.h"
#include "rewind/tune/tune_target.h"

namespace rwd::tune {

class SceneTarget final : public TuneTarget {
 public:
  /// The catalogue scene `name` at `size`; size 0 picks the scene's chart
  /// size (the size rewind-scene-sweep sweeps). kInvalidArgument for an
  /// unknown name (listing the catalogue) or a size the scene cannot take.
  /// `sleep` false keeps every body awake (the solver alone must hold).
  static Result<std::unique_ptr<SceneTarget>> create(const std::string& name, int size,
                                                     bool sleep = true);

  std::string kind() const override { return "scene"; }
  std::string name() const override { return name_; }
  int size() const override { return size_; }
  std::string description() const override;
  SolverSetting default_setting() const override;
  Tick ticks() const override { return ticks_; }
  Measurement measure(const SolverSetting& setting) override;

 private:
  SceneTarget(std::string name, int size, std::string what, Tick ticks, bool sleep);

  std::string name_;
  int size_;
  std::string what_;  // the catalogue's description
  Tick ticks_;
  sim::WorldConfig base_;  // defaults, with sleeping as asked
};

}  // namespace rwd::tune
