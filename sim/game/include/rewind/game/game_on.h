// SPDX-License-Identifier: MIT
#pragma once
// Bases for games written against one concrete world type. They turn the
// lane-neutral Game calls into calls with the typed world, once per tick.
#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rewind/game/game.h"
#include "rewind/game/world_lane.h"

namespace rwd::game {

/// A game whose world is a `World` (e.g. sim::World3D), run by a
/// WorldLane<World>. Besides what WorldLane needs, `World` provides the
/// config codec: static encode_config(const Config&, out),
/// decode_config(bytes) -> Result<Config> and describe_config(const Config&).
template <class World>
class GameOn : public Game {
 public:
  using Config = typename WorldLane<World>::Config;

  /// World tuning this game runs with.
  virtual Config world_config() const = 0;

  std::unique_ptr<Lane> make_lane() const final {
    return std::make_unique<WorldLane<World>>(world_config());
  }
  bool accepts_lane(const Lane& lane) const final { return world_of<World>(lane) != nullptr; }
  void encode_world_config(std::vector<uint8_t>& out) const final {
    World::encode_config(world_config(), out);
  }
  Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
      std::span<const uint8_t> bytes) const final {
    Result<Config> config = World::decode_config(bytes);
    if (!config.ok()) return config.status();
    return World::describe_config(*config);
  }
  Status build(const MatchSetup& setup, Lane& lane, std::span<std::byte> state) const final {
    return build_world(setup, world_in(lane), state);
  }
  Status apply_inputs(Tick tick, std::span<const PlayerInput> inputs, Lane& lane,
                      std::span<std::byte> state) const final {
    return apply_world(tick, inputs, world_in(lane), state);
  }
  Status after_step(Tick tick, Lane& lane, std::span<std::byte> state) const final {
    return after_step_world(tick, world_in(lane), state);
  }

 protected:
  virtual Status build_world(const MatchSetup& setup, World& world,
                             std::span<std::byte> state) const = 0;
  virtual Status apply_world(Tick tick, std::span<const PlayerInput> inputs, World& world,
                             std::span<std::byte> state) const = 0;
  virtual Status after_step_world(Tick tick, World& world, std::span<std::byte> state) const = 0;

 private:
  // Simulation only hands a game the lane its make_lane() type made, so the
  // cast needs no check on the per-tick path.
  static World& world_in(Lane& lane) { return static_cast<WorldLane<World>&>(lane).world(); }
};

/// Convenience base for games whose state is one trivially copyable struct
/// and whose input is one struct `Input` (StickInput unless the game names
/// its own; a game with its own Input also overrides Game::input_spec() to
/// describe it, with the same size).
template <class World, class State, InputLayout Input = StickInput>
class GameWithState : public GameOn<World> {
  static_assert(std::is_trivially_copyable_v<State>, "game state must be trivially copyable");

 public:
  size_t state_size() const final { return sizeof(State); }
  void hash_state(std::span<const std::byte> state, rwd::StateHasher& hasher) const final {
    hash_typed(load(state), hasher);
  }
  Status validate_state(const MatchSetup& setup, std::span<const std::byte> state) const final {
    if (state.size() != sizeof(State)) {
      return Status::Error(ErrorCode::kCorrupt, "game state block has the wrong size");
    }
    return validate_typed(setup, load(state));
  }

 protected:
  // Game's build(), apply_inputs() and after_step() on the typed world and
  // state; what they change in `state` is kept even when they fail.
  virtual Status build_typed(const MatchSetup& setup, World& world, State& state) const = 0;
  virtual Status apply_typed(Tick tick, std::span<const Input> inputs, World& world,
                             State& state) const = 0;
  virtual Status after_step_typed(Tick tick, World& world, State& state) const = 0;
  virtual void hash_typed(const State& state, rwd::StateHasher& hasher) const = 0;
  virtual Status validate_typed(const MatchSetup& setup, const State& state) const = 0;

 private:
  Status build_world(const MatchSetup& setup, World& world,
                     std::span<std::byte> state) const final {
    if (this->input_spec().size != sizeof(Input)) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "input_spec() declares " + std::to_string(this->input_spec().size) +
                               " bytes, but the game's Input struct has " +
                               std::to_string(sizeof(Input)));
    }
    State s{};
    Status status = build_typed(setup, world, s);
    store(s, state);
    return status;
  }
  Status apply_world(Tick tick, std::span<const PlayerInput> inputs, World& world,
                     std::span<std::byte> state) const final {
    std::array<Input, kMaxPlayers> typed;
    const size_t count = std::min(inputs.size(), typed.size());
    for (size_t p = 0; p < count; ++p) typed[p] = inputs[p].template as<Input>();
    State s = load(state);
    Status status = apply_typed(tick, std::span<const Input>(typed.data(), count), world, s);
    store(s, state);
    return status;
  }
  Status after_step_world(Tick tick, World& world, std::span<std::byte> state) const final {
    State s = load(state);
    Status status = after_step_typed(tick, world, s);
    store(s, state);
    return status;
  }
  static State load(std::span<const std::byte> bytes) {
    State s;
    std::memcpy(&s, bytes.data(), sizeof(State));
    return s;
  }
  static void store(const State& s, std::span<std::byte> bytes) {
    std::memcpy(bytes.data(), &s, sizeof(State));
  }
};

}  // namespace rwd::game
