// SPDX-License-Identifier: MIT
#pragma once
// A match's deterministic simulation: world + game state + tick. This is the
// unit that rollback saves, restores, steps and checksums. It reaches the
// world only through the Lane interface, so it hosts any lane.
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"
#include "rewind/game/lane.h"
#include "rewind/sim/world_config.h"

namespace rwd::game {

/// Everything a Simulation is, copied by value. The world part is opaque:
/// only the lane that saved it reads it. Reusing one snapshot object reuses
/// its buffers, so steady-state save() does not allocate; copying one
/// allocates.
struct SimSnapshot {
  std::unique_ptr<LaneSnapshot> world;  ///< made by the first save() into it
  std::vector<std::byte> game_state;
  Tick tick = 0;

  SimSnapshot() = default;
  SimSnapshot(const SimSnapshot& other);
  SimSnapshot& operator=(const SimSnapshot& other);
  SimSnapshot(SimSnapshot&&) noexcept = default;
  SimSnapshot& operator=(SimSnapshot&&) noexcept = default;
  ~SimSnapshot() = default;
};

class Simulation {
 public:
  /// Creates the named game's match. Unknown names and invalid setups are
  /// kInvalidArgument.
  static Result<std::unique_ptr<Simulation>> create(std::string_view game_name,
                                                    const MatchSetup& setup);
  /// Creates the named 3D-lane game's match on a world built from
  /// `world_config` instead of the game's own world_config(), for tools
  /// that measure how a game plays at other solver settings (rewind-tune).
  /// Start from the game's world_config() and change only solver fields
  /// (substeps, relax_iterations, contact_hertz...): tick length, gravity
  /// and bounds are part of the game's design. Such a match agrees (checksums,
  /// replays) only with matches made with the same config; servers and
  /// clients use the overload above. A config World3D::validate_config()
  /// refuses is kInvalidArgument, as are unknown names, games on another
  /// lane and invalid setups.
  static Result<std::unique_ptr<Simulation>> create(std::string_view game_name,
                                                    const MatchSetup& setup,
                                                    const sim::WorldConfig& world_config);
  /// `game` (registered or not) on `lane`, a lane of the type
  /// game->make_lane() makes (e.g. one built from another config), or on a
  /// lane of its own when null. kInvalidArgument for a null game, an
  /// invalid setup or a lane of another type; the game's own error when
  /// its build() fails.
  static Result<std::unique_ptr<Simulation>> create(std::unique_ptr<Game> game,
                                                    const MatchSetup& setup,
                                                    std::unique_ptr<Lane> lane = nullptr);

  /// The next tick step() will simulate.
  Tick tick() const { return tick_; }
  const MatchSetup& setup() const { return setup_; }
  const Game& game() const { return *game_; }
  /// The world, lane-neutral; world_of<World>() (world_lane.h) reaches the
  /// concrete world when the caller knows the lane.
  Lane& lane() { return *lane_; }
  const Lane& lane() const { return *lane_; }
  std::span<const std::byte> game_state() const { return game_state_; }

  /// Simulates tick(): applies `inputs` (exactly player_count, index = player
  /// slot), steps the world, runs the game's after-step rules, then tick()+1.
  /// When the game's rules fail, their error (naming the game and the tick)
  /// is returned and tick() stays: the state is then whatever the rules
  /// left, so restore a snapshot or drop the simulation. An input the
  /// game's InputSpec refuses is kInvalidArgument naming the player, before
  /// anything changes.
  Status step(std::span<const PlayerInput> inputs);

  /// Copies the state into `out`, reusing its buffers.
  void save(SimSnapshot& out) const;
  /// Copies back a snapshot that save() of a simulation of the same game
  /// wrote.
  void restore(const SimSnapshot& in);

  /// XXH3-64 over tick, world and game state (canonical fields).
  uint64_t checksum() const;
  /// checksum() of a saved snapshot of this match, without restoring it.
  uint64_t checksum_of(const SimSnapshot& snapshot) const;
  /// Lane-neutral body dump (every live body's fields in index order), for
  /// desync reports and replay diffs; `out` is cleared first.
  void dump_bodies(std::vector<rwd::BodyField>& out) const { lane_->dump_fields(out); }

  /// Portable encoding of the whole simulation (resync snapshots).
  void serialize(std::vector<uint8_t>& out) const;
  /// Replaces the state from serialize()'s bytes; kCorrupt leaves it intact.
  Status deserialize(std::span<const uint8_t> bytes);

 private:
  std::unique_ptr<Game> game_;
  MatchSetup setup_;
  std::unique_ptr<Lane> lane_;
  std::vector<std::byte> game_state_;
  Tick tick_ = 0;

  Simulation(std::unique_ptr<Game> game, const MatchSetup& setup, std::unique_ptr<Lane> lane);
};

/// Names of the built-in games, for --help texts.
std::vector<std::string_view> builtin_game_names();
/// Creates a built-in game by name, or nullptr.
std::unique_ptr<Game> make_builtin_game(std::string_view name);

}  // namespace rwd::game
