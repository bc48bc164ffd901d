// SPDX-License-Identifier: MIT
#pragma once
// "arena": the 2D sample game, top-down on the fixed-point lane. Each
// player steers a disc that shoves crates (and other players) around a
// walled arena; a crate pushed into either goal scores for the player who
// touched it last and comes back at the centre. A spinning bar sweeps the
// middle, two posts split the field, a turnstile and a spring-loaded gate
// turn on their hinges. The whole step is integer math.
#include <array>
#include <cstdint>

#include "rewind/game/game_on.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::game {

/// Button bits of StickInput::buttons in arena.
inline constexpr uint32_t kArenaDash = 1u << 0;

inline constexpr uint32_t kArenaMaxCrates = 16;

struct ArenaState {
  uint32_t player_count = 0;
  uint32_t crate_count = 0;
  std::array<sim2d::BodyId2D, kMaxPlayers> discs{};
  std::array<uint32_t, kMaxPlayers> score{};
  std::array<int32_t, kMaxPlayers> dash_cooldown{};  ///< ticks until the next dash
  std::array<sim2d::BodyId2D, kArenaMaxCrates> crates{};
  std::array<uint8_t, kArenaMaxCrates> crate_last_toucher{};  ///< player + 1, 0 = nobody
  std::array<sim2d::BodyId2D, 2> goals{};
  sim2d::BodyId2D spinner{};
  uint32_t goals_scored = 0;
};

class ArenaGame final : public GameWithState<sim2d::World2D, ArenaState> {
 public:
  std::string_view name() const override { return "arena"; }
  uint32_t rules_version() const override { return 1; }
  sim2d::World2DConfig world_config() const override;

 protected:
  Status build_typed(const MatchSetup& setup, sim2d::World2D& world,
                     ArenaState& state) const override;
  Status apply_typed(Tick tick, std::span<const StickInput> inputs, sim2d::World2D& world,
                     ArenaState& state) const override;
  Status after_step_typed(Tick tick, sim2d::World2D& world, ArenaState& state) const override;
  void hash_typed(const ArenaState& state, rwd::StateHasher& hasher) const override;
  Status validate_typed(const MatchSetup& setup, const ArenaState& state) const override;
};

}  // namespace rwd::game
