// SPDX-License-Identifier: MIT
#pragma once
// The seam between the engine and a game's rules. A Game is stateless logic:
// everything that must roll back lives in the World3D and in the game's own
// state block, which Simulation snapshots and checksums with the world.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>

#include "rewind/game/player_input.h"
#include "rewind/sim/state_hasher.h"
#include "rewind/sim/tick.h"
#include "rewind/sim/world3d.h"

namespace rwd::game {

/// What a match is created from; every client and the server must agree.
struct MatchSetup {
  uint32_t player_count = 2;  ///< [1, kMaxPlayers]
  uint64_t seed = 1;          ///< seeds the game's deterministic RNG
};

inline constexpr uint32_t kMaxPlayers = 32;

class Game {
 public:
  virtual ~Game() = default;
  /// Registry name, e.g. "crates".
  virtual std::string_view name() const = 0;
  /// Revision of the game's rules: raised whenever a change to the rules,
  /// the scene or the state block can alter a result for the same inputs.
  /// Replays record it next to sim::kSimRevision.
  virtual uint32_t rules_version() const = 0;
  /// World tuning this game runs with.
  virtual sim::WorldConfig world_config() const = 0;
  /// Size in bytes of the game's state block (trivially copyable data).
  virtual size_t state_size() const = 0;
  /// Builds the scene and initializes the zeroed state block.
  virtual void build(const MatchSetup& setup, sim::World3D& world,
                     std::span<std::byte> state) const = 0;
  /// Applies one tick of inputs (one per player, index = player slot)
  /// before the world steps.
  virtual void apply_inputs(Tick tick, std::span<const PlayerInput> inputs, sim::World3D& world,
                            std::span<std::byte> state) const = 0;
  /// Runs after the world stepped (scoring, respawns); may read events.
  virtual void after_step(Tick tick, sim::World3D& world, std::span<std::byte> state) const = 0;
  /// Feeds the canonical fields of the state block to the hasher.
  virtual void hash_state(std::span<const std::byte> state, sim::StateHasher& hasher) const = 0;
  /// Checks a state block that arrived from outside (a resync snapshot, a
  /// desync dump) before it is used: counts, indices and ranges the rules
  /// rely on. Returns kCorrupt naming the bad field.
  virtual Status validate_state(const MatchSetup& setup,
                                std::span<const std::byte> state) const = 0;
};

/// Convenience base for games whose state is one trivially copyable struct.
template <class State>
class GameWithState : public Game {
  static_assert(std::is_trivially_copyable_v<State>, "game state must be trivially copyable");

 public:
  size_t state_size() const final { return sizeof(State); }
  void build(const MatchSetup& setup, sim::World3D& world, std::span<std::byte> state) const final {
    State s{};
    build_typed(setup, world, s);
    store(s, state);
  }
  void apply_inputs(Tick tick, std::span<const PlayerInput> inputs, sim::World3D& world,
                    std::span<std::byte> state) const final {
    State s = load(state);
    apply_typed(tick, inputs, world, s);
    store(s, state);
  }
  void after_step(Tick tick, sim::World3D& world, std::span<std::byte> state) const final {
    State s = load(state);
    after_step_typed(tick, world, s);
    store(s, state);
  }
  void hash_state(std::span<const std::byte> state, sim::StateHasher& hasher) const final {
    hash_typed(load(state), hasher);
  }
  Status validate_state(const MatchSetup& setup, std::span<const std::byte> state) const final {
    if (state.size() != sizeof(State)) {
      return Status::Error(ErrorCode::kCorrupt, "game state block has the wrong size");
    }
    return validate_typed(setup, load(state));
  }

 protected:
  virtual void build_typed(const MatchSetup& setup, sim::World3D& world, State& state) const = 0;
  virtual void apply_typed(Tick tick, std::span<const PlayerInput> inputs, sim::World3D& world,
                           State& state) const = 0;
  virtual void after_step_typed(Tick tick, sim::World3D& world, State& state) const = 0;
  virtual void hash_typed(const State& state, sim::StateHasher& hasher) const = 0;
  virtual Status validate_typed(const MatchSetup& setup, const State& state) const = 0;

 private:
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
