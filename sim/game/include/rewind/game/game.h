// SPDX-License-Identifier: MIT
#pragma once
// The seam between the engine and a game's rules. A Game is stateless logic
// over one lane: everything that must roll back lives in the lane's world
// and in the game's own state block, which Simulation snapshots and
// checksums with the world. Games written against a concrete world derive
// from GameOn<World> or GameWithState<World, State> (game_on.h); this
// interface is what Simulation, and so the server and the tools, see.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rewind/core/input_spec.h"
#include "rewind/core/player_input.h"
#include "rewind/core/state_hasher.h"
#include "rewind/core/status.h"
#include "rewind/core/stick_input.h"
#include "rewind/core/tick.h"
#include "rewind/game/lane.h"

namespace rwd::game {

/// What a match is created from; every client and the server must agree.
struct MatchSetup {
  uint32_t player_count = 2;  ///< [1, kMaxPlayers]
  uint64_t seed = 1;          ///< seeds the game's deterministic RNG
};

inline constexpr uint32_t kMaxPlayers = 32;

/// Game::bot_input()'s default, a pure function of its arguments. For the
/// stick input (stick_input_spec()): a direction drawn at random every 40
/// ticks, with a rare jump (button bit 0) or dash (bit 1). For any other
/// spec: every field drawn from its range every 20 ticks (random_input()).
PlayerInput random_bot_input(const InputSpec& spec, uint64_t seed, uint32_t player, Tick tick);

class Game {
 public:
  virtual ~Game() = default;
  /// Registry name, e.g. "crates".
  virtual std::string_view name() const = 0;
  /// Revision of the game's rules: raised whenever a change to the rules,
  /// the scene or the state block can alter a result for the same inputs.
  /// Replays record it next to sim::kSimRevision.
  virtual uint32_t rules_version() const = 0;
  /// A new, empty world of this game's lane with the game's own tuning.
  virtual std::unique_ptr<Lane> make_lane() const = 0;
  /// Whether `lane` is of the type make_lane() makes (the only lanes the
  /// game's calls may be handed).
  virtual bool accepts_lane(const Lane& lane) const = 0;
  /// The game's world tuning as the game states it, in its lane's portable
  /// encoding (World3D::encode_config() for the 3D lane): what replay
  /// headers record and compare. `out` is replaced.
  virtual void encode_world_config(std::vector<uint8_t>& out) const = 0;
  /// Bytes encode_world_config() wrote (by this or another build) as
  /// readable (name, value) pairs in encoding order, for replay tools;
  /// kCorrupt when the lane cannot decode them.
  virtual Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
      std::span<const uint8_t> bytes) const = 0;
  /// Size in bytes of the game's state block (trivially copyable data).
  virtual size_t state_size() const = 0;
  /// What the game's input is: its size, its fields and their allowed
  /// ranges, and how a missing input is predicted. The server refuses an
  /// input outside it before the rules see it, so apply_inputs() only gets
  /// inputs the spec allows (or the neutral, all-zero input). The default
  /// is StickInput (two axes and 32 buttons). The spec must not change
  /// while the game is in use.
  virtual const InputSpec& input_spec() const { return stick_input_spec(); }
  // The three rules hooks return a Status so that no error is dropped: a
  // call the world refuses (a body the scene cannot create, a handle that
  // should exist but does not) is returned, and the match that runs the
  // game ends with its message (Simulation::step, the server, the client
  // SDK and the replay verifier all pass it on). An error is a bug in the
  // rules or a state no rule expects, never a way to reject a player's
  // input: inputs are clamped, not refused.

  /// Builds the scene into `lane` (made by make_lane(), or a lane of the
  /// same type) and initializes the zeroed state block.
  virtual Status build(const MatchSetup& setup, Lane& lane, std::span<std::byte> state) const = 0;
  /// Applies one tick of inputs (one per player, index = player slot)
  /// before the world steps. Each is the player's input as input_spec()
  /// describes it (PlayerInput::as<T>() reads the game's struct).
  virtual Status apply_inputs(Tick tick, std::span<const PlayerInput> inputs, Lane& lane,
                              std::span<std::byte> state) const = 0;
  /// Runs after the world stepped (scoring, respawns); may read events.
  virtual Status after_step(Tick tick, Lane& lane, std::span<std::byte> state) const = 0;
  /// Feeds the canonical fields of the state block to the hasher.
  virtual void hash_state(std::span<const std::byte> state, rwd::StateHasher& hasher) const = 0;
  /// Checks a state block that arrived from outside (a resync snapshot, a
  /// desync dump) before it is used: counts, indices and ranges the rules
  /// rely on. Returns kCorrupt naming the bad field.
  virtual Status validate_state(const MatchSetup& setup,
                                std::span<const std::byte> state) const = 0;
  /// The input a bot in seat `player` sends on `tick`: what rewind-bots
  /// plays by default (--script game) and load tests drive. It must be a
  /// pure function of its arguments, so a run repeats with the same seed.
  virtual PlayerInput bot_input(uint64_t seed, uint32_t player, Tick tick) const {
    return random_bot_input(input_spec(), seed, player, tick);
  }
};

}  // namespace rwd::game
