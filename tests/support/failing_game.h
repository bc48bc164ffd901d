// SPDX-License-Identifier: MIT
#pragma once
// A game whose rules return an error where a test says: at build, in
// apply_inputs or after_step on one tick, or in apply_inputs whenever
// player 0's axis_x is a trigger value. Everything else is one ball on the
// 3D lane and a step counter.
#include <memory>

#include "rewind/game/game_on.h"
#include "rewind/sim/world3d.h"

namespace rwd::test {

struct FailingGameState {
  uint32_t steps = 0;
};

class FailingGame final : public game::GameWithState<sim::World3D, FailingGameState> {
 public:
  enum class Where { kNowhere, kBuild, kApply, kAfterStep, kApplyOnTrigger };
  static constexpr int16_t kTrigger = 777;  ///< axis_x of player 0 that fails kApplyOnTrigger

  FailingGame(Where where, Tick tick) : where_(where), tick_(tick) {}
  std::string_view name() const override { return "failing"; }
  uint32_t rules_version() const override { return 1; }
  sim::WorldConfig world_config() const override { return {}; }

 protected:
  Status build_typed(const game::MatchSetup&, sim::World3D& world,
                     FailingGameState&) const override {
    sim::BodyDef ball;
    // A negative radius: the world refuses the body, and build passes that on.
    ball.shape = sim::Shape::make_sphere(where_ == Where::kBuild ? -1.0f : 0.5f);
    if (Result<sim::BodyId> id = world.create_body(ball); !id.ok()) return id.status();
    return Status::Ok();
  }
  Status apply_typed(Tick tick, std::span<const StickInput> inputs, sim::World3D&,
                     FailingGameState&) const override {
    if ((where_ == Where::kApply && tick == tick_) ||
        (where_ == Where::kApplyOnTrigger && !inputs.empty() && inputs[0].axis_x == kTrigger)) {
      return Status::Error(ErrorCode::kCorrupt, "score table out of range");
    }
    return Status::Ok();
  }
  Status after_step_typed(Tick tick, sim::World3D&, FailingGameState& state) const override {
    ++state.steps;
    if (where_ == Where::kAfterStep && tick == tick_) {
      return Status::Error(ErrorCode::kNotFound, "the flag's body is gone");
    }
    return Status::Ok();
  }
  void hash_typed(const FailingGameState& state, StateHasher& hasher) const override {
    hasher.add_u32(state.steps);
  }
  Status validate_typed(const game::MatchSetup&, const FailingGameState&) const override {
    return Status::Ok();
  }

 private:
  Where where_;
  Tick tick_;
};

}  // namespace rwd::test
