// SPDX-License-Identifier: MIT
#pragma once
// A built-in game as a tuning target. A game has no analytic answer, so its
// error is its distance from a reference: the same match (same seed, same
// scripted inputs) played at a very fine setting.
//
// Chaos decides how that distance may be measured. Two runs of a game with
// contacts that differ at all drift apart exponentially (a crate tips the
// other way, a pusher is grounded one tick later and its jump is refused),
// so the distance over a whole match measures chaos, not the setting: every
// setting, however fine, sooner or later has some body far from where the
// reference has it. The error
// is therefore measured over short windows: the match is cut into windows
// of `window_ticks` (a quarter second by default, about one push or
// landing); each starts the candidate from the reference's own state at its
// first tick and plays that window's inputs. What the candidate gets wrong
// within a window is the error the setting adds, and the windows sample
// every situation of the match (the tower standing, falling, crates shoved
// into walls) alike at every setting. Longer windows let chaos back in and
// flatten the differences between settings.
//
// For information it also reports how long a match played from the start,
// never corrected, stays within `diverge_m` of the reference.
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/game/simulation.h"
#include "rewind/tools/bot_script.h"
#include "rewind/tune/tune_target.h"

namespace rwd::tune {

/// How the match is played.
struct GamePlay {
  std::string game = "crates";
  uint32_t players = 4;  ///< [1, game::kMaxPlayers]
  uint64_t seed = 1;     ///< the match's seed and the input scripts' seed
  tools::BotScript script = tools::BotScript::kRandom;  ///< every player's inputs
  Tick ticks = 1800;                                    ///< match length, [1, 36000]; 30 s at 60 Hz
  Tick window_ticks = 15;           ///< length of each error window, [1, ticks]; 0.25 s at 60 Hz
  int32_t reference_substeps = 32;  ///< the reference's substeps, [1, 64]
  int32_t reference_relax_iterations = 4;  ///< the reference's relax passes, [0, 16]
  double diverge_m = 0.1;  ///< distance that ends the free run's "same match", m, > 0
};

class GameTarget final : public TuneTarget {
 public:
  /// Plays the reference match once (progress on `progress` if non-null).
  /// kInvalidArgument for an unknown game or out-of-range play.
  static Result<std::unique_ptr<GameTarget>> create(const GamePlay& play, std::ostream* progress);

  std::string kind() const override { return "game"; }
  std::string name() const override { return play_.game; }
  int size() const override { return static_cast<int>(play_.players); }
  std::string description() const override;
  SolverSetting default_setting() const override { return SolverSetting::of(config_); }
  Tick ticks() const override { return play_.ticks; }
  /// Metrics: position_error_m (the budget by default: 95th percentile over
  /// windows of the largest body-centre error within a window, m),
  /// position_error_mean_m, velocity_error_mps and diverged_s (reported,
  /// no limit unless --budget sets one). ms_per_step is the whole game tick
  /// (rules and world step) over the windows.
  Measurement measure(const SolverSetting& setting) override;

  /// The reference setting.
  SolverSetting reference_setting() const;

 private:
  GameTarget(const GamePlay& play, const game::Game& game, const sim::WorldConfig& config);
  Status play_reference(std::ostream* progress);
  /// Largest distance of any tracked body from the reference after `tick`:
  /// positions (m) and velocities (m/s).
  void compare(const game::Simulation& sim, Tick tick, double& position_m, double& velocity_mps,
               double* position_sum_m) const;

  GamePlay play_;
  sim::WorldConfig config_;                            // the game's own world config
  std::vector<std::vector<rwd::PlayerInput>> inputs_;  // [tick][player]
  std::vector<sim::BodyId> bodies_;                    // dynamic bodies, index order
  std::vector<game::SimSnapshot> window_starts_;       // reference state at each window start
  std::vector<sim::Vec3> reference_position_;          // [tick * bodies + body], after the tick
  std::vector<sim::Vec3> reference_velocity_;
};

}  // namespace rwd::tune
