// SPDX-License-Identifier: MIT
#pragma once
// A game with its own input: a car's steering, throttle and brake (CarInput,
// 4 bytes) and a predictor that lets go of the brake. The rules add each
// player's input to its total, so every input a step used shows in the
// state; one ball keeps the world non-empty.
#include <array>
#include <cstddef>
#include <cstdint>

#include "rewind/game/game_on.h"
#include "rewind/sim/world3d.h"

namespace rwd::test {

struct CarInput {
  int16_t steer = 0;     ///< [-500, 500]
  uint8_t throttle = 0;  ///< [0, 100]
  uint8_t brake = 0;     ///< [0, 1]
};

struct CarGameState {
  std::array<int64_t, game::kMaxPlayers> steer_total{};
  std::array<uint32_t, game::kMaxPlayers> brakes{};
};

inline PlayerInput release_brake(const PlayerInput& newest) {
  CarInput car = newest.as<CarInput>();
  car.brake = 0;
  return PlayerInput::of(car);
}

/// `size` other than 4 declares a spec that does not match CarInput.
class CarInputGame final : public game::GameWithState<sim::World3D, CarGameState, CarInput> {
 public:
  explicit CarInputGame(uint8_t size = sizeof(CarInput)) : spec_{kSpec} { spec_.size = size; }
  std::string_view name() const override { return "cars"; }
  uint32_t rules_version() const override { return 1; }
  sim::WorldConfig world_config() const override { return {}; }
  const InputSpec& input_spec() const override { return spec_; }

  static constexpr InputField kFields[] = {
      {"steer", InputFieldType::kI16, offsetof(CarInput, steer), -500, 500},
      {"throttle", InputFieldType::kU8, offsetof(CarInput, throttle), 0, 100},
      {"brake", InputFieldType::kU8, offsetof(CarInput, brake), 0, 1},
  };
  static constexpr InputSpec kSpec{"car", sizeof(CarInput), kFields, &release_brake};

 protected:
  Status build_typed(const game::MatchSetup&, sim::World3D& world, CarGameState&) const override {
    sim::BodyDef ball;
    ball.shape = sim::Shape::make_sphere(0.5f);
    if (Result<sim::BodyId> id = world.create_body(ball); !id.ok()) return id.status();
    return Status::Ok();
  }
  Status apply_typed(Tick, std::span<const CarInput> inputs, sim::World3D&,
                     CarGameState& state) const override {
    for (size_t p = 0; p < inputs.size(); ++p) {
      state.steer_total[p] += inputs[p].steer;
      state.brakes[p] += inputs[p].brake;
    }
    return Status::Ok();
  }
  Status after_step_typed(Tick, sim::World3D&, CarGameState&) const override {
    return Status::Ok();
  }
  void hash_typed(const CarGameState& state, StateHasher& hasher) const override {
    for (size_t p = 0; p < state.steer_total.size(); ++p) {
      hasher.add_u64(static_cast<uint64_t>(state.steer_total[p]));
      hasher.add_u32(state.brakes[p]);
    }
  }
  Status validate_typed(const game::MatchSetup&, const CarGameState&) const override {
    return Status::Ok();
  }

 private:
  InputSpec spec_;
};

}  // namespace rwd::test
